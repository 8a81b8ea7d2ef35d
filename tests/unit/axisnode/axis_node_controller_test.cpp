// The axis node core in closed loop with a simulated drive (no bus, no DDS): each cycle the
// controller's RPDO goes to the drive, a SYNC steps it, and its TPDO comes back next cycle.
#include "axisnode/control/axis_node_controller.hpp"
#include "axisnode/drivesim/simulated_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace mcnc;
using axisnode::AxisAlarm;
using axisnode::AxisNodeController;
using axisnode::AxisNodeInput;

namespace {

constexpr double kCycle = 0.001;

struct Loop {
  AxisNodeController node;
  drivesim::SimulatedDrive drive;
  canopen::TxPdoCsp tpdo{};
  bool have_tpdo = false;
  std::uint64_t cycle = 0;

  explicit Loop(int deadline = 5, double start = 12.5, double acceleration = 0.0,
                int best_effort_watch_cycles = 0)
      : node([&] {
          axisnode::AxisNodeSetup s{10000.0, kCycle, deadline};
          s.acceleration = acceleration;
          s.best_effort_watch_cycles = best_effort_watch_cycles;
          return s;
        }()),
        drive(drivesim::DriveParams{1, 10000.0, 0.004, 500.0, 5000.0, start}, kCycle) {
    drive.power_on();
    drive.on_nmt(canopen::NmtCommand::start);
  }

  // One cycle; `setpoint` < 0 cycles means none arrived.
  const axisnode::AxisNodeOutput& step(AxisNodeInput in) {
    in.have_tpdo = have_tpdo;
    in.statusword = tpdo.statusword;
    in.position_counts = tpdo.position_actual;
    const auto& out = node.cycle(cycle++, in);
    drive.on_rpdo(canopen::RxPdoCsp{out.controlword, out.target_counts});
    tpdo = drive.on_sync();
    have_tpdo = true;
    return out;
  }

  void enable() {
    for (int i = 0; i < 10 && !node.output().enabled; ++i) {
      AxisNodeInput in;
      in.have_setpoint = true;
      in.setpoint_valid = false;
      step(in);
    }
  }
};

AxisNodeInput setpoint(double pos, double vel = 0.0) {
  AxisNodeInput in;
  in.have_setpoint = true;
  in.setpoint_valid = true;
  in.setpoint_pos = pos;
  in.setpoint_vel = vel;
  return in;
}

}  // namespace

TEST(AxisNodeController, EnablesTheDriveAndTakesOverItsPositionWithoutAJump) {
  Loop loop;
  loop.enable();
  ASSERT_TRUE(loop.node.output().enabled);
  EXPECT_EQ(loop.drive.state(), cia402::State::operation_enabled);
  EXPECT_DOUBLE_EQ(loop.node.output().cmd, 12.5);
  EXPECT_NEAR(loop.drive.position(), 12.5, 1e-12);
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::none);
}

TEST(AxisNodeController, FollowsSetpointsToTheDriveInCounts) {
  Loop loop;
  loop.enable();
  for (int i = 0; i < 400; ++i) {
    loop.step(setpoint(20.0));
  }
  EXPECT_EQ(loop.node.output().target_counts, 200000);
  EXPECT_NEAR(loop.drive.position(), 20.0, 1e-6);
  EXPECT_NEAR(loop.node.output().act, 20.0, 1e-4);
}

TEST(AxisNodeController, InvalidSetpointHoldsPosition) {
  Loop loop;
  loop.enable();
  AxisNodeInput hold;
  hold.have_setpoint = true;
  hold.setpoint_valid = false;
  hold.setpoint_pos = 99.0;
  for (int i = 0; i < 20; ++i) {
    loop.step(hold);
  }
  EXPECT_DOUBLE_EQ(loop.node.output().cmd, 12.5);
}

// With the axis's acceleration known, a missing setpoint continues the motion as a stop at that
// deceleration would: never past where the owner's move could have ended (in realtime under
// loss, the last velocity carried a link axis 49 um past the end of its move).
TEST(AxisNodeController, MissingSetpointsContinueAsAStopAtTheAxisDeceleration) {
  Loop loop(/*deadline=*/10, 12.5, /*acceleration=*/2000.0);
  loop.enable();
  for (int i = 0; i < 50; ++i) {
    loop.step(setpoint(12.5 + 0.01 * i, 10.0));  // 10 mm/s
  }
  const double last = loop.node.output().cmd;
  AxisNodeInput none;
  // 2 mm/s less each 1 ms cycle: 9, 7, 5, 3 and 1 um, then at rest.
  const double expected[] = {0.009, 0.016, 0.021, 0.024, 0.025, 0.025, 0.025};
  for (int i = 0; i < 7; ++i) {
    const auto& out = loop.step(none);
    EXPECT_FALSE(out.quick_stop) << "cycle " << i;
    EXPECT_NEAR(out.cmd, last + expected[i], 1e-9) << "cycle " << i;
  }
  // The stop is 10^2 / (2 * 2000) = 25 um long, half of what the last velocity would have run.
}

TEST(AxisNodeController, MissingSetpointsAreExtrapolatedThenQuickStopAtTheDeadline) {
  Loop loop(/*deadline=*/5);
  loop.enable();
  for (int i = 0; i < 50; ++i) {
    loop.step(setpoint(12.5 + 0.01 * i, 10.0));  // 10 mm/s
  }
  const double last = loop.node.output().cmd;
  AxisNodeInput none;
  for (int i = 1; i <= 4; ++i) {
    const auto& out = loop.step(none);
    EXPECT_FALSE(out.quick_stop) << "cycle " << i;
    EXPECT_NEAR(out.cmd, last + 10.0 * kCycle * i, 1e-9);  // continues the motion
    EXPECT_EQ(out.missing_setpoints, i);
  }
  const auto& out = loop.step(none);  // the fifth missing cycle
  EXPECT_TRUE(out.quick_stop);
  EXPECT_EQ(out.new_alarm, AxisAlarm::setpoint_deadline);
  EXPECT_EQ(out.controlword, cia402::encode_controlword(cia402::Command::quick_stop));
  // The drive ramps down and rests in quick stop active.
  for (int i = 0; i < 200; ++i) {
    loop.step(none);
  }
  EXPECT_EQ(loop.drive.state(), cia402::State::quick_stop_active);
  EXPECT_EQ(loop.drive.velocity(), 0.0);
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::setpoint_deadline);
  EXPECT_FALSE(loop.node.output().enabled);
  // New setpoints do not restart motion after a quick stop.
  const double rest = loop.drive.position();
  for (int i = 0; i < 50; ++i) {
    loop.step(setpoint(rest + 5.0));
  }
  EXPECT_DOUBLE_EQ(loop.drive.position(), rest);
}

TEST(AxisNodeController, OwnerLostIsAnAlarmAndQuickStop) {
  Loop loop;
  loop.enable();
  AxisNodeInput in = setpoint(12.5);
  in.owner_lost = true;
  const auto& out = loop.step(in);
  EXPECT_TRUE(out.quick_stop);
  EXPECT_EQ(out.new_alarm, AxisAlarm::owner_lost);
}

TEST(AxisNodeController, EmergencyStopQuickStopsWithoutAnAxisAlarm) {
  Loop loop;
  loop.enable();
  AxisNodeInput in = setpoint(12.5);
  in.emergency_stop = true;
  const auto& out = loop.step(in);
  EXPECT_TRUE(out.quick_stop);
  EXPECT_EQ(out.new_alarm, AxisAlarm::none);
}

TEST(AxisNodeController, DriveThatStopsAnsweringIsAlarmed) {
  Loop loop(/*deadline=*/3);
  loop.enable();
  loop.have_tpdo = false;
  AxisNodeInput in = setpoint(12.5);
  AxisNodeInput no_answer = in;
  // Feed the controller directly: no TPDO for three cycles.
  axisnode::AxisNodeController& node = loop.node;
  const std::uint64_t last = loop.cycle - 1;  // the last TPDO was used in this cycle
  EXPECT_EQ(node.cycle(last + 1, no_answer).new_alarm, AxisAlarm::none);
  EXPECT_EQ(node.cycle(last + 2, no_answer).new_alarm, AxisAlarm::none);
  EXPECT_EQ(node.cycle(last + 3, no_answer).new_alarm, AxisAlarm::drive_lost);
}

// A lockstep machine paced after its E-stop runs without real-time scheduling: the drive's
// simulator may answer late on a loaded host, so the drive is judged silent only after the
// longer watch (decision 127). The same node, cycles and silence alarm at the deadline when
// the cycles are scheduled.
TEST(AxisNodeController, PacedBestEffortADriveIsSilentOnlyAfterTheLongerWatch) {
  for (const bool best_effort : {false, true}) {
    Loop loop(/*deadline=*/3, 12.5, 0.0, /*best_effort_watch_cycles=*/20);
    loop.enable();
    const std::uint64_t last = loop.cycle - 1;  // the last answer was used in this cycle
    AxisNodeInput silent = setpoint(12.5);
    silent.emergency_stop = true;
    silent.paced_best_effort = best_effort;
    std::uint64_t alarm_after = 0;
    for (std::uint64_t c = last + 1; c < last + 100 && alarm_after == 0; ++c) {
      if (loop.node.cycle(c, silent).new_alarm == AxisAlarm::drive_lost) {
        alarm_after = c - last;
      }
    }
    EXPECT_EQ(alarm_after, best_effort ? 20U : 3U) << "paced best effort: " << best_effort;
  }
}

// The heartbeat likewise: consumer time 15 cycles, watched over 40 when paced best effort.
TEST(AxisNodeController, PacedBestEffortTheHeartbeatIsLostOnlyAfterTheLongerWatch) {
  for (const bool best_effort : {false, true}) {
    axisnode::AxisNodeSetup setup{10000.0, kCycle, 5, 15};
    setup.best_effort_watch_cycles = 40;
    axisnode::AxisNodeController node(setup);
    AxisNodeInput in;
    in.have_tpdo = true;  // the drive answers; only its heartbeat stops after cycle 10
    in.paced_best_effort = best_effort;
    std::uint64_t lost_at = 0;
    for (std::uint64_t c = 0; c < 200 && lost_at == 0; ++c) {
      in.heartbeats = c <= 10 ? c + 1 : 11;
      if (node.cycle(c, in).new_alarm == AxisAlarm::heartbeat_lost) {
        lost_at = c;
      }
    }
    EXPECT_EQ(lost_at, best_effort ? 51U : 26U) << "paced best effort: " << best_effort;
  }
}

TEST(AxisNodeController, AnAlarmIsRaisedOnceAndStaysActive) {
  Loop loop;
  loop.enable();
  AxisNodeInput in = setpoint(12.5);
  in.owner_lost = true;
  EXPECT_EQ(loop.step(in).new_alarm, AxisAlarm::owner_lost);
  for (int i = 0; i < 10; ++i) {
    const auto& out = loop.step(in);
    EXPECT_EQ(out.new_alarm, AxisAlarm::none);
    EXPECT_EQ(out.alarm, AxisAlarm::owner_lost);
  }
}

TEST(AxisNodeController, DeadlineIsArmedByTheFirstSetpoint) {
  Loop loop(/*deadline=*/3);
  AxisNodeInput none;
  for (int i = 0; i < 50; ++i) {
    loop.step(none);  // enables, but the owner has not spoken yet
  }
  EXPECT_TRUE(loop.node.output().enabled);
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::none);
  loop.step(setpoint(12.5));
  loop.step(none);
  loop.step(none);
  EXPECT_EQ(loop.step(none).new_alarm, AxisAlarm::setpoint_deadline);
}

TEST(AxisNodeController, SkippedCyclesCountTowardTheDeadline) {
  Loop loop(/*deadline=*/5);
  loop.enable();
  loop.step(setpoint(12.5));
  const std::uint64_t last = loop.cycle - 1;
  AxisNodeInput none;
  none.have_tpdo = true;  // the drive answers; only the owner is silent
  none.statusword = loop.tpdo.statusword;
  none.position_counts = loop.tpdo.position_actual;
  EXPECT_EQ(loop.node.cycle(last + 4, none).new_alarm, AxisAlarm::none);  // ticks skipped
  EXPECT_EQ(loop.node.cycle(last + 5, none).new_alarm, AxisAlarm::setpoint_deadline);
}

TEST(AxisNodeController, HeartbeatLostIsAnAlarmAndQuickStopAfterTheConsumerTime) {
  // Heartbeats every 100 cycles, consumer time 150 cycles: the alarm comes 151 cycles after
  // the last one, not before; not at all while they come.
  AxisNodeController node(axisnode::AxisNodeSetup{10000.0, kCycle, 5, 150});
  drivesim::SimulatedDrive drive(drivesim::DriveParams{1, 10000.0, 0.004, 500.0, 5000.0, 0.0},
                                 kCycle);
  drive.power_on();
  drive.on_nmt(canopen::NmtCommand::start);
  canopen::TxPdoCsp tpdo{};
  std::uint64_t heartbeats = 0;
  std::uint64_t alarm_cycle = 0;
  for (std::uint64_t cycle = 0; cycle < 1000 && alarm_cycle == 0; ++cycle) {
    if (cycle % 100 == 0 && cycle <= 400) {
      ++heartbeats;  // the last one at cycle 400
    }
    AxisNodeInput in = setpoint(0.0);
    in.have_tpdo = cycle > 0;
    in.statusword = tpdo.statusword;
    in.position_counts = tpdo.position_actual;
    in.heartbeats = heartbeats;
    const auto& out = node.cycle(cycle, in);
    drive.on_rpdo(canopen::RxPdoCsp{out.controlword, out.target_counts});
    tpdo = drive.on_sync();
    if (out.new_alarm == AxisAlarm::heartbeat_lost) {
      alarm_cycle = cycle;
      EXPECT_TRUE(out.quick_stop);
      EXPECT_FALSE(out.enabled);
    }
  }
  EXPECT_EQ(alarm_cycle, 551U);
}

TEST(AxisNodeController, ASetpointBeyondTheSoftLimitIsNotFollowed) {
  axisnode::AxisNodeSetup setup{10000.0, kCycle, 5};
  setup.has_soft_limits = true;
  setup.soft_min = -50.0;
  setup.soft_max = 20.0;
  Loop loop;
  loop.node = AxisNodeController(setup);
  loop.enable();
  // Up to the limit at 10 mm/s, as a channel would move it, then one setpoint beyond.
  for (int k = 1; k <= 750; ++k) {  // 12.51 ... 20.00
    ASSERT_EQ(loop.step(setpoint(12.5 + 0.01 * k, 10.0)).new_alarm, AxisAlarm::none) << k;
  }
  const auto& out = loop.step(setpoint(20.01, 10.0));
  EXPECT_EQ(out.new_alarm, AxisAlarm::soft_limit);
  EXPECT_TRUE(out.quick_stop);
  EXPECT_LE(out.cmd, 20.0);  // never commanded
  for (int i = 0; i < 50; ++i) {
    const auto& o = loop.step(setpoint(20.01 + 0.01 * i, 10.0));
    EXPECT_LT(o.cmd, 20.01);  // the quick stop from 10 mm/s ends within 0.01 mm
  }
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::soft_limit);
}

TEST(AxisNodeController, AFollowingErrorAboveItsLimitStopsTheAxis) {
  axisnode::AxisNodeSetup setup{10000.0, kCycle, 5};
  setup.following_error_limit = 0.5;
  Loop loop;
  loop.node = AxisNodeController(setup);
  loop.enable();
  // A step of 0.4 mm is followed; one of 1 mm leaves the drive (4 ms loop) too far behind.
  EXPECT_EQ(loop.step(setpoint(12.9)).new_alarm, AxisAlarm::none);
  for (int i = 0; i < 10; ++i) {
    loop.step(setpoint(12.9));
  }
  const auto& out = loop.step(setpoint(13.9));
  EXPECT_EQ(out.new_alarm, AxisAlarm::following_error);
  EXPECT_TRUE(out.quick_stop);
}

TEST(AxisNodeController, AnOperatorResetClearsADriveFaultAndTheDriveRunsAgain) {
  Loop loop;
  loop.enable();
  for (int i = 0; i < 20; ++i) {
    loop.step(setpoint(12.5 + 0.001 * i, 1.0));
  }
  loop.drive.schedule_fault(drivesim::DriveFault::overcurrent, loop.cycle + 1);  // next SYNC
  AxisAlarm raised = AxisAlarm::none;
  for (int i = 0; i < 10; ++i) {
    const auto& out = loop.step(setpoint(12.52));
    if (out.new_alarm != AxisAlarm::none) {
      raised = out.new_alarm;
    }
  }
  ASSERT_EQ(raised, AxisAlarm::drive_fault);
  ASSERT_EQ(loop.drive.state(), cia402::State::fault);
  // Without a reset the node leaves the fault alone: controlword 0 (disable voltage).
  EXPECT_EQ(loop.step(setpoint(12.52)).controlword, 0x0000);

  loop.node.reset();
  // The controlwords from the reset on: fault reset (bit 7 rising), then the enable sequence
  // of CiA 402: shutdown, switch on, enable operation.
  std::vector<std::uint16_t> controlwords;
  for (int i = 0; i < 10; ++i) {
    const auto& out = loop.step(setpoint(12.52));
    if (controlwords.empty() || controlwords.back() != out.controlword) {
      controlwords.push_back(out.controlword);
    }
    EXPECT_EQ(out.new_alarm, AxisAlarm::none);
  }
  EXPECT_EQ(controlwords, (std::vector<std::uint16_t>{0x0080, 0x0006, 0x0007, 0x000F}));
  EXPECT_EQ(loop.drive.state(), cia402::State::operation_enabled);
  EXPECT_TRUE(loop.node.output().enabled);
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::none);
  EXPECT_FALSE(loop.node.output().quick_stop);
  // It follows again, from where the drive stood.
  for (int i = 0; i < 400; ++i) {
    loop.step(setpoint(15.0));
  }
  EXPECT_NEAR(loop.drive.position(), 15.0, 1e-6);
}

TEST(AxisNodeController, AFaultThatStaysIsAlarmedAgainAfterTheResetTime) {
  axisnode::AxisNodeSetup setup{10000.0, kCycle, 5};
  setup.fault_reset_cycles = 20;
  AxisNodeController node(setup);
  AxisNodeInput faulted;
  faulted.have_tpdo = true;
  faulted.have_setpoint = true;
  faulted.statusword = cia402::encode_statusword(cia402::State::fault, false);
  EXPECT_EQ(node.cycle(0, faulted).new_alarm, AxisAlarm::drive_fault);
  node.reset();
  std::uint64_t again = 0;
  for (std::uint64_t c = 1; c < 100 && again == 0; ++c) {
    const auto& out = node.cycle(c, faulted);
    if (out.new_alarm == AxisAlarm::drive_fault) {
      again = c;
    }
    if (c == 1) {
      EXPECT_EQ(out.controlword, 0x0080);
    }
  }
  EXPECT_EQ(again, 21U);
}

TEST(AxisNodeController, AResetWithTheHeartbeatStillSilentIsAlarmedAgain) {
  AxisNodeController node(axisnode::AxisNodeSetup{10000.0, kCycle, 5, 150});
  AxisNodeInput in;
  in.have_tpdo = true;
  in.statusword = cia402::encode_statusword(cia402::State::operation_enabled, false);
  in.heartbeats = 1;
  std::uint64_t lost = 0;
  for (std::uint64_t c = 0; c < 400 && lost == 0; ++c) {
    if (node.cycle(c, in).new_alarm == AxisAlarm::heartbeat_lost) {
      lost = c;
    }
  }
  ASSERT_EQ(lost, 151U);
  node.reset();
  std::uint64_t again = 0;
  for (std::uint64_t c = 300; c < 800 && again == 0; ++c) {
    const auto& out = node.cycle(c, in);
    if (c == 300) {
      EXPECT_EQ(out.alarm, AxisAlarm::none);
    }
    if (out.new_alarm == AxisAlarm::heartbeat_lost) {
      again = c;
    }
  }
  EXPECT_EQ(again, 451U);
}

TEST(AxisNodeController, AResetDuringAQuickStopWaitsUntilTheDriveHasStopped) {
  // An owner loss at 200 mm/s: quick stop on the drive's 5000 mm/s^2 ramp. The operator resets
  // at once; the node must not re-enable the drive while it still brakes.
  Loop loop(/*deadline=*/5, 0.0);
  loop.enable();
  double target = 0.0;
  for (int i = 0; i < 300; ++i) {
    target += 0.2;  // 200 mm/s
    loop.step(setpoint(target, 200.0));
  }
  AxisNodeInput lost = setpoint(target, 200.0);
  lost.owner_lost = true;
  ASSERT_EQ(loop.step(lost).new_alarm, AxisAlarm::owner_lost);
  loop.node.reset();
  double v_before = loop.drive.velocity();
  double hardest = 0.0;
  double speed_at_enable = -1.0;  // the drive's speed when the node first asks to re-enable
  for (int i = 0; i < 200; ++i) {
    AxisNodeInput hold;
    hold.have_setpoint = true;
    const double speed = std::abs(loop.drive.velocity());
    const auto& out = loop.step(hold);
    if (out.controlword == 0x000F && speed_at_enable < 0.0) {
      speed_at_enable = speed;
    }
    hardest = std::max(hardest, (v_before - loop.drive.velocity()) / kCycle);
    v_before = loop.drive.velocity();
  }
  EXPECT_EQ(speed_at_enable, 0.0);
  EXPECT_LE(hardest, 5000.0 * 1.1);         // the quick-stop ramp, not the torque limit
  EXPECT_TRUE(loop.node.output().enabled);  // and afterwards back in operation
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::none);
}

TEST(AxisNodeController, ADriveThatFaultsAgainAfterTheResetIsAlarmedWithOneFaultReset) {
  Loop loop;
  loop.enable();
  loop.drive.schedule_fault(drivesim::DriveFault::overcurrent, loop.cycle + 1);
  for (int i = 0; i < 10; ++i) {
    loop.step(setpoint(12.5));
  }
  ASSERT_EQ(loop.node.output().alarm, AxisAlarm::drive_fault);
  loop.node.reset();
  int resets = 0;
  std::uint16_t previous = 0;
  AxisAlarm again = AxisAlarm::none;
  for (int i = 0; i < 150; ++i) {
    if (i == 2) {
      loop.drive.schedule_fault(drivesim::DriveFault::overcurrent, loop.cycle + 1);
    }
    const auto& out = loop.step(setpoint(12.5));
    resets += (out.controlword & 0x0080) != 0 && (previous & 0x0080) == 0 ? 1 : 0;
    previous = out.controlword;
    if (out.new_alarm != AxisAlarm::none) {
      again = out.new_alarm;
    }
  }
  EXPECT_EQ(resets, 1);  // the operator's one, not one per fault
  EXPECT_EQ(again, AxisAlarm::drive_fault);
}

TEST(AxisNodeController, APositionActualValueThatWrapsIsCountedOn) {
  // 32-bit counts: from just below 2^31 on, the position goes on, and so does the target.
  axisnode::AxisNodeSetup setup{1000.0, kCycle, 5};
  AxisNodeController node(setup);
  AxisNodeInput in;
  in.have_tpdo = true;
  in.statusword = cia402::encode_statusword(cia402::State::operation_enabled, false);
  in.position_counts = 2147483000;
  node.cycle(1, in);
  in.position_counts = static_cast<std::int32_t>(2147483000U + 2000U);  // wrapped
  const auto& out = node.cycle(2, in);
  EXPECT_NEAR(out.act, 2147485.0, 1e-9);
  EXPECT_NEAR(out.vel, 2000.0, 1e-6);        // degrees per second, no jump
  EXPECT_EQ(out.target_counts, 2147483000);  // held where it took over
  in.have_setpoint = true;
  in.setpoint_valid = true;
  in.setpoint_pos = 2147485.5;
  in.position_counts = static_cast<std::int32_t>(2147483000U + 2500U);
  EXPECT_EQ(node.cycle(3, in).target_counts, static_cast<std::int32_t>(2147483000U + 2500U));
  EXPECT_EQ(node.output().alarm, AxisAlarm::none);
}

TEST(AxisNodeController, HomingCountsOnlyAfterItsOwnStartAndAHomingErrorIsAnAlarm) {
  axisnode::AxisNodeSetup setup{10000.0, kCycle, 5};
  setup.homing = true;
  AxisNodeController node(setup);
  const std::uint16_t operating = cia402::encode_statusword(cia402::State::operation_enabled, true);
  AxisNodeInput in;
  in.have_tpdo = true;
  in.mode_display = axisnode::kModeHoming;
  // A drive that still says "homing attained" from before: not homed by this node.
  in.statusword = static_cast<std::uint16_t>(operating | 0x1000U);
  in.position_counts = 123;
  const auto& first = node.cycle(1, in);
  EXPECT_FALSE(first.homed);
  EXPECT_EQ(first.controlword & 0x0010U, 0U);  // bit 4 not yet up: the edge comes next
  EXPECT_EQ(node.cycle(2, in).controlword & 0x0010U, 0x0010U);
  EXPECT_FALSE(node.output().homed);
  // Now the drive reports a homing error (bit 13): alarm 2010, never enabled.
  in.statusword = static_cast<std::uint16_t>(operating | 0x2000U);
  EXPECT_EQ(node.cycle(3, in).new_alarm, AxisAlarm::homing_failed);
  EXPECT_FALSE(node.output().enabled);
  EXPECT_FALSE(node.output().homed);
}

TEST(AxisNodeController, AHomingThatDoesNotEndInTimeIsAnAlarm) {
  axisnode::AxisNodeSetup setup{10000.0, kCycle, 5};
  setup.homing = true;
  setup.homing_timeout_cycles = 50;
  AxisNodeController node(setup);
  AxisNodeInput in;
  in.have_tpdo = true;
  in.mode_display = axisnode::kModeHoming;
  in.statusword = cia402::encode_statusword(cia402::State::operation_enabled, false);
  std::uint64_t alarm_at = 0;
  for (std::uint64_t c = 1; c < 200 && alarm_at == 0; ++c) {
    if (node.cycle(c, in).new_alarm == AxisAlarm::homing_failed) {
      alarm_at = c;
    }
  }
  EXPECT_EQ(alarm_at, 51U);
}

// Issue 25: a SYNC the SYNC producer did not send (another producer on the bus) is alarm 2011
// and a quick stop, raised once.
TEST(AxisNodeController, ASyncOfAnotherProducerIsAnAlarmAndQuickStop) {
  Loop loop;
  loop.enable();
  AxisNodeInput in = setpoint(12.5);
  EXPECT_EQ(loop.step(in).new_alarm, AxisAlarm::none);
  in.foreign_syncs = 1;
  const auto& out = loop.step(in);
  EXPECT_EQ(out.new_alarm, AxisAlarm::foreign_sync);
  EXPECT_TRUE(out.quick_stop);
  EXPECT_EQ(axisnode::kAlarmBase + static_cast<int>(out.alarm), 2011);
  in.foreign_syncs = 40;
  EXPECT_EQ(loop.step(in).new_alarm, AxisAlarm::none) << "raised once";
}

// Stopping is safe: a drive moving at feed is not ready to be disabled until its quick stop
// has brought it to rest (statusword "halted"); then it is.
TEST(AxisNodeController, AMovingDriveIsReadyToDisableOnlyOnceItsQuickStopHalted) {
  Loop loop;
  loop.enable();
  for (int i = 0; i < 100; ++i) {
    loop.step(setpoint(12.5 + 0.1 * i, 100.0));  // 100 mm/s
  }
  ASSERT_FALSE(loop.node.ready_to_disable()) << "in operation";
  AxisNodeInput estop;
  estop.emergency_stop = true;
  int cycles = 0;
  while (!loop.node.ready_to_disable() && cycles < 1000) {
    loop.step(estop);
    ++cycles;
    if (!loop.node.ready_to_disable()) {
      EXPECT_NE(loop.drive.state(), cia402::State::switch_on_disabled);
    }
  }
  // 100 mm/s at the drive's 5000 mm/s^2 takes 20 cycles to stop, and a few for the frames.
  EXPECT_GE(cycles, 20);
  ASSERT_TRUE(loop.node.ready_to_disable());
  EXPECT_EQ(loop.drive.state(), cia402::State::quick_stop_active);
  const double at_rest = loop.drive.position();
  loop.step(estop);
  EXPECT_DOUBLE_EQ(loop.drive.position(), at_rest);
}
