#include "common/trace/trace_writer.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace mcnc::trace {
namespace {

namespace fs = std::filesystem;

// A file name unique to this process and test, removed at the end of the test.
class TempFile {
 public:
  explicit TempFile(const std::string& tag) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("mcnc_trace_" + std::to_string(::getpid()) + "_" + info->name() + "_" + tag);
    fs::remove(path_);
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  [[nodiscard]] std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string escape(const std::string& in, std::size_t out_size) {
  std::vector<char> out(out_size, '#');
  json_escape(in.c_str(), out.data(), out.size());
  // Terminated inside the buffer.
  bool terminated = false;
  for (char c : out) {
    terminated = terminated || c == '\0';
  }
  EXPECT_TRUE(terminated) << "size " << out_size;
  return terminated ? std::string(out.data()) : std::string();
}

// The text back from a JSON string body, or throws when it is not a valid one.
std::string unescape(const std::string& body) {
  return nlohmann::json::parse("\"" + body + "\"").get<std::string>();
}

TEST(JsonEscape, QuotesAndBackslash) {
  EXPECT_EQ(escape("a\"b\\c", 64), "a\\\"b\\\\c");
  EXPECT_EQ(escape("\"\"", 64), "\\\"\\\"");
  EXPECT_EQ(escape("C:\\nc\\O1.nc", 64), "C:\\\\nc\\\\O1.nc");
  EXPECT_EQ(unescape(escape("say \"hi\" \\o/", 64)), "say \"hi\" \\o/");
}

TEST(JsonEscape, ControlCharacters) {
  EXPECT_EQ(escape("a\nb\rc\td", 64), "a\\nb\\rc\\td");
  EXPECT_EQ(escape("\x01", 64), "\\u0001");
  EXPECT_EQ(escape("x\x1fy", 64), "x\\u001fy");
  EXPECT_EQ(escape("\b\f", 64), "\\u0008\\u000c");
  // Every control character round-trips through a JSON parser.
  std::string all;
  for (int c = 1; c < 0x20; ++c) {
    all.push_back(static_cast<char>(c));
  }
  const std::string escaped = escape(all, 512);
  for (char c : escaped) {
    EXPECT_GE(static_cast<unsigned char>(c), 0x20u);
  }
  EXPECT_EQ(unescape(escaped), all);
}

TEST(JsonEscape, PlainTextAndEmpty) {
  EXPECT_EQ(escape("", 1), "");
  EXPECT_EQ(escape("", 16), "");
  EXPECT_EQ(escape("G01 X10.5 Z-3", 64), "G01 X10.5 Z-3");
  // Bytes above 0x7f (UTF-8) pass unchanged.
  EXPECT_EQ(escape("\xc2\xb0", 16), "\xc2\xb0");
}

TEST(JsonEscape, TruncationIsTerminatedAndNeverCutsAnEscape) {
  const std::string input =
      "ab\"c\\d\ne\x01"
      "fgh\"\"\\\\\t\x02xyz";
  const std::string full = escape(input, 1024);
  ASSERT_EQ(unescape(full), input);
  for (std::size_t size = 1; size <= full.size() + 8; ++size) {
    SCOPED_TRACE(size);
    const std::string cut = escape(input, size);
    EXPECT_LT(cut.size(), size);
    EXPECT_EQ(full.compare(0, cut.size(), cut), 0) << cut;  // a prefix of the whole escape
    EXPECT_NO_THROW(unescape(cut)) << cut;                  // and still a valid JSON string
  }
  // A long input in a small buffer never writes past it.
  std::vector<char> buf(32 + 16, 'Z');
  json_escape(std::string(1000, '"').c_str(), buf.data(), 32);
  for (std::size_t i = 32; i < buf.size(); ++i) {
    EXPECT_EQ(buf[i], 'Z') << i;
  }
}

TEST(JsonEscape, TextThatFitsIsNotCut) {
  // "cut if too long": a string whose escape fits the buffer comes out whole.
  EXPECT_EQ(escape("abc", 4), "abc");
  EXPECT_EQ(escape("abc", 8), "abc");
  EXPECT_EQ(escape("0123456789", 11), "0123456789");
  EXPECT_EQ(escape("a\"b", 5), "a\\\"b");
}

TEST(TraceWriter, WritesExactlyTheEmittedEventsInOrder) {
  TempFile file("part");
  TraceWriter writer(file.str(), "ch1");
  ASSERT_TRUE(writer.enabled());
  constexpr int kEvents = 3000;
  for (int i = 0; i < kEvents; ++i) {
    writer.emit(static_cast<std::uint64_t>(i / 3), i % 2 == 0 ? "block" : "state",
                "\"n\":%d,\"ch\":\"%s\"", i, "main");
  }
  writer.flush();
  // Visible while the writer still exists.
  const auto lines = read_lines(file.str());
  ASSERT_EQ(lines.size(), static_cast<std::size_t>(kEvents));
  EXPECT_EQ(writer.dropped(), 0u);
  for (int i = 0; i < kEvents; ++i) {
    SCOPED_TRACE(i);
    const std::string& line = lines[static_cast<std::size_t>(i)];
    const std::string head = "{\"cycle\":" + std::to_string(i / 3) + ",\"src\":\"ch1\",\"ev\":\"" +
                             (i % 2 == 0 ? "block" : "state") + "\",";
    ASSERT_EQ(line.compare(0, head.size(), head), 0) << line;
    const auto j = nlohmann::ordered_json::parse(line);
    ASSERT_TRUE(j.is_object());
    ASSERT_EQ(j.size(), 5u);
    auto it = j.begin();
    EXPECT_EQ(it.key(), "cycle");
    EXPECT_EQ(it.value().get<std::uint64_t>(), static_cast<std::uint64_t>(i / 3));
    ++it;
    EXPECT_EQ(it.key(), "src");
    EXPECT_EQ(it.value(), "ch1");
    ++it;
    EXPECT_EQ(it.key(), "ev");
    ++it;
    EXPECT_EQ(it.key(), "n");
    EXPECT_EQ(it.value().get<int>(), i);
    EXPECT_EQ(j["ch"], "main");
  }
}

TEST(TraceWriter, EventWithoutFields) {
  TempFile file("part");
  {
    TraceWriter writer(file.str(), "axis2");
    writer.emit(42, "tick", nullptr);
    writer.flush();
    EXPECT_EQ(read_all(file.str()).back(), '\n');
  }
  const auto lines = read_lines(file.str());
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "{\"cycle\":42,\"src\":\"axis2\",\"ev\":\"tick\"}");
}

TEST(TraceWriter, FieldsThatFormatToNothingStillGiveValidJson) {
  // One JSON object per line, whatever the fields expand to.
  TempFile file("part");
  TraceWriter writer(file.str(), "p");
  writer.emit(5, "note", "%s", "");
  writer.flush();
  const auto lines = read_lines(file.str());
  ASSERT_EQ(lines.size() + writer.dropped(), 1u);
  for (const auto& line : lines) {
    EXPECT_TRUE(nlohmann::json::accept(line)) << line;
  }
}

TEST(TraceWriter, FlushMakesEventsVisibleEachTime) {
  TempFile file("part");
  TraceWriter writer(file.str(), "p");
  for (int round = 1; round <= 20; ++round) {
    writer.emit(static_cast<std::uint64_t>(round), "r", "\"round\":%d", round);
    writer.flush();
    const auto lines = read_lines(file.str());
    ASSERT_EQ(lines.size(), static_cast<std::size_t>(round));
    EXPECT_EQ(nlohmann::json::parse(lines.back())["round"], round);
  }
}

TEST(TraceWriter, DestructionWritesWhatIsPending) {
  TempFile file("part");
  {
    TraceWriter writer(file.str(), "p");
    for (int i = 0; i < 500; ++i) {
      writer.emit(static_cast<std::uint64_t>(i), "e", "\"i\":%d", i);
    }
  }
  const auto lines = read_lines(file.str());
  ASSERT_EQ(lines.size(), 500u);
  for (int i = 0; i < 500; ++i) {
    EXPECT_EQ(nlohmann::json::parse(lines[static_cast<std::size_t>(i)])["i"], i);
  }
}

TEST(TraceWriter, DisabledWriterWritesNothing) {
  TraceWriter writer("", "p");
  EXPECT_FALSE(writer.enabled());
  for (int i = 0; i < 100; ++i) {
    writer.emit(static_cast<std::uint64_t>(i), "e", "\"i\":%d", i);
  }
  writer.flush();
  EXPECT_EQ(writer.dropped(), 0u);
}

TEST(TraceWriter, UnwritablePathThrows) {
  EXPECT_THROW(TraceWriter("/nonexistent-mcnc-dir/sub/trace.jsonl", "p"), std::runtime_error);
}

TEST(TraceWriter, TooLongEventIsDroppedWholeAndCounted) {
  TempFile file("part");
  TraceWriter writer(file.str(), "p");
  writer.emit(1, "before", "\"k\":%d", 1);
  const std::string huge(2000, 'x');
  writer.emit(2, "huge", "\"text\":\"%s\"", huge.c_str());
  writer.emit(3, "after", "\"k\":%d", 3);
  writer.flush();
  EXPECT_EQ(writer.dropped(), 1u);
  const auto lines = read_lines(file.str());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(lines[0])["ev"], "before");
  EXPECT_EQ(nlohmann::json::parse(lines[1])["ev"], "after");
  EXPECT_EQ(read_all(file.str()).find("huge"), std::string::npos);
}

// The longest line a slot holds: 768 bytes with '}', '\n' and the terminator.
constexpr std::size_t kLongestLine = 766;

TEST(TraceWriter, EventsUpToTheSlotSizeAreWrittenLongerOnesDropped) {
  TempFile file("part");
  TraceWriter writer(file.str(), "p");
  const std::string head = "{\"cycle\":7,\"src\":\"p\",\"ev\":\"fit\",\"pad\":\"";
  for (std::size_t total = kLongestLine - 3; total <= kLongestLine + 3; ++total) {
    // total = head + pad + "\"}"
    const std::string pad(total - head.size() - 2, 'a');
    writer.emit(7, "fit", "\"pad\":\"%s\"", pad.c_str());
  }
  writer.flush();
  const auto lines = read_lines(file.str());
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(writer.dropped(), 3u);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].size(), kLongestLine - 3 + i);
    EXPECT_TRUE(nlohmann::json::accept(lines[i])) << lines[i];
  }
}

TEST(TraceWriter, LongHeaderWithFieldsIsNeverWrittenWithoutItsFields) {
  // Vary the event name so that the fixed part of the line falls on every length around the
  // slot size: each event is either written whole (with its field) or dropped and counted.
  TempFile file("part");
  TraceWriter writer(file.str(), "p");
  const std::string base = "{\"cycle\":1,\"src\":\"p\",\"ev\":\"\"";
  int emitted = 0;
  for (std::size_t header = kLongestLine - 8; header <= kLongestLine + 2; ++header) {
    const std::string ev(header - base.size(), 'e');
    writer.emit(1, ev.c_str(), "\"k\":%d", 7);
    ++emitted;
  }
  writer.flush();
  const auto lines = read_lines(file.str());
  EXPECT_EQ(lines.size() + writer.dropped(), static_cast<std::size_t>(emitted));
  for (const auto& line : lines) {
    EXPECT_NE(line.find("\"k\":7"), std::string::npos) << "written without its field: " << line;
    EXPECT_TRUE(nlohmann::json::accept(line)) << line;
  }
}

TEST(TraceWriter, ConcurrentProducersKeepTheirOwnOrder) {
  TempFile file("part");
  constexpr int kThreads = 4;
  constexpr int kPerThread = 1500;
  std::uint64_t dropped = 0;
  {
    TraceWriter writer(file.str(), "p");
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&writer, t] {
        for (int i = 0; i < kPerThread; ++i) {
          writer.emit(static_cast<std::uint64_t>(i), "e", "\"t\":%d,\"i\":%d", t, i);
        }
      });
    }
    for (auto& th : threads) {
      th.join();
    }
    writer.flush();
    dropped = writer.dropped();
  }
  const auto lines = read_lines(file.str());
  EXPECT_EQ(lines.size() + dropped, static_cast<std::size_t>(kThreads * kPerThread));
  std::vector<int> last(kThreads, -1);
  for (const auto& line : lines) {
    const auto j = nlohmann::json::parse(line);
    const int t = j["t"].get<int>();
    const int i = j["i"].get<int>();
    ASSERT_GE(t, 0);
    ASSERT_LT(t, kThreads);
    EXPECT_GT(i, last[static_cast<std::size_t>(t)]);
    last[static_cast<std::size_t>(t)] = i;
  }
}

}  // namespace
}  // namespace mcnc::trace
