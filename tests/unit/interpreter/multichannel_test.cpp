// Multi-channel words as one channel's commands: G04.1, G140/G141/G142, G144/G145, G51.4/G50.4,
// G114.1/G113, CH n, CHN (spec dafeng §3).
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <set>

namespace mcnc::interp::test {
namespace {

std::set<int> channels_of(const Command& c) {
  std::set<int> s;
  for (int ch = 1; ch <= 255; ++ch) {
    if (c.has_channel(ch)) {
      s.insert(ch);
    }
  }
  return s;
}

InterpreterConfig channel(int n, InterpreterConfig c = lathe()) {
  c.channel = n;
  return c;
}

TEST(InterpMultiChannel, G041ChannelLists) {
  RunResult r = run_ok(
      "G04.1 P1 Q123\nG04.1 P2 Q10\nG04.1 P3 Q1 Q1=2\nG04.1 P4 Q-1\nG04.1 P5\nG04.1\n"
      "G04.1 P6 Q1=3 Q1\nM30\n");
  auto s = r.of(Op::sync);
  ASSERT_EQ(s.size(), 7u);
  EXPECT_EQ(channels_of(s[0]), (std::set<int>{1, 2, 3}));
  EXPECT_EQ(channels_of(s[1]), (std::set<int>{1, 10}));
  EXPECT_EQ(channels_of(s[2]), (std::set<int>{1, 12}));
  EXPECT_TRUE(s[3].all_channels);
  EXPECT_TRUE(s[4].all_channels);
  EXPECT_FALSE(s[5].has_p);
  EXPECT_EQ(channels_of(s[6]), (std::set<int>{1, 13}));
  for (const Command& c : s) {
    EXPECT_TRUE(c.barrier);
  }
  EXPECT_EQ(s[0].p, 1);
  EXPECT_EQ(s[2].p, 3);
}

TEST(InterpMultiChannel, G041MustIncludeThisChannel) {
  run_alarm("G00 X1\nG04.1 P1 Q12\nM30\n", alarm::kSyncForm, 2, -1, channel(3));
  RunResult r = run_ok("G04.1 P1 Q23\nM30\n", channel(3));
  EXPECT_EQ(channels_of(r.of(Op::sync)[0]), (std::set<int>{2, 3}));
}

TEST(InterpMultiChannel, G041QWithoutPIsAnAlarm) {
  run_alarm("G00 X1\nG04.1 Q12\nM30\n", alarm::kSyncForm, 2);
}

TEST(InterpMultiChannel, G041BadQIsAnAlarm) {
  run_alarm("G04.1 P1 Q1.5\nM30\n", alarm::kSyncForm, 1);
}

TEST(InterpMultiChannel, AxisExchange) {
  InterpreterConfig c = lathe_xyz();
  c.axes.push_back(AxisConfig{'A', false, true});
  c.axes.back().exchange = 14;
  RunResult r = run_ok("G140 A14\nG141 A14 P1\nG141 A14\nG142\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 5u);
  EXPECT_EQ(r.commands[0].op, Op::axis_release);
  EXPECT_EQ(r.commands[0].axis, 'A');
  EXPECT_EQ(r.commands[0].exchange, 14);
  EXPECT_EQ(r.commands[1].op, Op::axis_acquire);
  EXPECT_TRUE(r.commands[1].force);
  EXPECT_FALSE(r.commands[2].force);
  EXPECT_EQ(r.commands[3].op, Op::axis_restore);
}

TEST(InterpMultiChannel, ReleasedAxisCannotBeProgrammedUntilG142) {
  InterpreterConfig c = lathe_xyz();
  c.axes.push_back(AxisConfig{'A', false, true});
  c.axes.back().exchange = 14;
  run_alarm("G140 A14\nG00 X10\nG00 A5\nM30\n", alarm::kReleasedAxis, 3, -1, c);
  RunResult r = run_ok("G140 A14\nG142\nG00 A5\nM30\n", c);
  EXPECT_NEAR(r.of(Op::rapid)[0].to[3], 5, 1e-9);
}

TEST(InterpMultiChannel, G140WrongExchangeNumberIsAnAlarm) {
  InterpreterConfig c = lathe_xyz();
  c.axes.push_back(AxisConfig{'A', false, true});
  c.axes.back().exchange = 14;
  run_alarm("G140 A15\nM30\n", alarm::kBadWordValue, 1, -1, c);
}

TEST(InterpMultiChannel, G144ArgumentsAndWait) {
  RunResult r = run_ok("G144 N2 P2000 H1 Q10 A1 Z26\nG144 N3 P3000 H0\nG145\nM30\n");
  auto s = r.of(Op::subcall);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].channel, 2);
  EXPECT_EQ(s[0].program, 2000);
  EXPECT_TRUE(s[0].wait);
  EXPECT_TRUE(s[0].barrier);
  ASSERT_EQ(s[0].args.size(), 3u);
  EXPECT_EQ(s[0].args[0], (std::pair<int, double>{1, 1}));
  EXPECT_EQ(s[0].args[1], (std::pair<int, double>{17, 10}));
  EXPECT_EQ(s[0].args[2], (std::pair<int, double>{26, 26}));
  EXPECT_FALSE(s[1].wait);
  EXPECT_EQ(r.of(Op::subcall_release).size(), 1u);
}

TEST(InterpMultiChannel, G144LOnlyWithH1) {
  run_alarm("G144 N2 P2000 H0 L2\nM30\n", alarm::kWordNotAllowed, 1);
}

TEST(InterpMultiChannel, G144WithoutNIsAnAlarm) {
  run_alarm("G00 X1\nG144 P2000\nM30\n", alarm::kBadWordValue, 2);
}

TEST(InterpMultiChannel, AxisSync) {
  RunResult r = run_ok("G51.4 P1 Q2\nG50.4 P1 Q2\nG51.4 Q4\nM30\n");
  ASSERT_EQ(r.commands.size(), 4u);
  EXPECT_EQ(r.commands[0].op, Op::axis_couple);
  EXPECT_EQ(r.commands[0].master, 1);
  EXPECT_EQ(r.commands[0].slave, 2);
  EXPECT_EQ(r.commands[1].op, Op::axis_decouple);
  EXPECT_EQ(r.commands[1].slave, 2);
  EXPECT_EQ(r.commands[2].master, 0);
}

TEST(InterpMultiChannel, AxisSyncNeedsQ) {
  run_alarm("G51.4 P1\nM30\n", alarm::kBadWordValue, 1);
}

TEST(InterpMultiChannel, SpindleSync) {
  RunResult r = run_ok("G114.1\nG113\nG114.1 P2 Q-3 K3 R45.5\nM30\n");
  ASSERT_EQ(r.commands.size(), 4u);
  EXPECT_EQ(r.commands[0].op, Op::spindle_sync);
  EXPECT_EQ(r.commands[0].sync_p, 1);
  EXPECT_EQ(r.commands[0].sync_q, 1);
  EXPECT_EQ(r.commands[0].sync_k, 1);
  EXPECT_NEAR(r.commands[0].sync_r, 0, 1e-12);
  EXPECT_EQ(r.commands[1].op, Op::spindle_unsync);
  EXPECT_EQ(r.commands[2].sync_p, 2);
  EXPECT_EQ(r.commands[2].sync_q, -3);
  EXPECT_EQ(r.commands[2].sync_k, 3);
  EXPECT_NEAR(r.commands[2].sync_r, 45.5, 1e-12);
}

TEST(InterpMultiChannel, ChInItsChannelRuns) {
  RunResult r = run_ok("O1002\nCH2\nG00 X10\nM30\n", channel(2));
  EXPECT_EQ(r.of(Op::rapid).size(), 1u);
}

TEST(InterpMultiChannel, ChInAnotherChannelIsAnAlarmBeforeAnything) {
  RunResult r = run_alarm("O1001\nCH1\nG00 X10\nM30\n", alarm::kWrongChannel, 2, -1, channel(2));
  EXPECT_TRUE(r.commands.empty());
}

TEST(InterpMultiChannel, ChnReadsTheChannel) {
  for (int ch : {1, 2, 7}) {
    RunResult r = run_ok("#1=CHN\nG00 Z[#1]\nIF[CHN==2] G00 Z100\nM30\n", channel(ch));
    auto m = r.of(Op::rapid);
    ASSERT_EQ(m.size(), ch == 2 ? 2u : 1u);
    EXPECT_NEAR(m[0].to[1], ch, 1e-9);
  }
}

TEST(InterpMultiChannel, SharedRetainedVariableAcrossChannelQualifiedAddress) {
  // #aa bbbbbb: channel 1's own variables addressed with its channel number.
  RunResult r = run_ok("#100=5\nG00 Z[#1000100]\nM30\n", channel(1));
  EXPECT_NEAR(r.of(Op::rapid)[0].to[1], 5, 1e-9);
}

}  // namespace
}  // namespace mcnc::interp::test
