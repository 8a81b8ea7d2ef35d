// Canned cycles in the interpreter: the words, modal amounts and units of G74/G75/G76 and the
// hole cycles G83-G89 (spec dafeng §2.5, gsk A.6.31-A.6.35 and D2-27..D2-30). The expansions
// themselves are tested in tests/unit/cycles/.
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cmath>

namespace mcnc::interp::test {
namespace {

InterpreterConfig lathe_xzc() {
  InterpreterConfig c;
  c.axes = {AxisConfig{'X', true}, AxisConfig{'Z', false}, AxisConfig{'C', false, true}};
  return c;
}

// gsk D2-27: G74 R1; G74 Z-20 Q5000 F0.1 from (X0, Z2): Q without a point is in 0.001 mm.
TEST(InterpCycles, G74PeckDrillingFromTheFirstBlocksRetract) {
  RunResult r = run_ok("G00 X0 Z2\nG74 R1\nG74 Z-20 Q5000 F0.1\nM30\n");
  const auto feeds = r.of(Op::linear);
  ASSERT_EQ(feeds.size(), 5u);
  const double ends[] = {-3, -8, -13, -18, -20};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_AT(feeds[i], 0, ends[i]);
  }
  EXPECT_AT(r.commands[r.commands.size() - 2], 0, 2);  // back to the start
}

// gsk D2-28: grooves at Z-10, -14, -18, -20 with P3000 (3 mm radius pecks) Q4000.
TEST(InterpCycles, G75GroovesSteppedByQ) {
  RunResult r = run_ok("G00 X52 Z-10\nG75 R0.5\nG75 X40 Z-20 P3000 Q4000 F0.05\nM30\n");
  const auto feeds = r.of(Op::linear);
  ASSERT_EQ(feeds.size(), 8u);  // 4 grooves x 2 pecks
  EXPECT_AT(feeds[1], 20, -10);
  EXPECT_AT(feeds[3], 20, -14);
  EXPECT_AT(feeds[7], 20, -20);
}

TEST(InterpCycles, GroovingAlarms) {
  run_alarm("G00 X52 Z-10\nG75 X40 Z-20 P3000 F0.05\nM30\n", alarm::kCycleWordMissing, 2);
  run_alarm("G00 X52 Z-10\nG17 G75 X40 Z-20 P3000 Q4000 F0.05\nM30\n", alarm::kNoPlaneAxis, 2);
  run_alarm("G00 X52 Z-10\nG75 X40 Z-20 P3000 Q4000\nM30\n", alarm::kFeedMissing, 2);
}

// Dafeng §7-15 (L1829-1835): the first block's P010060 R0.2 stay for the second block.
TEST(InterpCycles, G76FirstBlockIsModal) {
  RunResult r = run_ok("G00 X68 Z50\nG76 P010060 R0.2\nG76 X60.4 Z25 P3.68 Q1.8 F6\nM30\n");
  const auto threads = r.of(Op::thread);
  ASSERT_EQ(threads.size(), 5u);  // 4 roughing passes and 1 finishing pass
  EXPECT_NEAR(threads.back().to[0], 30.2, 1e-9);
  EXPECT_NEAR(threads[0].to[0], 34.0 - 0.12 - 1.8, 1e-9);  // crest 33.88, first depth 1.8
  for (const Command& t : threads) {
    EXPECT_DOUBLE_EQ(t.lead, 6.0);
  }
  // gsk D2-29: P021060 = 2 finishing passes, chamfer 1.0 lead, 60 degrees; Q100 = 0.1 mm.
  RunResult g =
      run_ok("G00 X32 Z3\nG76 P021060 Q100 R0.1\nG76 X27.6 Z-30 P1200 Q400 F2\nM30\n", gsk());
  const auto gt = g.of(Op::thread);
  ASSERT_EQ(gt.size(), 2u * (7u + 2u));  // each pass threads, then chamfers out
  EXPECT_NEAR(gt[gt.size() - 2].to[0], 13.8, 1e-9);
  EXPECT_TRUE(gt.back().continuous);
}

// GSK G78 (gsk A.6.33): G76's cycle with the infeed (m) and the entry (r) chosen, D finishing
// passes, L starts and the run-out J/K of G92.
TEST(InterpCycles, GskG78ChoosesInfeedEntryPassesAndStarts) {
  // m = 0 constant steps of Q400 (0.4 mm) to 1.1 (1.2 - R0.1): 0.4, 0.8, 1.1; then D2
  // finishing passes; L2: every pass twice. Entry 0: straight in (every pass starts at Z3).
  RunResult r =
      run_ok("G00 X32 Z3\nG78 P000060 Q100 R0.1 D2 L2\nG78 X27.6 Z-30 P1200 Q400 F2\nM30\n", gsk());
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u * (3u + 2u));        // no run-out (param №19 is 0 here)
  EXPECT_NEAR(t[0].to[0], 15.0 - 0.4, 1e-9);  // the crest at 15 (radius), first step 0.4
  EXPECT_NEAR(t[2].to[0], 15.0 - 0.8, 1e-9);
  EXPECT_NEAR(t[4].to[0], 15.0 - 1.1, 1e-9);
  EXPECT_NEAR(t.back().to[0], 13.8, 1e-9);
  EXPECT_DOUBLE_EQ(t[1].start_angle, 180.0);
  for (const Command& c : r.of(Op::rapid)) {
    if (c.to[0] < 16.0) {
      EXPECT_NEAR(c.to[1], 3.0, 1e-9);  // each infeed point at Z3: entry 0, the centre
    }
  }
}

TEST(InterpCycles, GskG78EntryFlanksAndRunOut) {
  // Cutting towards -Z: r = 1 (left) enters along the flank towards -Z, ahead of the cut; r = 2
  // (right) along the one behind it, the G76 way. J1 K4: the run-out rises 1 mm over 4 mm.
  const std::string second = "G78 X27.6 Z-30 P1200 Q400 F2\nM30\n";
  RunResult left = run_ok("G00 X32 Z3\nG78 P010160 Q100 R0.1 J1 K4\n" + second, gsk());
  RunResult right = run_ok("G00 X32 Z3\nG78 P010260 Q100 R0.1 J1 K4\n" + second, gsk());
  RunResult g76 = run_ok(
      "G00 X32 Z3\nG76 P010060 Q100 R0.1\n" + std::string("G76 X27.6 Z-30 P1200 Q400 F2\nM30\n"),
      gsk());
  const auto first_in = [](const RunResult& x) { return x.of(Op::rapid)[1].to[1]; };
  const double t = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  EXPECT_NEAR(first_in(right), 3.0 - 0.4 * t, 1e-9);
  EXPECT_NEAR(first_in(g76), first_in(right), 1e-9);
  EXPECT_NEAR(first_in(left), 3.0 - (2 * 1.2 - 0.4) * t, 1e-9);
  const auto lt = left.of(Op::thread);
  ASSERT_GE(lt.size(), 2u);
  EXPECT_NEAR(lt[1].to[0] - lt[0].to[0], 1.0, 1e-9);  // the rise J
  EXPECT_NEAR(lt[0].to[1], -26.0, 1e-9);              // over the last K of Z
}

TEST(InterpCycles, GskG78Alarms) {
  const ExpectedAlarm cases[] = {
      {"G00 X32 Z3\nG78 P020060\nM30\n", alarm::kCycleValue, 2},  // m 2
      {"G00 X32 Z3\nG78 P000460\nM30\n", alarm::kCycleValue, 2},  // r 4
      {"G00 X32 Z3\nG78 P010060 L0\nM30\n", alarm::kCycleValue, 2},
      {"G00 X32 Z3\nG78 P010060 E-0.5\nM30\n", alarm::kCycleValue, 2},
      // A screw-in as long as the thread leaves it nothing to cut at its depth.
      {"G00 X32 Z3\nG78 P010060 E33\nG78 X27.6 Z-30 P1200 Q400 F2\nM30\n", alarm::kCycleValue, 3},
      {"G00 X32 Z3\nG78 X27.6 Z-30 P1200 F2\nM30\n", alarm::kCycleWordMissing, 2},
  };
  expect_alarms(cases, gsk());
  run_alarm("G00 X32 Z3\nG78 P010060\nM30\n", alarm::kUnsupportedG, 2);  // not Dafeng's
}

// GSK G78 E (gsk A.6.33, decision 84): every pass screws in, its thread starting E (radius)
// outside its depth and reaching it at 45 degrees; E0 in a later first block ends it.
TEST(InterpCycles, GskG78ScrewInStartsEachPassOutsideItsDepth) {
  const std::string second = "G78 X27.6 Z-30 P1200 Q400 F2\n";
  RunResult r = run_ok("G00 X32 Z3\nG78 P010060 Q100 R0.1 E0.5\n" + second +
                           "G00 X32 Z3\nG78 E0\n" + second + "M30\n",
                       gsk());
  const auto first = r.at_line(3);
  ASSERT_GE(first.size(), 3u);
  // The crest lies at 15 (radius), the first pass 0.4 below it; centre entry (r = 0).
  EXPECT_EQ(first[0].op, Op::rapid);
  EXPECT_AT(first[0], 15.1, 3);
  EXPECT_EQ(first[1].op, Op::thread);
  EXPECT_AT(first[1], 14.6, 2.5);
  EXPECT_DOUBLE_EQ(first[1].lead, 2.0);
  EXPECT_FALSE(first[1].continuous);  // it waits for the one-revolution signal
  EXPECT_EQ(first[2].op, Op::thread);
  EXPECT_AT(first[2], 14.6, -30);
  EXPECT_TRUE(first[2].continuous);
  std::size_t passes = 0;
  for (const Command& c : first) {
    if (c.op == Op::rapid && c.to[1] == 3.0 && c.to[0] < 16.0) {
      ++passes;
      EXPECT_GT(c.to[0], 13.8 + 0.5 - 1e-9);  // no infeed point below the root plus E
    }
  }
  const auto second_run = r.at_line(6);
  const auto threads = [](const std::vector<Command>& v) {
    std::size_t n = 0;
    for (const Command& c : v) {
      n += c.op == Op::thread ? 1 : 0;
    }
    return n;
  };
  EXPECT_EQ(threads(first), 2 * passes);   // a screw-in and the thread in every pass
  EXPECT_EQ(threads(second_run), passes);  // E0: the thread alone
}

// Dafeng G76 PQ (dafeng L1795, decision 85): the spec's example with PQ5. Every 5 mm of
// thread a roughing pass lifts out of its chip to the pass before at 45 degrees and back in;
// the finishing pass cuts through.
TEST(InterpCycles, DafengG76PqBreaksTheChipOfRoughingPasses) {
  RunResult r = run_ok("G00 X68 Z50\nG76 P010060 R0.2 PQ5\nG76 X60.4 Z25 P3.68 Q1.8 F6\nM30\n");
  const auto t = r.of(Op::thread);
  const double tan30 = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  // Pass 1 at depth 1.8 (crest 33.88, radius), from Z50 - 1.8 tan 30: two breaks up to the
  // crest, then on to Z25 (r = 00: no chamfer).
  const double z0 = 50.0 - 1.8 * tan30;
  ASSERT_GE(t.size(), 7u);
  EXPECT_AT(t[0], 32.08, z0 - 5.0);
  EXPECT_AT(t[1], 33.88, z0 - 6.8);
  EXPECT_AT(t[2], 32.08, z0 - 8.6);
  EXPECT_AT(t[3], 32.08, z0 - 13.6);
  EXPECT_AT(t[4], 33.88, z0 - 15.4);
  EXPECT_AT(t[5], 32.08, z0 - 17.2);
  EXPECT_AT(t[6], 32.08, 25.0);
  EXPECT_FALSE(t[0].continuous);
  for (std::size_t i = 1; i < 7; ++i) {
    EXPECT_TRUE(t[i].continuous) << i;
    EXPECT_DOUBLE_EQ(t[i].lead, 6.0) << i;
  }
  // Pass 2 (depth 1.8 sqrt 2) lifts to pass 1's depth only.
  EXPECT_NEAR(t[8].to[0], 32.08, 1e-9);
  // The finishing pass: one thread move at the full height.
  EXPECT_AT(t.back(), 30.2, 25.0);
  EXPECT_NE(t[t.size() - 2].to[0], 30.2);
  // Without PQ the same cycle cuts each pass in one move.
  RunResult plain = run_ok("G00 X68 Z50\nG76 P010060 R0.2\nG76 X60.4 Z25 P3.68 Q1.8 F6\nM30\n");
  EXPECT_EQ(plain.of(Op::thread).size(), 5u);
  run_alarm("G00 X68 Z50\nG76 P010060 R0.2 PQ-1\nM30\n", alarm::kCycleValue, 2);
}

TEST(InterpCycles, G76NeedsHeightAndFirstDepth) {
  run_alarm("G00 X68 Z50\nG76 X60.4 Z25 P3.68 F6\nM30\n", alarm::kCycleWordMissing, 2);
  run_alarm("G00 X68 Z50\nG76 P1234567\nM30\n", alarm::kCycleValue, 2);
}

// Dafeng §7-21 (L1907-1940): G83.5 with M12, then H90 K3: four holes at C 0/90/180/270, each
// between M12 and M13, cancelled by G00.
TEST(InterpCycles, G83HolesRepeatWithIncrementalPositioning) {
  RunResult r = run_ok(
      "G98 G00 Z5\nG00 X100\nG83.5 Z-10 C0 R1 Q4 F300 M12\nH90 K3\nG00 Z100\nM30\n", lathe_xzc());
  const auto aux = r.of(Op::aux);
  ASSERT_EQ(aux.size(), 8u);
  for (std::size_t i = 0; i < aux.size(); ++i) {
    EXPECT_EQ(aux[i].code, i % 2 == 0 ? 12 : 13);
  }
  double bottoms = 0;
  for (const Command& c : r.of(Op::linear)) {
    bottoms += c.to[1] == -10.0 ? 1 : 0;
  }
  EXPECT_EQ(bottoms, 4);
  // The last hole at C270, then G00 Z100 ends the cycle and moves.
  const Command last = r.at_line(5)[0];
  EXPECT_EQ(last.op, Op::rapid);
  EXPECT_NEAR(last.to[2], 270.0, 1e-9);
  EXPECT_NEAR(last.to[1], 100.0, 1e-9);
}

TEST(InterpCycles, G80EndsTheHoleCycle) {
  RunResult r = run_ok("G00 X0 Z5\nG83 Z-10 R1 F100\nG80\nZ10\nM30\n");
  EXPECT_EQ(r.at_line(4).size(), 1u);  // a plain rapid again
  EXPECT_EQ(r.at_line(4)[0].op, Op::rapid);
}

TEST(InterpCycles, TappingUsesTheLeadAndReversesATurningSpindle) {
  RunResult r = run_ok("M03 S500\nG00 X0 Z5\nG84 Z-10 R1 F1.25\nG80\nM30\n");
  const auto taps = r.of(Op::thread);
  ASSERT_EQ(taps.size(), 2u);  // in and out, synchronised
  EXPECT_DOUBLE_EQ(taps[0].lead, 1.25);
  EXPECT_AT(taps[0], 0, -10);
  const auto spindles = r.of(Op::spindle);
  ASSERT_EQ(spindles.size(), 3u);
  EXPECT_EQ(spindles[1].spindle_direction, SpindleDirection::ccw);
  EXPECT_EQ(spindles[2].spindle_direction, SpindleDirection::cw);
  run_alarm("G00 X0 Z5\nG84 Z-10 R1\nM30\n", alarm::kThreadLead, 2);
}

TEST(InterpCycles, HoleCycleRPointInAPlaneWithoutItsAxes) {
  // G19 (YZ) on an X/Z lathe: no drilling axis for the R point. Found by the fuzzer: an alarm
  // on the R word, never an axis index out of range.
  run_alarm("G00 X0 Z5\nG19\nG83 Z-10 R1 F100\nM30\n", alarm::kNoPlaneAxis, 3);
}

TEST(InterpCycles, HoleCycleNeedsItsBottom) {
  run_alarm("G00 X0 Z5\nG83 R1 F100\nX10\nM30\n", alarm::kCycleWordMissing, 2);
}

// GSK: R is the back-off, J0/J1 the peck type, Q in 0.001 mm (gsk D2-30).
TEST(InterpCycles, GskDrillingWords) {
  RunResult r = run_ok("G00 X0 Z0\nG83 Z-10 Q3000 R1 P500 F0.1 J0\nG80\nM30\n", gsk());
  const auto feeds = r.of(Op::linear);
  ASSERT_EQ(feeds.size(), 4u);
  EXPECT_AT(feeds[0], 0, -3);
  EXPECT_AT(feeds[1], 0, -6);
  EXPECT_AT(feeds[3], 0, -10);
  ASSERT_EQ(r.of(Op::dwell).size(), 1u);
  EXPECT_DOUBLE_EQ(r.of(Op::dwell)[0].seconds, 0.5);
}

// gsk D2-32: G33 Z-15 F1.5 from Z5 with M03: tap in, M05, M04, tap out, M05; L2 twice.
TEST(InterpCycles, GskG33FlexibleTapping) {
  RunResult r = run_ok("M03 S300\nG00 X0 Z5\nG33 Z-15 F1.5\nM30\n", gsk());
  const auto cycle = r.at_line(3);
  ASSERT_EQ(cycle.size(), 5u);
  EXPECT_EQ(cycle[0].op, Op::thread);
  EXPECT_AT(cycle[0], 0, -15);
  EXPECT_DOUBLE_EQ(cycle[0].lead, 1.5);
  EXPECT_EQ(cycle[1].spindle_direction, SpindleDirection::stop);
  EXPECT_EQ(cycle[2].spindle_direction, SpindleDirection::ccw);
  EXPECT_EQ(cycle[3].op, Op::thread);
  EXPECT_AT(cycle[3], 0, 5);
  EXPECT_EQ(cycle[4].spindle_direction, SpindleDirection::stop);
  RunResult twice = run_ok("M03 S300\nG00 X0 Z5\nG33 Z-15 F1.5 L2\nM30\n", gsk());
  EXPECT_EQ(twice.at_line(3).size(), 11u);  // the second one starts the spindle again
  run_alarm("G00 X0 Z5\nG33 Z-15 F1.5\nM30\n", alarm::kWordNotAllowed, 2, -1, gsk());
  run_alarm("M03 S300\nG00 X0 Z5\nG33 Z-15 F1.5\nM30\n", alarm::kUnsupportedG, 3);
}

// gsk A.6.22 rule 4: M98 under compensation is an alarm in the GSK dialect.
TEST(InterpCycles, GskSubprogramCallUnderCompensation) {
  InterpreterConfig c = gsk();
  c.tool_geometry[1].radius = 0.4;
  run_alarm("O1\nT0101\nG42 G00 X20 Z5\nM98 P100\nM30\nO100\nG01 Z0 F1\nM99\n",
            alarm::kCompensationStart, 4, -1, c);
}

// A hole cycle keeps P as its dwell at the bottom when S stands beside it (not `S_ Paab`),
// in the cycle's block and in the blocks that repeat it.
TEST(InterpCycles, DwellOfAHoleCycleBesideASpeed) {
  RunResult r =
      run_ok("M03 S500\nG00 X0 Z5\nG83 Z-20 R2 P500 F0.1 S800\nZ-25 P700 S900\nG80\nM30\n");
  const auto spindles = r.of(Op::spindle);
  ASSERT_EQ(spindles.size(), 3u);
  EXPECT_EQ(spindles[1].spindle, 1);
  EXPECT_DOUBLE_EQ(spindles[1].rpm, 800.0);
  EXPECT_EQ(spindles[2].spindle, 1);
  EXPECT_DOUBLE_EQ(spindles[2].rpm, 900.0);
  const auto dwells = r.of(Op::dwell);
  ASSERT_EQ(dwells.size(), 2u);
  EXPECT_DOUBLE_EQ(dwells[0].seconds, 0.5);
  EXPECT_DOUBLE_EQ(dwells[1].seconds, 0.7);
}

}  // namespace
}  // namespace mcnc::interp::test
