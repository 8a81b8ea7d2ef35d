#include "common/trace/trace_merge.hpp"

#include "common/trace/trace_writer.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace mcnc::trace {
namespace {

namespace fs = std::filesystem;

// A scratch folder unique to this process and test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("mcnc_merge_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

std::string write_part(const TempDir& dir, const std::string& name,
                       const std::vector<std::string>& lines) {
  const std::string path = dir.file(name);
  std::ofstream out(path);
  for (const auto& line : lines) {
    out << line << '\n';
  }
  return path;
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

std::string ev(std::uint64_t cycle, const std::string& src, const std::string& tag) {
  return "{\"cycle\":" + std::to_string(cycle) + ",\"src\":\"" + src + "\",\"ev\":\"" + tag + "\"}";
}

TEST(MergeParts, OrdersByCycleThenPartThenLine) {
  TempDir dir;
  const auto a = write_part(
      dir, "a.jsonl", {ev(1, "a", "a1"), ev(3, "a", "a3x"), ev(3, "a", "a3y"), ev(5, "a", "a5")});
  const auto b = write_part(dir, "b.jsonl", {ev(0, "b", "b0"), ev(3, "b", "b3"), ev(4, "b", "b4")});
  const auto c = write_part(dir, "c.jsonl", {ev(2, "c", "c2"), ev(3, "c", "c3")});
  const std::string out = dir.file("trace.jsonl");
  std::size_t written = 0;
  const std::uint64_t last = merge_parts({a, b, c}, out, &written);
  EXPECT_EQ(last, 5u);
  EXPECT_EQ(written, 9u);
  EXPECT_EQ(read_lines(out),
            (std::vector<std::string>{ev(0, "b", "b0"), ev(1, "a", "a1"), ev(2, "c", "c2"),
                                      ev(3, "a", "a3x"), ev(3, "a", "a3y"), ev(3, "b", "b3"),
                                      ev(3, "c", "c3"), ev(4, "b", "b4"), ev(5, "a", "a5")}));
}

TEST(MergeParts, PartOrderAsGivenNotByName) {
  TempDir dir;
  const auto a = write_part(dir, "a.jsonl", {ev(7, "a", "first-a"), ev(7, "a", "second-a")});
  const auto z = write_part(dir, "z.jsonl", {ev(7, "z", "first-z"), ev(7, "z", "second-z")});
  const std::string out = dir.file("trace.jsonl");
  EXPECT_EQ(merge_parts({z, a}, out), 7u);
  EXPECT_EQ(read_lines(out),
            (std::vector<std::string>{ev(7, "z", "first-z"), ev(7, "z", "second-z"),
                                      ev(7, "a", "first-a"), ev(7, "a", "second-a")}));
}

TEST(MergeParts, LineOrderWithinAPartKeptEvenWhenCyclesInterleave) {
  TempDir dir;
  // A part whose cycles are not sorted (events of one cycle written late stay after earlier ones).
  const auto a = write_part(dir, "a.jsonl",
                            {ev(2, "a", "x"), ev(1, "a", "y"), ev(2, "a", "z"), ev(1, "a", "w")});
  const std::string out = dir.file("trace.jsonl");
  EXPECT_EQ(merge_parts({a}, out), 2u);
  EXPECT_EQ(read_lines(out), (std::vector<std::string>{ev(1, "a", "y"), ev(1, "a", "w"),
                                                       ev(2, "a", "x"), ev(2, "a", "z")}));
}

TEST(MergeParts, CyclesCompareAsNumbers) {
  TempDir dir;
  const std::uint64_t big = 5000000000ull;  // above 32 bits
  const auto a = write_part(dir, "a.jsonl", {ev(10, "a", "ten"), ev(big, "a", "big")});
  const auto b = write_part(dir, "b.jsonl", {ev(9, "b", "nine"), ev(100, "b", "hundred")});
  const std::string out = dir.file("trace.jsonl");
  EXPECT_EQ(merge_parts({a, b}, out), big);
  EXPECT_EQ(read_lines(out),
            (std::vector<std::string>{ev(9, "b", "nine"), ev(10, "a", "ten"),
                                      ev(100, "b", "hundred"), ev(big, "a", "big")}));
}

TEST(MergeParts, SkipsLinesThatAreNotEvents) {
  TempDir dir;
  const auto a = write_part(dir, "a.jsonl",
                            {"# trace part of a", "", ev(4, "a", "kept"), " " + ev(1, "a", "space"),
                             "{\"src\":\"a\",\"cycle\":2}", "{\"cyc\":3}", "[1,2,3]",
                             "{\"Cycle\":0}", ev(6, "a", "kept2")});
  const std::string out = dir.file("trace.jsonl");
  std::size_t written = 99;
  EXPECT_EQ(merge_parts({a}, out, &written), 6u);
  EXPECT_EQ(written, 2u);
  EXPECT_EQ(read_lines(out), (std::vector<std::string>{ev(4, "a", "kept"), ev(6, "a", "kept2")}));
}

TEST(MergeParts, NoEventsGivesCycleZeroAndAnEmptyFile) {
  TempDir dir;
  const auto a = write_part(dir, "a.jsonl", {"not an event"});
  const std::string out = dir.file("trace.jsonl");
  {
    std::ofstream stale(out);
    stale << ev(99, "old", "stale") << '\n';
  }
  std::size_t written = 99;
  EXPECT_EQ(merge_parts({a}, out, &written), 0u);
  EXPECT_EQ(written, 0u);
  EXPECT_TRUE(fs::exists(out));
  EXPECT_EQ(fs::file_size(out), 0u);  // truncated, not appended
  EXPECT_EQ(merge_parts({}, out), 0u);
}

TEST(MergeParts, UnwritableOutputThrows) {
  TempDir dir;
  const auto a = write_part(dir, "a.jsonl", {ev(1, "a", "x")});
  EXPECT_THROW(merge_parts({a}, dir.file("missing-dir/trace.jsonl")), std::runtime_error);
}

TEST(MergeParts, MergesWhatTraceWritersWrote) {
  TempDir dir;
  const std::string pa = dir.file("channel.part");
  const std::string pb = dir.file("axis.part");
  {
    TraceWriter a(pa, "channel");
    TraceWriter b(pb, "axis1");
    for (std::uint64_t c = 1; c <= 50; ++c) {
      b.emit(c, "fb", "\"pos\":%.3f", static_cast<double>(c) * 0.5);
      a.emit(c, "sp", "\"pos\":%.3f", static_cast<double>(c) * 0.5);
      if (c % 10 == 0) {
        a.emit(c, "block", "\"line\":%d", static_cast<int>(c / 10));
      }
    }
  }
  const std::string out = dir.file("trace.jsonl");
  std::size_t written = 0;
  EXPECT_EQ(merge_parts({pa, pb}, out, &written), 50u);
  EXPECT_EQ(written, 105u);
  const auto lines = read_lines(out);
  ASSERT_EQ(lines.size(), 105u);
  std::size_t i = 0;
  for (std::uint64_t c = 1; c <= 50; ++c) {
    const std::string prefix = "{\"cycle\":" + std::to_string(c) + ",";
    EXPECT_EQ(lines[i++].rfind(prefix + "\"src\":\"channel\",\"ev\":\"sp\"", 0), 0u) << c;
    if (c % 10 == 0) {
      EXPECT_EQ(lines[i++].rfind(prefix + "\"src\":\"channel\",\"ev\":\"block\"", 0), 0u) << c;
    }
    EXPECT_EQ(lines[i++].rfind(prefix + "\"src\":\"axis1\",\"ev\":\"fb\"", 0), 0u) << c;
  }
}

}  // namespace
}  // namespace mcnc::trace
