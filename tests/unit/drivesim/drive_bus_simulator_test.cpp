#include "axisnode/drivesim/drive_bus_simulator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace mcnc::drivesim {
namespace {

using canopen::CanFrame;
using canopen::NmtCommand;
using canopen::NmtState;
using cia402::State;

constexpr double kCycle = 0.001;

DriveParams params(std::uint8_t node, double initial = 0.0) {
  DriveParams p;
  p.node_id = node;
  p.counts_per_unit = 10000.0;
  p.time_constant_s = 0.004;
  p.max_velocity = 500.0;
  p.quick_stop_decel = 5000.0;
  p.initial_position = initial;
  return p;
}

// A minimal CANopen master driving the simulator the way the axis node does: RPDO, then SYNC,
// then read the TPDO.
class Harness {
 public:
  explicit Harness(std::vector<DriveParams> drives) : sim_(drives, kCycle) {
    boot_count_ = sim_.power_on(out_);
  }

  std::size_t send(const CanFrame& frame) {
    last_count_ = sim_.handle(frame, out_);
    return last_count_;
  }

  void start(std::uint8_t node) { send(canopen::encode_nmt(NmtCommand::start, node)); }

  // One cycle for one node: RPDO(cw, target) + SYNC; the node's TPDO if it answered.
  std::optional<canopen::TxPdoCsp> cycle(std::uint8_t node, std::uint16_t cw, std::int32_t target) {
    send(canopen::encode_rpdo_csp(node, canopen::RxPdoCsp{cw, target}));
    send(canopen::encode_sync(0));
    for (std::size_t i = 0; i < last_count_; ++i) {
      if (out_[i].id == canopen::kTpdo1Base + node) {
        return canopen::decode_tpdo_csp(out_[i]);
      }
    }
    return std::nullopt;
  }

  // Walks the drive to operation enabled with next_controlword, holding the target at the
  // reported actual position. Returns the number of SYNC cycles used.
  int enable(std::uint8_t node) {
    auto tpdo = cycle(node, 0x0000, 0);
    int cycles = 1;
    while (tpdo && cia402::decode_statusword(tpdo->statusword) != State::operation_enabled &&
           cycles < 20) {
      const auto cw = cia402::next_controlword(cia402::decode_statusword(tpdo->statusword),
                                               cia402::Goal::enabled, true);
      tpdo = cycle(node, cw, tpdo->position_actual);
      ++cycles;
    }
    return cycles;
  }

  const SimulatedDrive& drive(std::uint8_t node) const { return *sim_.find(node); }
  DriveBusSimulator& sim() { return sim_; }
  std::span<const CanFrame> outputs() const { return {out_.data(), last_count_}; }
  std::size_t boot_count() const { return boot_count_; }

 private:
  DriveBusSimulator sim_;
  std::array<CanFrame, 8> out_{};
  std::size_t boot_count_ = 0;
  std::size_t last_count_ = 0;
};

TEST(DriveBusSimulator, PowerOnSendsBootUpAndEntersPreOperational) {
  Harness h({params(1), params(2)});
  ASSERT_EQ(h.boot_count(), 2U);
  EXPECT_EQ(h.drive(1).nmt_state(), NmtState::preoperational);
  EXPECT_EQ(h.drive(2).nmt_state(), NmtState::preoperational);
  EXPECT_EQ(h.drive(1).state(), State::switch_on_disabled);
}

TEST(DriveBusSimulator, RejectsBadNodeIds) {
  EXPECT_THROW(DriveBusSimulator({params(0)}, kCycle), std::invalid_argument);
  EXPECT_THROW(DriveBusSimulator({params(128)}, kCycle), std::invalid_argument);
  EXPECT_THROW(DriveBusSimulator({params(3), params(3)}, kCycle), std::invalid_argument);
}

TEST(DriveBusSimulator, EnableSequenceReachesOperationEnabledWithoutJump) {
  Harness h({params(1, 2.5)});
  h.start(1);
  EXPECT_EQ(h.drive(1).nmt_state(), NmtState::operational);
  // The master sends a stale target (0) with the enabling controlword: no jump.
  auto tpdo = h.cycle(1, 0x0006, 0);
  ASSERT_TRUE(tpdo);
  EXPECT_EQ(cia402::decode_statusword(tpdo->statusword), State::ready_to_switch_on);
  EXPECT_EQ(h.cycle(1, 0x0007, 0)->statusword & 0x6F, 0x23);
  tpdo = h.cycle(1, 0x000F, 0);
  EXPECT_EQ(cia402::decode_statusword(tpdo->statusword), State::operation_enabled);
  EXPECT_EQ(tpdo->position_actual, 25000);
  EXPECT_DOUBLE_EQ(h.drive(1).position(), 2.5);
  EXPECT_DOUBLE_EQ(h.drive(1).velocity(), 0.0);
  EXPECT_NE(tpdo->statusword & 0x0400, 0);  // target reached
}

TEST(DriveBusSimulator, EnableWithNextControlword) {
  Harness h({params(1)});
  h.start(1);
  EXPECT_EQ(h.enable(1), 4);  // 0x0000, 0x0006, 0x0007, 0x000F
  EXPECT_EQ(h.drive(1).state(), State::operation_enabled);
}

TEST(DriveBusSimulator, NmtResetSendsBootUp) {
  Harness h({params(1), params(2)});
  h.start(0);
  h.enable(1);
  ASSERT_EQ(h.drive(1).state(), State::operation_enabled);

  ASSERT_EQ(h.send(canopen::encode_nmt(NmtCommand::reset_node, 1)), 1U);
  const CanFrame boot = h.outputs()[0];
  EXPECT_EQ(boot.id, 0x701U);
  EXPECT_EQ(canopen::decode_heartbeat(boot), NmtState::bootup);
  EXPECT_EQ(h.drive(1).nmt_state(), NmtState::preoperational);
  EXPECT_EQ(h.drive(1).state(), State::switch_on_disabled);
  EXPECT_EQ(h.drive(2).nmt_state(), NmtState::operational);

  // Broadcast reset communication: both drives boot up again.
  ASSERT_EQ(h.send(canopen::encode_nmt(NmtCommand::reset_communication, 0)), 2U);
  EXPECT_EQ(h.outputs()[0].id, 0x701U);
  EXPECT_EQ(h.outputs()[1].id, 0x702U);
  EXPECT_EQ(h.drive(2).nmt_state(), NmtState::preoperational);

  EXPECT_EQ(h.send(canopen::encode_nmt(NmtCommand::start, 2)), 0U);
  EXPECT_EQ(h.drive(2).nmt_state(), NmtState::operational);
  h.send(canopen::encode_nmt(NmtCommand::stop, 2));
  EXPECT_EQ(h.drive(2).nmt_state(), NmtState::stopped);
  h.send(canopen::encode_nmt(NmtCommand::enter_preoperational, 2));
  EXPECT_EQ(h.drive(2).nmt_state(), NmtState::preoperational);
}

TEST(DriveBusSimulator, PdosIgnoredWhenNotOperational) {
  Harness h({params(1)});
  // Pre-operational: neither RPDO nor SYNC has an effect, no TPDO.
  EXPECT_FALSE(h.cycle(1, 0x0006, 0));
  EXPECT_FALSE(h.cycle(1, 0x0006, 0));
  EXPECT_EQ(h.drive(1).state(), State::switch_on_disabled);
  // The RPDO sent in pre-operational was not latched: after start, a bare SYNC applies the
  // power-on controlword (0), not 0x0006.
  h.start(1);
  h.send(canopen::encode_sync(1));
  EXPECT_EQ(h.outputs().size(), 1U);
  EXPECT_EQ(h.drive(1).state(), State::switch_on_disabled);

  h.enable(1);
  h.send(canopen::encode_nmt(NmtCommand::stop, 1));
  EXPECT_FALSE(h.cycle(1, 0x000F, 50000));
  EXPECT_EQ(h.drive(1).position(), 0.0);
}

TEST(DriveBusSimulator, IgnoresOtherNodesAndCountsMalformed) {
  Harness h({params(1)});
  h.start(1);
  // Other node ids and frames the drives do not consume: ignored, not counted.
  h.send(canopen::encode_rpdo_csp(9, canopen::RxPdoCsp{0x0006, 0}));
  h.send(canopen::encode_nmt(NmtCommand::stop, 9));
  h.send(canopen::encode_tpdo_csp(9, canopen::TxPdoCsp{}));
  h.send(canopen::encode_heartbeat(127, NmtState::operational));
  CanFrame other_short = canopen::encode_rpdo_csp(9, canopen::RxPdoCsp{});
  other_short.dlc = 2;
  h.send(other_short);
  EXPECT_EQ(h.sim().malformed_count(), 0U);
  EXPECT_EQ(h.drive(1).nmt_state(), NmtState::operational);

  CanFrame rpdo = canopen::encode_rpdo_csp(1, canopen::RxPdoCsp{0x0006, 0});
  rpdo.dlc = 5;
  EXPECT_EQ(h.send(rpdo), 0U);
  CanFrame sync = canopen::encode_sync(3);
  sync.dlc = 3;
  EXPECT_EQ(h.send(sync), 0U);
  CanFrame nmt = canopen::encode_nmt(NmtCommand::start, 1);
  nmt.dlc = 1;
  EXPECT_EQ(h.send(nmt), 0U);
  nmt = canopen::encode_nmt(NmtCommand::start, 1);
  nmt.data[0] = 0x55;
  EXPECT_EQ(h.send(nmt), 0U);
  EXPECT_EQ(h.sim().malformed_count(), 4U);
  // The malformed RPDO did not get latched.
  h.send(canopen::encode_sync(0));
  EXPECT_EQ(h.drive(1).state(), State::switch_on_disabled);
}

TEST(DriveBusSimulator, DeterministicAndIndependentDrives) {
  auto run = [] {
    Harness h({params(1), params(2, -1.0)});
    h.start(0);
    h.enable(1);
    h.enable(2);
    for (int n = 0; n < 30; ++n) {
      h.send(canopen::encode_rpdo_csp(1, canopen::RxPdoCsp{0x000F, 3 * n * 100}));
      h.send(canopen::encode_rpdo_csp(2, canopen::RxPdoCsp{0x000F, -10000 - n * 50}));
      h.send(canopen::encode_sync(0));
      EXPECT_EQ(h.outputs().size(), 2U);
    }
    return std::make_pair(h.drive(1).position(), h.drive(2).position());
  };
  const auto first = run();
  const auto second = run();
  EXPECT_EQ(first, second);
  EXPECT_GT(first.first, 0.0);
  EXPECT_LT(first.second, -1.0);
}

TEST(DriveBusSimulator, OutputsThatDoNotFitAreDropped) {
  DriveBusSimulator sim({params(1), params(2), params(3)}, kCycle);
  std::array<CanFrame, 2> small{};
  EXPECT_EQ(sim.power_on(small), 2U);
  EXPECT_EQ(sim.find(3)->nmt_state(), NmtState::preoperational);
  sim.handle(canopen::encode_nmt(NmtCommand::start, 0), small);
  EXPECT_EQ(sim.handle(canopen::encode_sync(0), small), 2U);
  EXPECT_EQ(sim.find(9), nullptr);
}

}  // namespace
}  // namespace mcnc::drivesim
