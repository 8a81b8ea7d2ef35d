// A spindle drive switching modes in operation, frame by frame: the master maps the spindle's
// PDOs by SDO (canopen::spindle_pdos), then the modes of operation travel in RPDO1 (0x6060) and
// come back in TPDO1 (0x6061); the target velocity in RPDO2 (0x60FF). The simulator reads each
// RPDO by its mapping; a frame of another length is not processed.
#include "axisnode/control/axis_node_controller.hpp"
#include "axisnode/drivesim/drive_bus_simulator.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/frames.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <optional>
#include <vector>

namespace mcnc::drivesim {
namespace {

using canopen::CanFrame;
using cia402::State;

constexpr double kCycle = 0.001;
constexpr std::uint8_t kNode = 3;

DriveParams spindle_params() {
  DriveParams p;
  p.node_id = kNode;
  p.counts_per_unit = 1000.0;  // per degree
  p.max_velocity = 30000.0;    // deg/s (5000 rpm)
  p.quick_stop_decel = 20000.0;
  p.units_per_rev = 360.0;  // direct drive
  return p;
}

TEST(SpindleFrames, RpdosAndTpdoCarryTheModes) {
  const canopen::RxPdoSpindle pdo{0x000F, -123456, 9, 3600000};
  const CanFrame r1 = canopen::encode_rpdo1_spindle(kNode, pdo);
  EXPECT_EQ(r1.id, 0x203U);
  ASSERT_EQ(r1.dlc, 7);
  EXPECT_EQ((std::array<std::uint8_t, 7>{r1.data[0], r1.data[1], r1.data[2], r1.data[3], r1.data[4],
                                         r1.data[5], r1.data[6]}),
            (std::array<std::uint8_t, 7>{0x0F, 0x00, 0xC0, 0x1D, 0xFE, 0xFF, 0x09}));
  const CanFrame r2 = canopen::encode_rpdo2_spindle(kNode, pdo);
  EXPECT_EQ(r2.id, 0x303U);
  ASSERT_EQ(r2.dlc, 4);
  EXPECT_EQ((std::array<std::uint8_t, 4>{r2.data[0], r2.data[1], r2.data[2], r2.data[3]}),
            (std::array<std::uint8_t, 4>{0x80, 0xEE, 0x36, 0x00}));  // 3 600 000
  EXPECT_EQ(canopen::classify(r2).kind, canopen::FrameKind::rpdo2);

  canopen::TxPdoCsp t{0x0237, 42, 8, true};
  const CanFrame f = canopen::encode_tpdo_csp(kNode, t);
  ASSERT_EQ(f.dlc, 7);
  const auto back = canopen::decode_tpdo_csp(f, true);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->mode_display, 8);
  EXPECT_FALSE(canopen::decode_tpdo_csp(f, false));  // 7 bytes where 6 are mapped
  t.has_mode_display = false;
  EXPECT_FALSE(canopen::decode_tpdo_csp(canopen::encode_tpdo_csp(kNode, t), true));
}

TEST(SpindleFrames, TheMappingIsWrittenInTheStandardsOrder) {
  const canopen::PdoLayout p = canopen::spindle_pdos();
  canopen::SdoWriteList w;
  ASSERT_TRUE(canopen::pdo_configuration(kNode, p.rpdo1, w));
  ASSERT_EQ(w.count, 8U);  // invalidate, type, count 0, 3 entries, count, validate
  EXPECT_EQ(w.writes[3].value, 0x60400010U);
  EXPECT_EQ(w.writes[4].value, 0x607A0020U);
  EXPECT_EQ(w.writes[5].value, 0x60600008U);
  EXPECT_EQ(w.writes[6].value, 3U);
  ASSERT_TRUE(canopen::pdo_configuration(kNode, p.rpdo2, w));
  EXPECT_EQ(w.writes[0].index, 0x1401);
  EXPECT_EQ(w.writes[0].value, 0x80000303U);  // RPDO2 of node 3, invalid while mapped
  EXPECT_EQ(w.writes[3].value, 0x60FF0020U);
  EXPECT_EQ(w.writes[w.count - 1].value, 0x303U);
  ASSERT_TRUE(canopen::pdo_configuration(kNode, p.tpdo1, w));
  EXPECT_EQ(w.writes[5].value, 0x60610008U);
}

// The simulator with one spindle drive, mapped as the master maps it, started and enabled.
class SpindleBus {
 public:
  SpindleBus() : sim_({spindle_params()}, kCycle) {
    sim_.power_on(out_);
    DriveObjects& od = const_cast<SimulatedDrive&>(*sim_.find(kNode)).objects();
    const canopen::PdoLayout p = canopen::spindle_pdos();
    for (const canopen::PdoMapping* pdo : {&p.rpdo1, &p.rpdo2, &p.tpdo1}) {
      canopen::SdoWriteList w;
      EXPECT_TRUE(canopen::pdo_configuration(kNode, *pdo, w));
      for (std::size_t i = 0; i < w.count; ++i) {
        const std::uint32_t v = w.writes[i].value;
        const std::uint8_t bytes[4] = {
            static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
            static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
        EXPECT_EQ(od.write(w.writes[i].index, w.writes[i].sub, bytes, w.writes[i].size), 0U)
            << std::hex << w.writes[i].index;
      }
    }
    sim_.handle(canopen::encode_nmt(canopen::NmtCommand::start, kNode), out_);
  }

  // One cycle: RPDO2, RPDO1, SYNC; TPDO1 decoded as a spindle's.
  std::optional<canopen::TxPdoCsp> cycle(const canopen::RxPdoSpindle& pdo) {
    sim_.handle(canopen::encode_rpdo2_spindle(kNode, pdo), out_);
    sim_.handle(canopen::encode_rpdo1_spindle(kNode, pdo), out_);
    const std::size_t n = sim_.handle(canopen::encode_sync(1), out_);
    for (std::size_t i = 0; i < n; ++i) {
      if (out_[i].id == 0x180U + kNode) {
        return canopen::decode_tpdo_csp(out_[i], true);
      }
    }
    return std::nullopt;
  }

  const SimulatedDrive& drive() const { return *sim_.find(kNode); }
  DriveBusSimulator& sim() { return sim_; }

 private:
  DriveBusSimulator sim_;
  std::array<CanFrame, 8> out_{};
};

TEST(SpindleModes, TheModeInTheRpdoTakesEffectAtTheSyncAndIsDisplayed) {
  SpindleBus bus;
  canopen::RxPdoSpindle pdo{0x0006, 0, 9, 0};
  for (const std::uint16_t cw : {0x06, 0x07, 0x0F}) {
    pdo.controlword = cw;
    bus.cycle(pdo);
  }
  ASSERT_EQ(bus.drive().state(), State::operation_enabled);
  // CSV at 3600 deg/s (600 rpm).
  pdo.target_velocity = 3600000;
  std::optional<canopen::TxPdoCsp> t;
  for (int i = 0; i < 500; ++i) {
    t = bus.cycle(pdo);
  }
  ASSERT_TRUE(t);
  EXPECT_EQ(t->mode_display, 9);
  EXPECT_NEAR(bus.drive().velocity(), 3600.0, 1e-3);
  // To CSP at a target ahead of where it turns by a cycle and the position loop's lag (4 ms at
  // 3600 deg/s): the drive takes it at the SYNC and keeps turning.
  const double at = bus.drive().position();
  pdo.mode = 8;
  pdo.target_position = static_cast<std::int32_t>(std::lround((at + 3.6 + 14.4) * 1000.0));
  t = bus.cycle(pdo);
  EXPECT_EQ(t->mode_display, 8);
  EXPECT_EQ(bus.drive().objects().mode(), 8);
  EXPECT_NEAR(bus.drive().velocity(), 3600.0, 100.0);  // no brake on the switch
  // Back to CSV.
  pdo.mode = 9;
  t = bus.cycle(pdo);
  EXPECT_EQ(t->mode_display, 9);
  // A mode it does not have (1, profile position) is not taken.
  pdo.mode = 1;
  t = bus.cycle(pdo);
  EXPECT_EQ(t->mode_display, 9);
}

TEST(SpindleModes, AnRpdoOfTheWrongLengthIsNotProcessed) {
  SpindleBus bus;
  const auto before = bus.sim().malformed_count();
  CanFrame six = canopen::encode_rpdo_csp(kNode, canopen::RxPdoCsp{0x0F, 5});  // 6 bytes
  std::array<CanFrame, 8> out{};
  bus.sim().handle(six, out);
  CanFrame two = canopen::encode_rpdo2_spindle(kNode, canopen::RxPdoSpindle{});
  two.dlc = 2;
  bus.sim().handle(two, out);
  EXPECT_EQ(bus.sim().malformed_count(), before + 2);
  EXPECT_FALSE(bus.drive().rpdo_since_sync());
}

// Lockstep over UDP: a SYNC may overtake one of a spindle's two RPDOs. The SYNC waits for
// each RPDO the drive got in the cycle before, not just for one of them, or the drive would
// step with last cycle's target.
TEST(SpindleModes, ASyncWaitsForBothRpdosOfAFedSpindle) {
  SpindleBus bus;
  canopen::RxPdoSpindle pdo{0x000F, 1000, 8, 0};
  bus.cycle(pdo);  // fed with both RPDOs: both awaited from now on
  EXPECT_FALSE(bus.sim().rpdos_complete());
  std::array<CanFrame, 8> out{};
  pdo.target_position = 2000;
  bus.sim().handle(canopen::encode_rpdo2_spindle(kNode, pdo), out);
  EXPECT_FALSE(bus.sim().rpdos_complete());  // RPDO1 is still on its way
  bus.sim().handle(canopen::encode_rpdo1_spindle(kNode, pdo), out);
  EXPECT_TRUE(bus.sim().rpdos_complete());
  bus.sim().handle(canopen::encode_sync(2), out);

  // RPDO1 alone in a cycle: only RPDO1 is awaited in the next.
  bus.sim().handle(canopen::encode_rpdo1_spindle(kNode, pdo), out);
  bus.sim().handle(canopen::encode_sync(3), out);
  EXPECT_FALSE(bus.sim().rpdos_complete());
  bus.sim().handle(canopen::encode_rpdo1_spindle(kNode, pdo), out);
  EXPECT_TRUE(bus.sim().rpdos_complete());
  bus.sim().handle(canopen::encode_sync(4), out);

  // A node that stops sending RPDO1 is no longer waited for once the shell gives up on it.
  bus.sim().handle(canopen::encode_sync(5), out);
  bus.sim().handle(canopen::encode_rpdo2_spindle(kNode, pdo), out);
  EXPECT_TRUE(bus.sim().rpdos_complete());  // nothing came in the cycle before
  bus.sim().handle(canopen::encode_sync(6), out);
  EXPECT_FALSE(bus.sim().rpdos_complete());  // RPDO2 is awaited now
  bus.sim().stop_awaiting_silent_drives();
  EXPECT_TRUE(bus.sim().rpdos_complete());

  // A drive NMT-stopped is not awaited.
  bus.sim().handle(canopen::encode_rpdo2_spindle(kNode, pdo), out);
  bus.sim().handle(canopen::encode_rpdo1_spindle(kNode, pdo), out);
  bus.sim().handle(canopen::encode_sync(7), out);
  EXPECT_FALSE(bus.sim().rpdos_complete());
  bus.sim().handle(canopen::encode_nmt(canopen::NmtCommand::stop, kNode), out);
  EXPECT_TRUE(bus.sim().rpdos_complete());
  bus.sim().handle(canopen::encode_nmt(canopen::NmtCommand::start, kNode), out);
  EXPECT_TRUE(bus.sim().rpdos_complete());
}

// The axis node's core and the drive in closed loop through the spindle's PDOs.
TEST(SpindleModes, TheNodeSwitchesCsvToCspAndBackWithoutAJump) {
  SpindleBus bus;
  axisnode::AxisNodeSetup setup{1000.0, kCycle, 5};
  setup.spindle = true;
  setup.following_error_limit = 30.0;  // degrees (spindle_lathe's)
  axisnode::AxisNodeController node(setup);
  std::optional<canopen::TxPdoCsp> t;
  auto step = [&](std::uint64_t c, bool velocity, double pos, double vel) {
    axisnode::AxisNodeInput in;
    in.have_setpoint = true;
    in.setpoint_valid = true;
    in.setpoint_velocity = velocity;
    in.setpoint_pos = pos;
    in.setpoint_vel = vel;
    in.have_tpdo = t.has_value();
    if (t) {
      in.statusword = t->statusword;
      in.position_counts = t->position_actual;
      in.mode_display = t->mode_display;
    }
    const auto& out = node.cycle(c, in);
    t = bus.cycle(canopen::RxPdoSpindle{out.controlword, out.target_counts, out.mode,
                                        out.target_velocity_counts});
    return out;
  };
  std::uint64_t c = 0;
  for (; c < 600; ++c) {
    const auto& out = step(c, true, 0.0, 3600.0);
    EXPECT_EQ(out.new_alarm, axisnode::AxisAlarm::none) << c;
  }
  ASSERT_EQ(node.output().mode_display, axisnode::kModeCsv);
  EXPECT_NEAR(bus.drive().velocity(), 3600.0, 1e-3);
  // The owner takes the spindle in position, continuing its turn at 3600 deg/s, then stops it
  // with a ramp to rest: the node switches, and the turn goes on without a brake or an alarm.
  // The owner's position continues from the spindle's feedback: where it will be when the
  // drive switches (a cycle on) plus the drive's lag at this speed (its 4 ms loop).
  double pos = node.output().act + 3.6 + 3600.0 * 0.004;
  double vel = 3600.0;
  bool switched = false;
  double slowest = 1e9;
  for (int i = 0; i < 100; ++i, ++c) {  // turning on in position
    pos += vel * kCycle;
    const auto& out = step(c, false, pos, vel);
    EXPECT_EQ(out.new_alarm, axisnode::AxisAlarm::none) << c;
    switched = switched || out.mode_changed;
    slowest = std::min(slowest, bus.drive().velocity());
  }
  EXPECT_GT(slowest, 3600.0 * 0.95);  // no brake at the switch
  for (int i = 0; i < 1200; ++i, ++c) {
    vel = std::max(0.0, vel - 6000.0 * kCycle);
    pos += vel * kCycle;
    const auto& out = step(c, false, pos, vel);
    EXPECT_EQ(out.new_alarm, axisnode::AxisAlarm::none) << c;
    switched = switched || out.mode_changed;
  }
  EXPECT_TRUE(switched);
  EXPECT_EQ(node.output().mode_display, axisnode::kModeCsp);
  EXPECT_NEAR(bus.drive().position(), pos, 0.01);  // positioned where the owner said
  EXPECT_NEAR(bus.drive().velocity(), 0.0, 1e-3);
  // And back to turning, the other way: never a turn the wrong way on the switch.
  double fastest_wrong_way = 0.0;
  for (int i = 0; i < 600; ++i, ++c) {
    step(c, true, 0.0, -1200.0);
    fastest_wrong_way = std::max(fastest_wrong_way, bus.drive().velocity());
  }
  EXPECT_LT(fastest_wrong_way, 1.0);
  EXPECT_EQ(node.output().mode_display, axisnode::kModeCsv);
  EXPECT_NEAR(bus.drive().velocity(), -1200.0, 1e-3);
  EXPECT_EQ(node.output().alarm, axisnode::AxisAlarm::none);
}

// An axis that homes at start-up: the node walks the drive to operation in homing mode,
// raises controlword bit 4, sees homing attained, switches to CSP and takes over at the home
// position, and only then is enabled for its owner.
TEST(HomingAxis, HomesAtStartThenFollowsInCsp) {
  DriveParams p = spindle_params();
  p.counts_per_unit = 10000.0;
  p.initial_position = 12.5;
  p.units_per_rev = 10.0;
  p.max_velocity = 200.0;
  SimulatedDrive drive(p, kCycle);
  drive.power_on();
  drive.on_nmt(canopen::NmtCommand::start);
  const auto write = [&](std::uint16_t index, std::uint32_t v, std::uint8_t size) {
    const std::uint8_t b[4] = {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                               static_cast<std::uint8_t>(v >> 16),
                               static_cast<std::uint8_t>(v >> 24)};
    ASSERT_EQ(drive.objects().write(index, 0, b, size), 0U);
  };
  write(0x6098, 37, 1);
  write(0x607C, static_cast<std::uint32_t>(500000), 4);  // home is 50 mm
  write(0x6060, 6, 1);
  axisnode::AxisNodeSetup setup{10000.0, kCycle, 5};
  setup.homing = true;
  axisnode::AxisNodeController node(setup);
  canopen::TxPdoCsp t{};
  bool have = false;
  std::vector<std::uint16_t> controlwords;
  std::uint64_t enabled_at = 0;
  for (std::uint64_t c = 0; c < 40; ++c) {
    axisnode::AxisNodeInput in;
    in.have_setpoint = true;
    in.setpoint_valid = node.output().enabled;
    in.setpoint_pos = 50.0;
    in.have_tpdo = have;
    in.statusword = t.statusword;
    in.position_counts = t.position_actual;
    in.mode_display = drive.objects().mode();
    const auto& out = node.cycle(c, in);
    if (controlwords.empty() || controlwords.back() != out.controlword) {
      controlwords.push_back(out.controlword);
    }
    if (out.enabled && enabled_at == 0) {
      enabled_at = c;
      EXPECT_DOUBLE_EQ(out.cmd, 50.0);  // taken over at home, no jump
      EXPECT_TRUE(out.homed);
    }
    RpdoValues v;
    v.controlword = out.controlword;
    v.has_controlword = true;
    v.target_position = out.target_counts;
    v.has_target_position = true;
    v.mode = out.mode;
    v.has_mode = true;
    drive.on_rpdo(v);
    t = drive.on_sync();
    have = true;
  }
  // Enable sequence, then bit 4 for the homing, then plain enable operation in CSP.
  EXPECT_EQ(controlwords,
            (std::vector<std::uint16_t>{0x0000, 0x0006, 0x0007, 0x000F, 0x001F, 0x000F}));
  EXPECT_GT(enabled_at, 0U);
  EXPECT_EQ(drive.objects().mode(), 8);
  EXPECT_NEAR(drive.position(), 50.0, 1e-9);  // homing moved the value, not the motor
  EXPECT_EQ(node.output().alarm, axisnode::AxisAlarm::none);
}

}  // namespace
}  // namespace mcnc::drivesim
