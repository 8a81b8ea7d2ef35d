// The axis node's core as the machine drives it, without DDS or a bus: candidates' setpoints and
// events in, the lockstep rule, who owns the axis (G140-G142), which setpoint wins while a
// coupling (G114.1, G51.4) holds, and what the trace is told, in order. The drive is the
// simulator's, stepped once a cycle.
#include "axisnode/node/axis_node.hpp"
#include "axisnode/drivesim/simulated_drive.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

using namespace mcnc;
using axisnode::AxisNode;
using axisnode::AxisNodeEvent;
using axisnode::AxisNodeHappening;
using axisnode::AxisNodeRoles;
using axisnode::SetpointSample;
using Happening = AxisNodeHappening::Kind;

namespace {

constexpr double kCycle = 0.001;

AxisNode::WriterId writer(std::uint8_t n) {
  AxisNode::WriterId w{};
  w[0] = n;
  return w;
}

// Axis 1 of channel 1, which channel 2 may acquire (G141).
AxisNodeRoles exchanged_axis() {
  AxisNodeRoles r;
  r.axis = 1;
  r.home = 1;
  r.candidates = {1, 2};
  r.exchangeable = true;
  r.in_position = 0.01;
  r.cycle_s = kCycle;
  r.controller = axisnode::AxisNodeSetup{10000.0, kCycle, 5};
  return r;
}

SetpointSample at(std::uint64_t cycle, double pos, bool valid = true) {
  return SetpointSample{cycle, pos, 0.0, 0.0, valid, false};
}

AxisNodeEvent request(std::uint32_t channel, std::uint64_t seq, std::uint64_t cycle,
                      ownership::OwnershipRequestKind kind, bool force = false) {
  AxisNodeEvent e;
  e.kind = AxisNodeEvent::Kind::axis_request;
  e.channel = channel;
  e.seq = seq;
  e.cycle = cycle;
  e.axis = 1;
  e.request = kind;
  e.force = force;
  return e;
}

// The core with its drive: each cycle takes the inputs, steps the controller, sends the RPDO
// and steps the drive; its TPDO comes back next cycle.
struct Node {
  AxisNode core;
  drivesim::SimulatedDrive drive;
  canopen::TxPdoCsp tpdo{};
  bool have_tpdo = false;
  std::vector<std::vector<AxisNodeHappening>> told;  // per cycle

  explicit Node(const AxisNodeRoles& roles, double start = 5.0)
      : core(roles), drive(drivesim::DriveParams{1, 10000.0, 0.004, 500.0, 5000.0, start}, kCycle) {
    drive.power_on();
    drive.on_nmt(canopen::NmtCommand::start);
  }

  const axisnode::AxisNodeOutput& run(std::uint64_t cycle) {
    core.take_inputs(cycle, true);
    told.emplace_back(core.happenings(), core.happenings() + core.happening_count());
    axisnode::DriveReadings d;
    d.have_tpdo = have_tpdo;
    d.statusword = tpdo.statusword;
    d.position_counts = tpdo.position_actual;
    const auto& out = core.step(cycle, d, false);
    drive.on_rpdo(canopen::RxPdoCsp{out.controlword, out.target_counts});
    tpdo = drive.on_sync();
    have_tpdo = true;
    return out;
  }
};

}  // namespace

TEST(AxisNode, RunsACycleOnlyOnceEveryCandidatesSetpointAndAnnouncedEventsAreIn) {
  AxisNode core(exchanged_axis());
  EXPECT_TRUE(core.ready(0));
  EXPECT_FALSE(core.ready(1));
  core.on_setpoint(1, 1, at(0, 5.0), 0, writer(1));
  EXPECT_FALSE(core.ready(1)) << "channel 2 may acquire the axis: its setpoint is waited for";
  core.on_setpoint(2, 1, at(0, 0.0, false), 1, writer(2));  // announces its event 1
  EXPECT_FALSE(core.ready(1)) << "the event channel 2 announced has not arrived";
  core.on_event(request(2, 1, 0, ownership::OwnershipRequestKind::acquire));
  EXPECT_TRUE(core.ready(1));
  // A setpoint for another axis, or from a channel that may not own this one, counts for nothing.
  core.on_setpoint(1, 2, at(1, 5.0), 0, writer(1));
  core.on_setpoint(3, 1, at(1, 5.0), 0, writer(3));
  EXPECT_FALSE(core.ready(2));
  EXPECT_FALSE(core.hears_from(3));
  EXPECT_TRUE(core.hears_from(2));
}

TEST(AxisNode, AReleaseActsFromTheCycleAfterItWasSentAndTheNewOwnerIsFollowedACycleLater) {
  Node n(exchanged_axis());
  std::uint64_t seq2 = 0;
  std::uint64_t seq1 = 0;
  for (std::uint64_t c = 0; c < 40; ++c) {
    ASSERT_TRUE(n.core.ready(c)) << c;
    n.run(c);
    // Channel 1 holds the axis at 5; at cycle 20 it sends G140, and channel 2 asks (G141) at 21.
    if (c == 20) {
      n.core.on_event(request(1, ++seq1, c, ownership::OwnershipRequestKind::release));
    }
    if (c == 21) {
      n.core.on_event(request(2, ++seq2, c, ownership::OwnershipRequestKind::acquire));
    }
    n.core.on_setpoint(1, 1, at(c, 5.0, c < 20), seq1, writer(1));
    n.core.on_setpoint(2, 1, at(c, 6.0, c > 21), seq2, writer(2));
  }
  EXPECT_EQ(n.core.standing().owner, 2U);
  EXPECT_EQ(n.core.standing().released_by, 1U);
  // Who was told what, and when.
  auto kinds_at = [&](std::size_t c) {
    std::vector<std::pair<Happening, std::uint32_t>> k;
    for (const AxisNodeHappening& h : n.told[c]) {
      k.emplace_back(h.kind, h.channel);
    }
    return k;
  };
  using V = std::vector<std::pair<Happening, std::uint32_t>>;
  EXPECT_EQ(kinds_at(1), (V{{Happening::follows, 1}})) << "channel 1's setpoint 0 at cycle 1";
  EXPECT_EQ(kinds_at(20), V{}) << "cycle 20 runs on channel 1's last valid setpoint, of 19";
  EXPECT_EQ(kinds_at(21), (V{{Happening::owner, 0}, {Happening::follows, 0}}))
      << "released at the cycle after it was sent";
  EXPECT_EQ(kinds_at(22), (V{{Happening::owner, 2}}));
  EXPECT_EQ(kinds_at(23), (V{{Happening::follows, 2}}))
      << "a new owner's setpoint from before it knew is not followed";
  EXPECT_EQ(n.told[22][0].previous, 0U);
  EXPECT_FALSE(n.told[22][0].forced);
  EXPECT_NEAR(n.core.output().cmd, 6.0, 1e-9);
  EXPECT_EQ(n.core.commanding_channel(), 2U);
}

TEST(AxisNode, AForcedAcquireWaitsUntilTheOwnersMoveEnds) {
  Node n(exchanged_axis());
  std::uint64_t seq2 = 0;
  std::uint64_t taken = 0;
  for (std::uint64_t c = 0; c < 200; ++c) {
    n.run(c);
    for (const AxisNodeHappening& h : n.told.back()) {
      if (h.kind == Happening::owner && h.channel == 2) {
        taken = c;
        EXPECT_TRUE(h.forced);
        EXPECT_EQ(h.previous, 1U);
      }
    }
    if (c == 10) {
      n.core.on_event(request(2, ++seq2, c, ownership::OwnershipRequestKind::acquire, true));
    }
    // Channel 1 moves from 5 to 5.1 over cycles 0-99 (0.001 a cycle), then stands.
    const double pos = 5.0 + 0.001 * static_cast<double>(std::min<std::uint64_t>(c, 100));
    SetpointSample sp{c, pos, c < 100 ? 1.0 : 0.0, 0.0, true, false};
    n.core.on_setpoint(1, 1, sp, 0, writer(1));
    n.core.on_setpoint(2, 1, at(c, 0.0, false), seq2, writer(2));
  }
  EXPECT_GT(taken, 100U) << "not in the middle of channel 1's move";
  EXPECT_LT(taken, 110U) << "taken as soon as the axis stands in position";
}

TEST(AxisNode, TheOwnersWriterGoneIsOwnerLostAndNoLongerWaitedFor) {
  AxisNode core(exchanged_axis());
  core.on_setpoint(1, 1, at(0, 5.0), 0, writer(1));
  core.on_setpoint(2, 1, at(0, 0.0, false), 0, writer(2));
  core.take_inputs(1, true);
  EXPECT_FALSE(core.owner_lost());
  core.on_setpoint_writer_gone(writer(9));  // not one of its inputs' writers
  EXPECT_FALSE(core.owner_lost());
  core.on_setpoint(2, 1, at(1, 0.0, false), 0, writer(2));
  EXPECT_FALSE(core.ready(2));
  core.on_setpoint_writer_gone(writer(1));
  EXPECT_TRUE(core.owner_lost());
  EXPECT_TRUE(core.ready(2)) << "a lost input is not waited for";
}

TEST(AxisNode, RequestsBeyondWhatTheNodeKeepsAreCountedNeverSilent) {
  AxisNode core(exchanged_axis());
  for (std::uint64_t k = 1; k <= 300; ++k) {
    core.on_event(request(2, k, 5, ownership::OwnershipRequestKind::acquire));
  }
  EXPECT_EQ(core.requests_dropped(), 300U - 256U);
  // Events of channels that may not own the axis are not its requests.
  AxisNode other(exchanged_axis());
  other.on_event(request(3, 1, 5, ownership::OwnershipRequestKind::acquire));
  other.take_inputs(6, true);
  EXPECT_EQ(other.standing().owner, 1U);
}

TEST(AxisNode, AGantrySlaveWaitsForItsMastersSampleAndCopiesItsIncrements) {
  AxisNodeRoles r = exchanged_axis();
  r.axis = 2;
  r.candidates = {1};
  r.exchangeable = false;
  r.may_follow = true;
  r.leaders = {1};
  r.power_on_master = 1;
  Node n(r, 3.0);
  EXPECT_EQ(n.core.standing().coupled_to, 1U);
  for (std::uint64_t c = 0; c < 60; ++c) {
    ASSERT_TRUE(n.core.ready(c)) << c;
    n.run(c);
    n.core.on_setpoint(1, 2, at(c, 0.0, false), 0, writer(1));
    EXPECT_FALSE(n.core.ready(c + 1)) << "the master's sample of this cycle is waited for";
    // The master stands at 10 until cycle 30, then moves 0.002 a cycle.
    const double master = 10.0 + (c > 30 ? 0.002 * static_cast<double>(c - 30) : 0.0);
    n.core.on_leader_feedback(1, c, master, true, writer(7));
  }
  // From where both stood, the slave moved as much as its master: at its cycle 59 the master
  // stands at its sample of 58 plus one cycle at the speed between 57 and 58, 29 steps of 0.002.
  EXPECT_NEAR(n.core.output().cmd - 3.0, 0.002 * 29, 1e-9);
  EXPECT_TRUE(n.core.standing().coupling_locked);
  // Its master's node gone: nothing of it is waited for any more.
  n.core.on_setpoint(1, 2, at(60, 0.0, false), 0, writer(1));
  EXPECT_FALSE(n.core.ready(61 + 1));
  n.core.on_leader_gone(writer(7));
  n.core.on_setpoint(1, 2, at(61, 0.0, false), 0, writer(1));
  EXPECT_TRUE(n.core.ready(62));
}

TEST(AxisNode, ASlaveSpindleCouplesAtTheCycleAfterG1141ForItsOwnGroupOnly) {
  AxisNodeRoles r = exchanged_axis();
  r.axis = 4;
  r.home = 2;
  r.candidates = {2, 1};
  r.sync_group = 1;
  r.sync_master = 3;
  r.sync_channel = 1;
  r.spindle_coupling = coupling::SpindleCouplingSetup{kCycle, 3600.0, 0.05, 1.0};
  AxisNode core(r);
  core.on_setpoint(2, 4, at(0, 0.0), 0, writer(2));
  core.on_setpoint(1, 4, at(0, 0.0, false), 0, writer(1));
  EXPECT_FALSE(core.ready(1)) << "the coupling channel's status and the master are waited for";
  core.on_sync_channel_status(1, 0, 1, writer(1));
  core.on_master_feedback(3, 0, 90.0, 0.0, 90.0, writer(3));
  EXPECT_FALSE(core.ready(1)) << "the coupling channel announced an event";
  AxisNodeEvent e;
  e.kind = AxisNodeEvent::Kind::spindle_sync;
  e.channel = 1;
  e.seq = 1;
  e.cycle = 0;
  e.sync_on = true;
  e.sync_group = 1;
  e.spindle = coupling::SpindleCouplingCommand{1, -1, 30.0};
  core.on_event(e);
  e.sync_group = 2;  // another group's coupling is not this spindle's
  core.on_event(e);
  ASSERT_TRUE(core.ready(1));
  core.take_inputs(1, true);
  ASSERT_EQ(core.happening_count(), 2U);
  EXPECT_EQ(core.happenings()[0].kind, Happening::spindle_coupled);
  EXPECT_EQ(core.happenings()[1].kind, Happening::follows) << "the coupling is followed";
  EXPECT_EQ(core.happenings()[1].channel, 2U);
  EXPECT_EQ(core.happenings()[0].master, 3U);
  EXPECT_EQ(core.happenings()[0].spindle.q, -1);
  EXPECT_DOUBLE_EQ(core.happenings()[0].spindle.r, 30.0);
  EXPECT_EQ(core.standing().coupled_to, 3U);
}

// G51.8 (spec dafeng §2.6.7): X of channel 1 is the cam's slave, S1 (axis 3) its master. The
// node adds the lift at S1's angle to the channel's setpoint from the cycle after the event,
// reaching it within its limits, and G50.8 takes it off again.
namespace {

// Axis 1 of channel 1, laid over by a coupling that channel 1 commands to the spindle axis 3
// (G51.8's cam, G81.4's gear box).
AxisNodeRoles over_spindle_3() {
  AxisNodeRoles r;
  r.axis = 1;
  r.home = 1;
  r.candidates = {1};
  r.in_position = 0.01;
  r.cycle_s = kCycle;
  r.controller = axisnode::AxisNodeSetup{10000.0, kCycle, 5};
  r.sync_master = 3;
  r.sync_channel = 1;
  return r;
}

}  // namespace

TEST(AxisNode, ACamSlaveAddsTheLiftAtItsMastersAngleToTheChannelsSetpointUntilG508) {
  AxisNodeRoles r = over_spindle_3();
  r.cam = true;
  r.cam_coupling = coupling::CamCouplingSetup{kCycle, 100.0, 1000.0};
  Node n(r);
  const std::array<double, 4> table{0.0, 1.0, 3.0, 2.0};
  std::uint64_t seq = 0;
  double angle = 90.0;  // the table's second point: a lift of 1
  double last_cmd = 5.0;
  double last_vel = 0.0;
  std::uint64_t coupled_at = 0;
  std::uint64_t decoupled_at = 0;
  for (std::uint64_t c = 0; c < 1500; ++c) {
    if (c == 10 || c == 1000) {
      AxisNodeEvent e;
      e.kind = AxisNodeEvent::Kind::cam_sync;
      e.channel = 1;
      e.seq = ++seq;
      e.cycle = c;
      e.sync_on = c == 10;
      e.cam = coupling::cam_profile_of(0, 0.0, 0.0, 0.0, table);
      n.core.on_event(e);
    }
    n.core.on_setpoint(1, 1, at(c, 5.0), seq, writer(1));
    n.core.on_sync_channel_status(1, c, seq, writer(1));
    angle = c == 600 ? 180.0 : angle;  // the master turns on to the third point: a lift of 3
    n.core.on_master_feedback(3, c, angle, 0.0, angle, writer(3));
    ASSERT_TRUE(n.core.ready(c + 1)) << c;
    const double cmd = n.run(c + 1).cmd;
    for (std::size_t k = 0; k < n.core.happening_count(); ++k) {
      coupled_at = n.core.happenings()[k].kind == Happening::cam_coupled ? c + 1 : coupled_at;
      decoupled_at = n.core.happenings()[k].kind == Happening::cam_decoupled ? c + 1 : decoupled_at;
    }
    if (c > 200) {  // enabled: the lift moves within 100 units/s and 1000 units/s^2
      const double vel = (cmd - last_cmd) / kCycle;
      ASSERT_LE(std::fabs(vel), 100.0 + 1e-6) << c;
      ASSERT_LE(std::fabs(vel - last_vel), 1000.0 * kCycle + 1e-6) << c;
      last_vel = vel;
    }
    last_cmd = cmd;
    if (c == 599) {
      EXPECT_NEAR(cmd, 6.0, 1e-9);
      EXPECT_EQ(n.core.superimposed(), 1.0);
      EXPECT_EQ(n.core.standing().coupled_to, 3U);
      EXPECT_TRUE(n.core.standing().coupling_locked);
    }
    if (c == 999) {
      EXPECT_NEAR(cmd, 8.0, 1e-9);
    }
  }
  EXPECT_EQ(coupled_at, 11U);  // the cycle after the event
  EXPECT_GT(decoupled_at, 1001U);
  EXPECT_NEAR(last_cmd, 5.0, 1e-9);
  EXPECT_EQ(n.core.superimposed(), 0.0);
  EXPECT_EQ(n.core.standing().coupled_to, 0U);
}

// G51.2 with a rotary servo axis as the polygon axis (param 5311, decision 157): axis 1 of
// channel 1 follows S1 (axis 3) at Q/P = 2 in CSP while the channel sends it no valid
// setpoint, G50.2 slows it to rest within its acceleration, and it then holds where it stands
// until the channel commands it there.
TEST(AxisNode, AServoPolygonAxisFollowsItsMasterInsteadOfTheChannelAndStandsWhereG502LeftIt) {
  AxisNodeRoles r = over_spindle_3();
  r.polygon = true;
  r.spindle_coupling = coupling::SpindleCouplingSetup{kCycle, 3600.0, 0.05, 1.0};
  Node n(r);
  std::uint64_t seq = 0;
  double master = 0.0;
  const double master_vel = 360.0;  // deg/s: the slave turns at 720 deg/s
  double last_cmd = 5.0;
  double stood = 0.0;
  std::uint64_t coupled_at = 0;
  std::uint64_t locked_at = 0;
  std::uint64_t decoupled_at = 0;
  for (std::uint64_t c = 0; c < 2800; ++c) {
    if (c == 300 || c == 1600) {
      AxisNodeEvent e;
      e.kind = AxisNodeEvent::Kind::polygon_sync;
      e.channel = 1;
      e.seq = ++seq;
      e.cycle = c;
      e.sync_on = c == 300;
      e.spindle = coupling::SpindleCouplingCommand{1, 2, 0.0};
      n.core.on_event(e);
    }
    // The channel holds C (its slot follows) from G51.2 until it takes it back at 2300.
    const bool valid = c < 300 || c >= 2300;
    n.core.on_setpoint(1, 1, at(c, c >= 2300 ? stood : 5.0, valid), seq, writer(1));
    n.core.on_sync_channel_status(1, c, seq, writer(1));
    n.core.on_master_feedback(3, c, master, master_vel, master, writer(3));
    master += master_vel * kCycle;
    ASSERT_TRUE(n.core.ready(c + 1)) << c;
    const auto& out = n.run(c + 1);
    for (std::size_t k = 0; k < n.core.happening_count(); ++k) {
      coupled_at = n.core.happenings()[k].kind == Happening::polygon_coupled ? c + 1 : coupled_at;
      decoupled_at =
          n.core.happenings()[k].kind == Happening::polygon_decoupled ? c + 1 : decoupled_at;
    }
    EXPECT_EQ(out.mode, axisnode::kModeCsp) << c;  // a servo axis: positions, never a speed
    locked_at = locked_at == 0 && n.core.standing().coupling_locked ? c + 1 : locked_at;
    if (locked_at != 0 && c > locked_at &&
        c < 1600) {  // locked: twice the master's angle of this cycle
      const double off = std::remainder(out.cmd - 2.0 * master, 360.0);
      ASSERT_NEAR(off, 0.0, 1e-6) << c;
      EXPECT_EQ(n.core.standing().coupled_to, 3U);
      EXPECT_TRUE(n.core.standing().coupling_locked);
    }
    if (c == 2299) {
      stood = out.cmd;
      EXPECT_EQ(n.core.standing().coupled_to, 0U);
    }
    if (c > 1900) {
      ASSERT_EQ(out.cmd, last_cmd) << c;  // stands, held, then commanded where it stands
    }
    last_cmd = out.cmd;
  }
  EXPECT_EQ(coupled_at, 301U);
  EXPECT_GT(locked_at, 500U);  // 0.2 s to reach 720 deg/s, then the phase
  EXPECT_LT(locked_at, 1500U);
  // From 720 deg/s to rest within 3600 deg/s^2: 0.2 s.
  EXPECT_NEAR(static_cast<double>(decoupled_at - 1601) * kCycle, 0.2, 0.01);
  EXPECT_GT(stood, 5.0 + 360.0);
}

namespace {

// G81.4 (spec dafeng §2.6.11): axis 1 of channel 1 is the gear box's work axis, the tool
// spindle S1 is axis 3 and the axial axis Z axis 2. The channel commands the work axis at 5.
AxisNodeRoles work_axis() {
  AxisNodeRoles r = over_spindle_3();
  r.egb = true;
  r.egb_axial = 2;
  r.leaders = {2};
  r.gear_box = coupling::GearBoxSetup{kCycle, 3600.0, 0.4, 0.05, 1.0, 0.0, 0.1};
  return r;
}

AxisNodeEvent egb_event(std::uint64_t seq, std::uint64_t cycle, bool on,
                        AxisNodeEvent::EgbOff off = AxisNodeEvent::EgbOff::stop) {
  AxisNodeEvent e;
  e.kind = AxisNodeEvent::Kind::egb_sync;
  e.channel = 1;
  e.seq = seq;
  e.cycle = cycle;
  e.sync_on = on;
  e.egb = coupling::GearBoxCommand{20, 1, 15.0, 2.0, true, 0.0};  // T20 L1 P15 Q2 R0
  e.egb_off = off;
  return e;
}

double off_period(double degrees, double period) {
  return std::fabs(degrees - period * std::round(degrees / period));
}

}  // namespace

// The work axis turns 1/20 of the tool spindle (1800 deg/s) in the phase R0 plus the helical
// angle of Z's travel, over the channel's setpoint; G80.4 stops it within 0.4 s where it
// reached, and it stays there until the channel commands that angle (absorb).
TEST(AxisNode, TheGearBoxsWorkAxisTurnsLOverTOfTheToolPlusTheHelixUntilG804AndTheChannelTakesIt) {
  Node n(work_axis());
  const double helix =
      std::sin(15.0 * std::numbers::pi / 180.0) / (std::numbers::pi * 40.0) * 360.0;
  // Z stands at 5, then from cycle 1000 speeds up to 10 mm/s in 20 ms (500 mm/s^2).
  const auto z_at = [](std::uint64_t c) {
    const double t = c < 1000 ? 0.0 : double(c - 1000) * kCycle;
    return t < 0.02 ? 5.0 - 250.0 * t * t : 5.0 - 0.1 - 10.0 * (t - 0.02);
  };
  std::uint64_t seq = 0;
  double channel = 5.0;  // where the channel commands the work axis
  double last_cmd = 5.0;
  std::uint64_t coupled_at = 0;
  std::uint64_t stopped_at = 0;
  std::uint64_t absorbed_at = 0;
  for (std::uint64_t c = 0; c < 2600; ++c) {
    if (c == 300 || c == 1500) {
      n.core.on_event(egb_event(++seq, c, c == 300));
    }
    if (c == 2200) {
      channel = last_cmd;  // the channel takes the angle, and tells the node in the same cycle
      n.core.on_event(egb_event(++seq, c, false, AxisNodeEvent::EgbOff::absorb));
    }
    n.core.on_setpoint(1, 1, at(c, channel), seq, writer(1));
    n.core.on_sync_channel_status(1, c, seq, writer(1));
    n.core.on_master_feedback(3, c, 1.8 * double(c), 1800.0, 1.8 * double(c), writer(3));
    if (c == 700) {
      EXPECT_FALSE(n.core.ready(c + 1)) << "the axial axis's sample is an input of the gear box";
    }
    n.core.on_leader_feedback(2, c, z_at(c), true, writer(2));
    ASSERT_TRUE(n.core.ready(c + 1)) << c;
    const double cmd = n.run(c + 1).cmd;
    for (const AxisNodeHappening& h : n.told.back()) {
      coupled_at = h.kind == Happening::egb_coupled ? c + 1 : coupled_at;
      absorbed_at = h.kind == Happening::egb_absorbed ? c + 1 : absorbed_at;
      if (h.kind == Happening::egb_stopped) {
        stopped_at = c + 1;
        EXPECT_EQ(h.egb_stop, AxisNodeHappening::EgbStop::program);
        EXPECT_NEAR(h.at, cmd - 5.0, 1e-9);
      }
    }
    // Locked: on the ratio, in phase, with the helical term (while Z speeds up, the node's
    // estimate of Z, extrapolated from the cycle before, is off by its acceleration's share).
    if (c >= 800 && c < 1500) {
      const double tool = 1.8 * double(c + 1);
      // R0: the work axis's angle, setpoint and offset together, is the tool's 1/20 + R.
      const double off = off_period(cmd - tool / 20.0 - (z_at(c + 1) - 5.0) * helix, 18.0);
      ASSERT_LT(off, c >= 999 && c < 1021 ? 1e-3 : 1e-9) << c;
      ASSERT_TRUE(n.core.standing().coupling_locked) << c;
      ASSERT_EQ(n.core.standing().coupled_to, 3U);
    }
    if (stopped_at != 0 && c + 1 > stopped_at) {
      ASSERT_NEAR(cmd, last_cmd, 1e-12) << "it stands where it reached, cycle " << c;
    }
    last_cmd = cmd;
  }
  EXPECT_EQ(coupled_at, 301U);  // the cycle after the event
  EXPECT_GT(stopped_at, 1501U);
  EXPECT_LE(stopped_at, 1501U + 400U + 1U);  // within the stop time
  EXPECT_EQ(absorbed_at, 2201U);
  EXPECT_EQ(n.core.superimposed(), 0.0);
  EXPECT_EQ(n.core.standing().coupled_to, 0U);
  EXPECT_NE(last_cmd, 5.0);
}

// The tool spindle's node gone: the work axis stops as for G80.4 and stands there.
TEST(AxisNode, TheGearBoxsWorkAxisStopsWhenTheToolSpindleIsLost) {
  AxisNodeRoles r = work_axis();
  r.egb_axial = 0;
  r.leaders = {};
  Node n(r);
  std::uint64_t stopped_at = 0;
  AxisNodeHappening::EgbStop why{};
  double last_cmd = 5.0;
  for (std::uint64_t c = 0; c < 1500; ++c) {
    if (c == 300) {
      AxisNodeEvent e = egb_event(1, c, true);
      e.egb = coupling::GearBoxCommand{20, 1, 0.0, 0.0, true, 0.0};
      n.core.on_event(e);
    }
    const std::uint64_t seq = c < 300 ? 0 : 1;
    n.core.on_setpoint(1, 1, at(c, 5.0), seq, writer(1));
    n.core.on_sync_channel_status(1, c, seq, writer(1));
    if (c < 800) {
      n.core.on_master_feedback(3, c, 1.8 * double(c), 1800.0, 1.8 * double(c), writer(3));
    } else if (c == 800) {
      n.core.on_master_gone(writer(3));
    }
    ASSERT_TRUE(n.core.ready(c + 1)) << c;
    const double cmd = n.run(c + 1).cmd;
    for (const AxisNodeHappening& h : n.told.back()) {
      if (h.kind == Happening::egb_stopped) {
        stopped_at = c + 1;
        why = h.egb_stop;
      }
    }
    if (c > 810) {  // slowing down evenly from 90 deg/s, never faster
      ASSERT_LE(std::fabs(cmd - last_cmd) / kCycle, 90.0 + 1e-6) << c;
    }
    last_cmd = cmd;
  }
  EXPECT_GT(stopped_at, 801U);
  EXPECT_LE(stopped_at, 801U + 400U + 1U);
  EXPECT_EQ(why, AxisNodeHappening::EgbStop::tool_lost);
  EXPECT_EQ(n.core.standing().coupled_to, 0U);
  EXPECT_NEAR(n.core.superimposed(), last_cmd - 5.0, 1e-9);
}

// A reset (param 5320.4): at_once stops the work axis within the stop time; when_tool_stops
// keeps the gear while the tool spindle turns and lets go once it stands.
TEST(AxisNode, AResetStopsTheGearBoxAtOnceOrOnceTheToolSpindleStands) {
  for (const bool at_once : {true, false}) {
    AxisNodeRoles r = work_axis();
    r.egb_axial = 0;
    r.leaders = {};
    r.egb_reset_at_once = at_once;
    Node n(r);
    std::uint64_t stopped_at = 0;
    AxisNodeHappening::EgbStop why{};
    double tool = 0.0;
    for (std::uint64_t c = 0; c < 2000; ++c) {
      if (c == 300 || c == 800) {
        AxisNodeEvent e = egb_event(c == 300 ? 1 : 2, c, c == 300, AxisNodeEvent::EgbOff::reset);
        e.egb = coupling::GearBoxCommand{20, 1, 0.0, 0.0, true, 0.0};
        n.core.on_event(e);
      }
      const std::uint64_t seq = c < 300 ? 0 : c < 800 ? 1 : 2;
      // The channel holds the work axis from its reset on.
      n.core.on_setpoint(1, 1, at(c, 5.0, c < 800), seq, writer(1));
      n.core.on_sync_channel_status(1, c, seq, writer(1));
      const double vel = c < 1200 ? 1800.0 : 0.0;  // the tool spindle stops at 1200
      tool += vel * kCycle;
      n.core.on_master_feedback(3, c, tool, vel, tool, writer(3));
      ASSERT_TRUE(n.core.ready(c + 1)) << c;
      (void)n.run(c + 1);
      for (const AxisNodeHappening& h : n.told.back()) {
        if (h.kind == Happening::egb_stopped) {
          stopped_at = c + 1;
          why = h.egb_stop;
        }
      }
      if (!at_once && c > 800 && c < 1200) {
        ASSERT_EQ(n.core.standing().coupled_to, 3U) << "still geared while the tool turns, " << c;
      }
    }
    EXPECT_EQ(why, AxisNodeHappening::EgbStop::reset);
    if (at_once) {
      EXPECT_GT(stopped_at, 801U);
      EXPECT_LE(stopped_at, 801U + 400U + 1U);
    } else {
      EXPECT_GT(stopped_at, 1201U);
    }
    EXPECT_EQ(n.core.standing().coupled_to, 0U);
  }
}

// G10 L14 P10: the owner's setpoint in torque mode reaches the controller, which asks the drive
// for CST with the torque (per mille) and the speed limit; back in position mode it asks for
// CSP. A node whose axis has no torque mode stays in CSP whatever the setpoint says.
TEST(AxisNode, TheOwnersTorqueModeGoesToTheDriveOnlyWhereTheAxisHasIt) {
  for (const bool has_torque_mode : {true, false}) {
    AxisNodeRoles roles = exchanged_axis();
    roles.candidates = {1};
    roles.exchangeable = false;
    roles.controller.torque_skip = true;
    roles.controller.torque_mode = has_torque_mode;
    Node node(roles);
    std::uint64_t cycle = 1;
    for (; cycle < 200; ++cycle) {
      node.core.on_setpoint(1, 1, at(cycle - 1, 5.0), 0, writer(1));
      node.run(cycle);
    }
    ASSERT_TRUE(node.core.output().enabled);
    SetpointSample torque = at(cycle - 1, 5.0);
    torque.torque_mode = true;
    torque.torque = -50.0;
    torque.torque_speed = 30.0;
    node.core.on_setpoint(1, 1, torque, 0, writer(1));
    const axisnode::AxisNodeOutput& pushed = node.run(cycle++);
    EXPECT_EQ(pushed.mode, has_torque_mode ? axisnode::kModeCst : axisnode::kModeCsp);
    EXPECT_EQ(pushed.target_torque, has_torque_mode ? -500 : 0);
    EXPECT_EQ(pushed.max_motor_speed, has_torque_mode ? 30U : 0U);
    node.core.on_setpoint(1, 1, at(cycle - 1, 5.0), 0, writer(1));
    const axisnode::AxisNodeOutput& back = node.run(cycle++);
    EXPECT_EQ(back.mode, axisnode::kModeCsp);
    EXPECT_EQ(back.target_torque, 0);
  }
}
