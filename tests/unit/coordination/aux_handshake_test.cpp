// M/S/T codes to the PLC: one request, its FIN, refusals and timeouts as alarms, the PLC gone,
// and a spindle start that a following spindle may not make.
#include "channel/coordination/aux_handshake.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace mcnc::coordination {
namespace {

constexpr AuxInputs kPlc{true, false};

PlcAnswer answer(std::uint64_t id, AuxOutcome outcome, const char* reason = "") {
  PlcAnswer a;
  a.id = id;
  a.outcome = outcome;
  std::strncpy(a.reason.data(), reason, a.reason.size() - 1);
  return a;
}

TEST(AuxHandshake, SendsOnceAndEndsWithItsOwnAnswer) {
  AuxHandshake aux(2);
  aux.begin(AuxKind::m_code, 8, false);
  EXPECT_FALSE(aux.sent());
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);
  EXPECT_EQ(aux.request().id, (std::uint64_t{2} << 40) | 1);
  EXPECT_EQ(aux.request().code, 8);
  EXPECT_TRUE(aux.sent());
  EXPECT_EQ(aux.step(kPlc), AuxStep::waiting);
  aux.on_answer(answer(aux.request().id + 1, AuxOutcome::done));  // another request's
  EXPECT_EQ(aux.step(kPlc), AuxStep::waiting);
  aux.on_answer(answer(aux.request().id, AuxOutcome::done));
  EXPECT_EQ(aux.step(kPlc), AuxStep::done);
  EXPECT_FALSE(aux.sent());
  // The next request counts on.
  aux.begin(AuxKind::t_code, 101, false);
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);
  EXPECT_EQ(aux.request().id, (std::uint64_t{2} << 40) | 2);
  EXPECT_EQ(aux.request().kind, AuxKind::t_code);
}

TEST(AuxHandshake, ARefusalOrATimeoutIsAnAlarmThatNamesTheCode) {
  AuxHandshake aux(1);
  aux.begin(AuxKind::t_code, 101, false);
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);
  aux.on_answer(answer(aux.request().id, AuxOutcome::refused, "turret not locked"));
  ASSERT_EQ(aux.step(kPlc), AuxStep::alarm);
  EXPECT_EQ(aux.alarm().number, kAlarmAuxRefused);
  EXPECT_STREQ(aux.alarm().text.data(), "T0101 refused by the PLC: turret not locked");

  aux.begin(AuxKind::m_code, 8, false);
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);
  aux.on_answer(answer(aux.request().id, AuxOutcome::timed_out, "no FIN"));
  ASSERT_EQ(aux.step(kPlc), AuxStep::alarm);
  EXPECT_EQ(aux.alarm().number, kAlarmAuxTimeout);
  EXPECT_STREQ(aux.alarm().text.data(), "M08 not done by the PLC: no FIN");
}

TEST(AuxHandshake, ThePlcGoneRefusesTheWaitingRequestAndEveryLaterOne) {
  AuxHandshake aux(1);
  aux.begin(AuxKind::m_code, 8, false);
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);
  aux.plc_lost();
  ASSERT_EQ(aux.step(kPlc), AuxStep::alarm);
  EXPECT_EQ(aux.alarm().number, kAlarmAuxRefused);
  EXPECT_NE(std::string(aux.alarm().text.data()).find("the PLC node is gone"), std::string::npos);
  EXPECT_TRUE(aux.plc_gone());
  aux.begin(AuxKind::m_code, 9, false);
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);  // still sent: the answer may be on its way
  EXPECT_EQ(aux.step(kPlc), AuxStep::alarm);
}

TEST(AuxHandshake, AnAnswerToAnAbandonedRequestIsIgnored) {
  AuxHandshake aux(1);
  aux.begin(AuxKind::m_code, 8, false);
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);
  const std::uint64_t old = aux.request().id;
  aux.abandon();  // a reset
  aux.on_answer(answer(old, AuxOutcome::done));
  aux.begin(AuxKind::m_code, 8, false);
  ASSERT_EQ(aux.step(kPlc), AuxStep::send);
  aux.on_answer(answer(old, AuxOutcome::done));
  EXPECT_EQ(aux.step(kPlc), AuxStep::waiting);
}

TEST(AuxHandshake, AFollowingSpindleDoesNotStartAndNothingIsSent) {
  AuxHandshake aux(1);
  aux.begin(AuxKind::m_code, 3, true);
  ASSERT_EQ(aux.step(AuxInputs{true, true}), AuxStep::alarm);
  EXPECT_EQ(aux.alarm().number, kAlarmSlaveSpindle);
  EXPECT_FALSE(aux.sent());
  // Once it no longer follows, the start is asked.
  EXPECT_EQ(aux.step(kPlc), AuxStep::send);
  EXPECT_EQ(aux.request().code, 3);
}

TEST(AuxHandshake, ASpindleStartWithoutPlcTurnsAtOnce) {
  AuxHandshake aux(1);
  aux.begin(AuxKind::m_code, 4, true);
  EXPECT_EQ(aux.step(AuxInputs{false, false}), AuxStep::done);
  EXPECT_FALSE(aux.sent());
}

}  // namespace
}  // namespace mcnc::coordination
