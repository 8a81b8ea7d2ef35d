// Programs stream (issue 23): a program is read from its file line by line, checked whole before
// it runs, and held only as a window of chunks (parse::ParsedProgram). These programs are longer
// than the window, so jumps, loops and the block structure reach lines that had left it.
#include "channel/interp/interpreter_source.hpp"
#include "channel/interp/parse/parsed_program.hpp"
#include "channel/interp/program/program_format_alarms.hpp"
#include "interp_test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace mcnc::interp::test {
namespace {

namespace fs = std::filesystem;

// More lines than the window holds.
constexpr int kLong =
    3 * static_cast<int>(parse::ParsedProgram::kWindowChunks) * parse::ParsedProgram::kChunkLines;

class ProgramStream : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir_ = fs::temp_directory_path() / ("mcnc_stream_" + std::to_string(rd()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  static RunResult run_file(const std::string& path, std::size_t limit = 1000000) {
    Interpreter in(lathe());
    if (auto a = in.start_file(path, "long.nc")) {
      RunResult r;
      r.alarm = *a;
      return r;
    }
    return drain(in, limit);
  }

  fs::path dir_;
};

// Line k (1-based) of the filler is `G01 X<k mod 97 + 1>`: every line moves X somewhere else.
// X is a diameter: the command's position is its radius.
std::string filler(int first_line, int lines) {
  std::ostringstream out;
  for (int k = first_line; k < first_line + lines; ++k) {
    out << "G01 X" << (k % 97) + 1 << " F100\n";
  }
  return out.str();
}

TEST_F(ProgramStream, AGotoBackOverTheWholeWindowRunsTheLoopAsOften) {
  // Line 1 O0001, 2 #1=0, 3 N1 (the loop's start), 4.. filler, then the count and the jump.
  std::string text =
      "O0001\n#1=0\nN1 #1=#1+1\n" + filler(4, kLong) + "IF [#1 LT 3] GOTO 1\nG00 X500\nM30\n";
  const RunResult r = run_file(write("long.nc", text));
  ASSERT_FALSE(r.alarm) << r.alarm->text;
  ASSERT_TRUE(r.ended);
  // A line near the start, one in the middle and the last filler line: three times each, at
  // their X (diameter), in order.
  for (const int line : {4, 4 + kLong / 2, 3 + kLong}) {
    const std::vector<Command> at = r.at_line(line);
    ASSERT_EQ(at.size(), 3U) << "line " << line;
    for (const Command& c : at) {
      EXPECT_NEAR(2 * c.to[0], (line % 97) + 1, 1e-9) << "line " << line;
    }
  }
  EXPECT_EQ(r.of(Op::linear).size(), 3U * kLong);
  EXPECT_NEAR(2 * r.commands[r.commands.size() - 2].to[0], 500.0, 1e-9);
}

TEST_F(ProgramStream, TheBlockStructureSpansChunksThatLeftTheWindow) {
  // A WHILE from line 3 to the end, an IF/ELSE whose branches are a window apart, and a BREAK
  // on the third pass: each branch line is reached after the window moved on.
  const int half = kLong / 2;
  std::string text = "O0002\n#1=0\nWHILE [#1 LT 10] DO1\n#1=#1+1\nIF [#1 EQ 2]\n" +
                     filler(6, half) + "ELSE\n#2=#1\n" + filler(8 + half, half) +
                     "ENDIF\nIF [#1 GE 3] BREAK\nEND1\nG00 X[#1*100+#2]\nM30\n";
  const RunResult r = run_file(write("structure.nc", text));
  ASSERT_FALSE(r.alarm) << r.alarm->text;
  // Pass 1 and 3 take ELSE (#2 = 3 at the end), pass 2 the IF branch; the BREAK leaves at 3.
  EXPECT_EQ(r.at_line(6).size(), 1U);
  EXPECT_EQ(r.at_line(8 + half).size(), 2U);
  EXPECT_NEAR(2 * r.commands[r.commands.size() - 2].to[0], 303.0, 1e-9);
}

TEST_F(ProgramStream, ASyntaxErrorOnTheLastLineIsAnAlarmBeforeAnyCommand) {
  const std::string path = write("bad.nc", "O0003\n" + filler(2, kLong) + "G01 X1 ]\nM30\n");
  Interpreter in(lathe());
  const std::optional<ProgramAlarm> alarm = in.start_file(path, "bad.nc");
  ASSERT_TRUE(alarm);
  EXPECT_EQ(alarm->line, kLong + 2);
  EXPECT_EQ(alarm->program, "bad.nc");
  EXPECT_FALSE(in.next().has_value());
}

TEST_F(ProgramStream, AFileWrittenWhileItsProgramRunsStopsItWithAlarm1036) {
  const std::string text = "O0004\n" + filler(2, kLong) + "M30\n";
  const std::string path = write("edited.nc", text);
  Interpreter in(lathe());
  ASSERT_FALSE(in.start_file(path, "edited.nc"));
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(in.next().has_value());
  }
  // The same length, another move on a line the run has not reached and the window never held.
  std::string edited = text;
  const std::size_t at = edited.rfind("G01 X");
  edited.replace(at, 5, "G00 X");
  write("edited.nc", edited);
  const RunResult r = drain(in);
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, program::alarm::kFileChanged);
  EXPECT_EQ(r.alarm->program, "edited.nc");
  EXPECT_FALSE(r.commands.empty());
  for (const Command& c : r.commands) {
    EXPECT_EQ(c.op, Op::linear) << "line " << c.line << ": the edited rapid never runs";
  }
}

TEST_F(ProgramStream, ABlockTextOutlivesItsChunkForTheCommandsKept) {
  // Line 2 moves; then a window and more of comment lines, then moves: by the time those are
  // pulled, line 2's chunk has left the window and its memory holds other lines.
  std::string text = "O0005\nN1 G01 X1 F100 (the first block)\n";
  for (int k = 0; k < kLong; ++k) {
    text += "(comment " + std::to_string(k) + ")\n";
  }
  text += filler(3 + kLong, 20) + "M30\n";
  const std::string path = write("texts.nc", text);
  InterpreterSource source(lathe(), 64);
  ASSERT_FALSE(source.load_file(path, "texts.nc"));
  source.rewind(AxisVector{});
  const std::optional<PullResult> first = source.next();
  ASSERT_TRUE(first && std::holds_alternative<Command>(*first));
  const std::string_view kept = std::get<Command>(*first).block_text;
  for (int k = 0; k < 20; ++k) {
    const std::optional<PullResult> r = source.next();
    ASSERT_TRUE(r && std::holds_alternative<Command>(*r));
    EXPECT_EQ(std::get<Command>(*r).line, 3 + kLong + k);
  }
  EXPECT_EQ(kept, "N1 G01 X1 F100 (the first block)");
}

}  // namespace
}  // namespace mcnc::interp::test
