// Read-ahead: macro statements are evaluated only as far as commands have been pulled; a
// barrier (G04.1, G04 I0, G53, M00, M01, M30 ...) is never looked past (spec dafeng §4.3).
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <random>

namespace mcnc::interp::test {
namespace {

Command pull(Interpreter& in) {
  auto x = in.next();
  EXPECT_TRUE(x.has_value());
  if (!x || !std::holds_alternative<Command>(*x)) {
    if (x) {
      ADD_FAILURE() << "alarm " << std::get<ProgramAlarm>(*x).text;
    }
    return Command{};
  }
  return std::get<Command>(*x);
}

const char* kBranch =
    "G00 X10\n"
    "G04.1 P1 Q12\n"
    "IF[#500==1] GOTO 100\n"
    "IF[#500==2] GOTO 200\n"
    "#3000=1(#500 WRONG)\n"
    "N100 G00 Z100\n"
    "M30\n"
    "N200 G00 Z200\n"
    "M30\n";

TEST(InterpReadAhead, BranchFollowsAVariableWrittenAtTheSync) {
  for (int value : {1, 2}) {
    Interpreter in(lathe());
    ASSERT_FALSE(in.start(kBranch, "t.nc"));
    EXPECT_EQ(pull(in).op, Op::rapid);
    Command sync = pull(in);
    ASSERT_EQ(sync.op, Op::sync);
    EXPECT_TRUE(sync.barrier);
    // Another channel publishes #500 while this one waits at the barrier.
    ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(value)));
    Command move = pull(in);
    ASSERT_EQ(move.op, Op::rapid);
    EXPECT_NEAR(move.to[1], value * 100.0, 1e-9);
    EXPECT_EQ(move.line, value == 1 ? 6 : 8);
  }
}

TEST(InterpReadAhead, ValueBeforeTheSyncIsNotUsed) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start(kBranch, "t.nc"));
  ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(1)));
  pull(in);
  pull(in);
  ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(2)));
  EXPECT_NEAR(pull(in).to[1], 200, 1e-9);
}

TEST(InterpReadAhead, G04I0IsABarrierToo) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start("G4I0\n#1=#500\nG00 Z[#1]\nM30\n", "t.nc"));
  Command s = pull(in);
  EXPECT_EQ(s.op, Op::sync);
  EXPECT_TRUE(s.barrier);
  ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(7)));
  EXPECT_NEAR(pull(in).to[1], 7, 1e-9);
}

TEST(InterpReadAhead, M00AndM01AreBarriers) {
  for (const char* stop : {"M00", "M01"}) {
    Interpreter in(lathe());
    ASSERT_FALSE(in.start(std::string(stop) + "\nG00 Z[#500]\nM30\n", "t.nc"));
    Command s = pull(in);
    EXPECT_EQ(s.op, Op::stop);
    EXPECT_TRUE(s.barrier);
    ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(3)));
    EXPECT_NEAR(pull(in).to[1], 3, 1e-9) << stop;
  }
}

TEST(InterpReadAhead, G53IsABarrier) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start("G53 Z10\nG00 X[#500]\nM30\n", "t.nc"));
  Command s = pull(in);
  EXPECT_TRUE(s.barrier);
  ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(40)));
  EXPECT_NEAR(pull(in).to[0], 20, 1e-9);
}

TEST(InterpReadAhead, OnePullEvaluatesOnlyUpToTheNextCommand) {
  // The assignment after the first move is not evaluated until the second pull.
  Interpreter in(lathe());
  ASSERT_FALSE(in.start("G00 Z1\n#500=#500+1\nG00 Z[#500]\nM30\n", "t.nc"));
  ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(10)));
  pull(in);
  EXPECT_NEAR(in.variables().read(500).value.number(), 10, 1e-12);
  ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(20)));
  EXPECT_NEAR(pull(in).to[1], 21, 1e-9);
}

TEST(InterpReadAhead, PositionAfterBarrierIsTheEndPoint) {
  // CT-MACRO-BUF-01: with G4I0 between, #1 is the end position of the move.
  RunResult r = run_ok("G01 X100 F100\nG4I0\n#1=#5021\nG00 Z[#1]\nM30\n");
  EXPECT_NEAR(r.of(Op::rapid)[0].to[1], 100, 1e-9);
}

TEST(InterpReadAhead, RandomInterleavingOfPullsAndWrites) {
  // A loop waits at a sync each round and moves to Z = the #500 published at that sync.
  const char* prog =
      "#1=0\n"
      "WHILE[#1 LT 50]DO1\n"
      "G04.1 P1 Q12\n"
      "G00 Z[#500]\n"
      "#1=#1+1\n"
      "END1\n"
      "M30\n";
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> value(-1000, 1000);
  Interpreter in(lathe());
  ASSERT_FALSE(in.start(prog, "t.nc"));
  for (int round = 0; round < 50; ++round) {
    ASSERT_EQ(pull(in).op, Op::sync);
    const int v = value(rng);
    ASSERT_FALSE(in.variables().write(500, macro::MacroValue::of(v)));
    Command m = pull(in);
    ASSERT_EQ(m.op, Op::rapid);
    EXPECT_NEAR(m.to[1], v, 1e-9) << "round " << round;
  }
  EXPECT_EQ(pull(in).op, Op::end);
  EXPECT_FALSE(in.next().has_value());
}

TEST(InterpReadAhead, CommandsAreNumberedInOrder) {
  RunResult r = run_ok("G00 Z1\nG00 Z2\nG04 X1\nM30\n");
  for (std::size_t i = 0; i < r.commands.size(); ++i) {
    EXPECT_EQ(r.commands[i].n, i + 1);
  }
  EXPECT_TRUE(r.commands.back().barrier);  // M30
}

}  // namespace
}  // namespace mcnc::interp::test
