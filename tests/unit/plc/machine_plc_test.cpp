// The PLC program (docs/plc.md): M codes with FIN, interlocks, time-outs, spindle start
// interlocks and T codes, from a machine file's plc section.
#include "plcnode/logic/machine_plc.hpp"
#include "common/config/machine_config.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mcnc::plc {
namespace {

// 1 ms cycle; the chuck's sensors follow its valve 200 ms later; the coolant has no sensor.
config::MachineConfig machine() {
  return config::parse_machine_yaml(R"(
machine: {name: m, cycle_us: 1000}
buses:
  - {name: b, uri: "socketcan:can0", sync_producer: X1}
  - {name: b2, uri: "socketcan:can1", sync_producer: X2}
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: S1, type: spindle, bus: b, node_id: 2}
  - {name: X2, address: X, bus: b2, node_id: 3}
channels: [{name: CH1, axes: [X1], spindles: [S1]}, {name: CH2, axes: [X2]}]
plc:
  signals:
    - {name: chuck1_clamp, type: output, initial: true}
    - {name: chuck1_closed, type: input, follows: chuck1_clamp, delay_ms: 200}
    - {name: chuck1_open, type: input, follows: chuck1_clamp, invert: true, delay_ms: 200}
    - {name: coolant, type: output}
    - {name: door_closed, type: input, initial: false}
  m_codes:
    - {code: 10, channels: [CH1], set: [chuck1_clamp], wait: [chuck1_closed]}
    - {code: 11, channels: [CH1], set: [chuck1_clamp=0], wait: [chuck1_open], spindle_stopped: S1}
    - {code: 8, set: [coolant]}
    - {code: 9, set: [coolant=0]}
    - {code: 50, wait: [door_closed], timeout_ms: 100}
    - {code: 51, requires: [door_closed], set: [coolant]}
  spindle_start: [{spindle: S1, requires: [chuck1_closed]}]
  tool_change_ms: 50
)");
}

// The key path a machine file is refused at, or "accepted".
std::string key_rejected(const std::string& yaml) {
  try {
    (void)config::parse_machine_yaml(yaml);
  } catch (const config::ConfigError& e) {
    return e.key_path();
  }
  return "accepted";
}

class PlcRig {
 public:
  PlcRig() : config_(machine()), plc_(config_.plc, config_.cycle_us) {}

  void ask(std::uint32_t channel, int code, AuxKind kind = AuxKind::m_code, int spindle = 0) {
    plc_.request(AuxRequest{channel, ++id_, kind, code, spindle, cycle_});
  }
  // Steps until an answer comes; the cycles it took.
  int until_answer(AuxResult& got, int limit = 5000) {
    for (int i = 0; i < limit; ++i) {
      const PlcOutput& out = plc_.cycle(++cycle_, spindles_);
      if (out.answer_count > 0) {
        got = out.answers[0];
        return i + 1;
      }
    }
    return -1;
  }
  bool signal(const std::string& name) const {
    return plc_.signal(config_.plc.find_signal(name)->index);
  }
  std::vector<AxisView> spindles_{{2, false}};
  void run_cycles(int n) {
    for (int i = 0; i < n; ++i) {
      plc_.cycle(++cycle_, spindles_);
    }
  }

 private:
  config::MachineConfig config_;
  MachinePlc plc_;
  std::uint64_t cycle_ = 0;
  std::uint64_t id_ = 0;
};

TEST(MachinePlc, AnMCodeEndsWhenItsInputFollowsTheOutput) {
  PlcRig rig;
  EXPECT_TRUE(rig.signal("chuck1_closed"));  // clamped at power-on
  rig.ask(1, 11);
  AuxResult a;
  const int took = rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::done);
  EXPECT_GE(took, 200);  // the sensor's 200 ms
  EXPECT_LE(took, 202);
  EXPECT_FALSE(rig.signal("chuck1_clamp"));
  EXPECT_TRUE(rig.signal("chuck1_open"));
  rig.ask(1, 10);
  EXPECT_GE(rig.until_answer(a), 200);
  EXPECT_TRUE(rig.signal("chuck1_closed"));
}

TEST(MachinePlc, ACodeWithoutFinConditionEndsAtOnce) {
  PlcRig rig;
  rig.ask(2, 8);
  AuxResult a;
  EXPECT_EQ(rig.until_answer(a), 1);
  EXPECT_EQ(a.outcome, AuxOutcome::done);
  EXPECT_EQ(a.request.channel, 2U);
  EXPECT_TRUE(rig.signal("coolant"));
}

TEST(MachinePlc, InterlocksRefuseAndChangeNothing) {
  PlcRig rig;
  rig.spindles_[0].turning = true;
  rig.ask(1, 11);  // no chuck open while the spindle turns
  AuxResult a;
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::refused);
  EXPECT_NE(std::string(a.reason.data()).find("turns"), std::string::npos);
  EXPECT_TRUE(rig.signal("chuck1_clamp"));
  rig.ask(1, 51);  // needs the door closed
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::refused);
  EXPECT_NE(std::string(a.reason.data()).find("door_closed=1"), std::string::npos);
  EXPECT_FALSE(rig.signal("coolant"));
  rig.ask(2, 10);  // M10 is channel 1's only
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::refused);
}

TEST(MachinePlc, AChuckOpensWhileItsSpindleTurnsInPhaseWithAnother) {
  PlcRig rig;
  // S1 (axis 2) turns; a slave (axis 9) follows it, not yet in phase: refused.
  rig.spindles_ = {{2, true, 0, false}, {9, true, 2, false}};
  rig.ask(1, 11);
  AuxResult a;
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::refused);
  rig.spindles_[1].locked = true;  // in phase: the part turns with both spindles
  rig.ask(1, 11);
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::done);
}

TEST(MachinePlc, ASpindleStartsOnlyWithTheChuckClosed) {
  PlcRig rig;
  rig.ask(1, 3, AuxKind::m_code, 2);
  AuxResult a;
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::done);
  // Just started, its feedback still says it stands: the chuck stays closed all the same.
  rig.ask(1, 11);
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::refused);
  rig.run_cycles(static_cast<int>(MachinePlc::kStartBridgeCycles));
  rig.ask(1, 11);
  rig.until_answer(a);
  rig.ask(1, 4, AuxKind::m_code, 2);
  rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::refused);
  EXPECT_NE(std::string(a.reason.data()).find("chuck1_closed=1"), std::string::npos);
}

TEST(MachinePlc, NoFinInTimeIsATimeOut) {
  PlcRig rig;
  rig.ask(1, 50);
  AuxResult a;
  const int took = rig.until_answer(a);
  EXPECT_EQ(a.outcome, AuxOutcome::timed_out);
  EXPECT_EQ(took, 1 + 100);  // taken in the cycle after it was sent, then 100 ms
  EXPECT_NE(std::string(a.reason.data()).find("door_closed=1"), std::string::npos);
}

TEST(MachinePlc, TCodesWaitForTheTurretAndRequestsAreTakenInOrder) {
  PlcRig rig;
  rig.ask(2, 101, AuxKind::t_code);
  rig.ask(1, 202, AuxKind::t_code);  // same cycle: channel 1 first
  AuxResult a;
  EXPECT_EQ(rig.until_answer(a), 1 + 50);
  EXPECT_EQ(a.request.channel, 1U);
  EXPECT_EQ(a.request.code, 202);
}

TEST(MachinePlc, TheMachineFileIsChecked) {
  const std::string head = R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
axes: [{name: X1, address: X, bus: b, node_id: 1}]
channels: [{name: CH1, axes: [X1]}]
plc:
  signals: [{name: v, type: output}, {name: s, type: input, follows: v}]
)";
  auto rejected = [&](const std::string& tail) { return key_rejected(head + tail); };
  EXPECT_EQ(rejected("  m_codes: [{code: 10, set: [s]}]\n"), "plc.m_codes[0].set[0]");  // an input
  EXPECT_EQ(rejected("  m_codes: [{code: 10, wait: [v]}]\n"), "plc.m_codes[0].wait[0]");
  EXPECT_EQ(rejected("  m_codes: [{code: 10, set: [w]}]\n"), "plc.m_codes[0].set[0]");
  EXPECT_EQ(rejected("  m_codes: [{code: 10, set: [v=2]}]\n"), "plc.m_codes[0].set[0]");
  EXPECT_EQ(rejected("  m_codes: [{code: 30}]\n"), "plc.m_codes[0].code");
  EXPECT_EQ(rejected("  m_codes: [{code: 10}, {code: 10}]\n"), "plc.m_codes[1]");
  EXPECT_EQ(rejected("  m_codes: [{code: 10, spindle_stopped: X1}]\n"),
            "plc.m_codes[0].spindle_stopped");
  EXPECT_EQ(rejected("  m_codes: [{code: 10, channels: [CH1], set: [v=0], wait: [s=0]}]\n"),
            "accepted");
}

// G31 P's skip signals (decision 92): a sensor input of the simulated machine that X1 switches
// where it reaches a position, from the axis's feedback; one the PLC has not heard of keeps its
// state.
// One axis X1 and a PLC with one output; the signals that follow are appended.
constexpr const char* kOneAxisPlc = R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
axes: [{name: X1, address: X, bus: b, node_id: 1}]
channels: [{name: CH1, axes: [X1]}]
plc:
  signals:
    - {name: v, type: output}
)";

TEST(MachinePlc, APositionInputIsOnWhereItsAxisStandsBeyondIt) {
  const config::MachineConfig m = config::parse_machine_yaml(std::string(kOneAxisPlc) + R"(
    - {name: touch, type: input, skip: 2, position: {axis: X1, at: -12.5, on: below}}
    - {name: clear, type: input, invert: true, position: {axis: X1, at: 5, on: above}}
)");
  ASSERT_EQ(m.plc.signals[1].skip, 2);
  MachinePlc plc(m.plc, m.cycle_us);
  const auto step = [&](bool known, double x) {
    const AxisView view{1, false, 0, false, known, x};
    return plc.cycle(1, std::span<const AxisView>(&view, 1)).inputs;
  };
  EXPECT_EQ(step(true, 0.0), 0b100U);    // touch off, clear on (inverted)
  EXPECT_EQ(step(true, -12.5), 0b110U);  // at the position: on
  EXPECT_EQ(step(false, 10.0), 0b110U);  // not heard of: as it was
  EXPECT_EQ(step(true, 5.0), 0b000U);    // clear goes off at 5
  EXPECT_EQ(step(true, -13.0), 0b110U);
}

TEST(MachinePlc, SkipSignalsAndPositionInputsAreChecked) {
  auto rejected = [&](const std::string& tail) { return key_rejected(kOneAxisPlc + tail); };
  EXPECT_EQ(rejected("    - {name: s, type: input, skip: 9}\n"), "plc.signals[1].skip");
  EXPECT_EQ(rejected("    - {name: s, type: output, skip: 1}\n"), "plc.signals[1].skip");
  EXPECT_EQ(rejected("    - {name: s, type: input, skip: 1}\n    - {name: t, type: input, "
                     "skip: 1}\n"),
            "plc.signals[2].skip");
  EXPECT_EQ(rejected("    - {name: s, type: input, position: {axis: Q1, at: 1, on: below}}\n"),
            "plc.signals[1].position.axis");
  EXPECT_EQ(rejected("    - {name: s, type: input, position: {axis: X1, at: 1, on: left}}\n"),
            "plc.signals[1].position.on");
  EXPECT_EQ(rejected("    - {name: s, type: input, follows: v, position: {axis: X1, at: 1, "
                     "on: below}}\n"),
            "plc.signals[1].position");
  EXPECT_EQ(rejected("    - {name: s, type: input, skip: 1, position: {axis: X1, at: 1, "
                     "on: below}}\n"),
            "accepted");
}

}  // namespace
}  // namespace mcnc::plc
