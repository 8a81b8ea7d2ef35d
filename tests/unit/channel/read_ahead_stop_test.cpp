// Which commands stop read-ahead, and what each held block carries for its machine.
#include "channel/control/read_ahead_stop.hpp"

#include "channel/coordination/coordination_alarm.hpp"

#include <gtest/gtest.h>

#include <array>

namespace mcnc::channel {
namespace {

interp::Command command(interp::Op op) {
  interp::Command c;
  c.op = op;
  c.n = 7;
  c.line = 12;
  return c;
}

struct Rules {
  std::array<coordination::AxisSlot, 2> slots{coordination::AxisSlot{'X'},
                                              coordination::AxisSlot{'A', true, 2}};
  StopRules rules{3, slots, true, false, {}};
  int spindle = 0;
  std::optional<interp::ProgramAlarm> alarm;
  ReadAheadStop stop(const interp::Command& c) { return read_ahead_stop(c, rules, spindle, alarm); }
};

TEST(ReadAheadStop, AMoveGoesToThePlannerAndASkipMoveStops) {
  Rules r;
  interp::Command move = command(interp::Op::linear);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(r.stop(move)));
  move.skip = true;
  move.input_on = false;
  const ReadAheadStop s = r.stop(move);
  ASSERT_TRUE(std::holds_alternative<SkipStop>(s));
  EXPECT_EQ(std::get<SkipStop>(s).arm, ProbeArm::falling);
  EXPECT_TRUE(std::get<SkipStop>(s).command.skip);
  EXPECT_FALSE(r.alarm);
}

TEST(ReadAheadStop, AWaitMarkCarriesItsParticipantsAndItsPlaceInTheProgram) {
  Rules r;
  interp::Command c = command(interp::Op::sync);
  c.has_p = true;
  c.p = 4;
  c.channels[0] = (1U << 1) | (1U << 3);
  const ReadAheadStop s = r.stop(c);
  ASSERT_TRUE(std::holds_alternative<SyncStop>(s));
  const SyncStop& m = std::get<SyncStop>(s);
  EXPECT_EQ(m.p, 4);
  EXPECT_TRUE(m.participants.test(1));
  EXPECT_TRUE(m.participants.test(3));
  EXPECT_EQ(m.participants.count(), 2U);
  EXPECT_EQ(m.block.n, 7U);
  EXPECT_EQ(m.block.line, 12);
  EXPECT_FALSE(m.block.started);
}

TEST(ReadAheadStop, AuxCodesStopOnlyWithAPlcAndTCodesCarryToolAndOffset) {
  Rules r;
  interp::Command m8 = command(interp::Op::aux);
  m8.code = 8;
  ReadAheadStop s = r.stop(m8);
  ASSERT_TRUE(std::holds_alternative<AuxStop>(s));
  EXPECT_EQ(std::get<AuxStop>(s).code, 8);
  EXPECT_EQ(std::get<AuxStop>(s).kind, coordination::AuxKind::m_code);
  interp::Command t = command(interp::Op::tool);
  t.tool = 1;
  t.offset = 1;
  s = r.stop(t);
  ASSERT_TRUE(std::holds_alternative<AuxStop>(s));
  EXPECT_EQ(std::get<AuxStop>(s).code, 101);
  EXPECT_EQ(std::get<AuxStop>(s).kind, coordination::AuxKind::t_code);
  r.rules.plc = false;
  EXPECT_TRUE(std::holds_alternative<std::monostate>(r.stop(m8)));
}

TEST(ReadAheadStop, ASpindleStartOrReversalAsksThePlcASpeedChangeDoesNot) {
  Rules r;
  interp::Command m3 = command(interp::Op::spindle);
  m3.spindle_direction = interp::SpindleDirection::cw;
  ReadAheadStop s = r.stop(m3);
  ASSERT_TRUE(std::holds_alternative<AuxStop>(s));
  EXPECT_TRUE(std::get<AuxStop>(s).spindle_start);
  EXPECT_EQ(std::get<AuxStop>(s).code, 3);
  EXPECT_EQ(r.spindle, 1);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(r.stop(m3)));  // M03 S.. while turning
  interp::Command m4 = m3;
  m4.spindle_direction = interp::SpindleDirection::ccw;
  s = r.stop(m4);
  ASSERT_TRUE(std::holds_alternative<AuxStop>(s));
  EXPECT_EQ(std::get<AuxStop>(s).code, 4);
  interp::Command m5 = m3;
  m5.spindle_direction = interp::SpindleDirection::stop;
  EXPECT_TRUE(std::holds_alternative<std::monostate>(r.stop(m5)));
  EXPECT_EQ(r.spindle, 0);
}

TEST(ReadAheadStop, AnExchangeNamesItsSlotOrIsAnAlarm) {
  Rules r;
  interp::Command g141 = command(interp::Op::axis_acquire);
  g141.axis = 'A';
  g141.force = true;
  const ReadAheadStop s = r.stop(g141);
  ASSERT_TRUE(std::holds_alternative<ExchangeStop>(s));
  EXPECT_EQ(std::get<ExchangeStop>(s).slot, 1U);
  EXPECT_TRUE(std::get<ExchangeStop>(s).force);
  EXPECT_EQ(std::get<ExchangeStop>(s).kind, coordination::AxisRequestKind::acquire);
  g141.axis = 'B';
  EXPECT_TRUE(std::holds_alternative<std::monostate>(r.stop(g141)));
  ASSERT_TRUE(r.alarm);
  EXPECT_EQ(r.alarm->number, coordination::kAlarmNotOwner);
  EXPECT_EQ(r.alarm->line, 12);
}

TEST(ReadAheadStop, ACallCarriesItsTargetAndTheArgumentsGiven) {
  Rules r;
  interp::Command g144 = command(interp::Op::subcall);
  g144.channel = 2;
  g144.program = 77;
  g144.wait = false;
  g144.repeat = 3;
  g144.args = {{1, 1.5}, {26, -2.0}, {27, 9.0}};
  const ReadAheadStop s = r.stop(g144);
  ASSERT_TRUE(std::holds_alternative<CallStop>(s));
  const coordination::CallRequest& call = std::get<CallStop>(s).call;
  EXPECT_EQ(call.caller, 3U);
  EXPECT_EQ(call.target, 2U);
  EXPECT_EQ(call.program, 77);
  EXPECT_FALSE(call.wait);
  EXPECT_EQ(call.repeat, 3);
  EXPECT_EQ(call.args_given, (1U << 0) | (1U << 25));  // #27 is no argument
  EXPECT_DOUBLE_EQ(call.args[25], -2.0);
  EXPECT_EQ(call.call_id, 0U);
}

}  // namespace
}  // namespace mcnc::channel
