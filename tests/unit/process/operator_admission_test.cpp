// A process takes an operator command or refuses it with a reason; the sender adds the answers
// up (issue 25: commands are never dropped silently).
#include "common/operator/operator_admission.hpp"
#include "common/config/machine_config.hpp"
#include "common/operator/operator_answers.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace mcnc::process {
namespace {

constexpr int kReset = static_cast<int>(OperatorActionKind::reset);
constexpr int kCycleStart = static_cast<int>(OperatorActionKind::cycle_start);
constexpr int kAlarmAck = static_cast<int>(OperatorActionKind::alarm_ack);

ArrivingCommand command(std::uint64_t cycle, int action = kCycleStart) {
  ArrivingCommand c;
  c.cycle = cycle;
  c.action = action;
  c.origin = "hmi";
  return c;
}

AdmissionState at(std::uint64_t cycle, std::size_t queued = 0, std::size_t later = 0) {
  AdmissionState s;
  s.cycle = cycle;
  s.generation = 3;
  s.queued = queued;
  s.queued_later = later;
  return s;
}

TEST(OperatorAdmission, LimitsAreOneSecondLateAndOneHourAheadInTheMachinesCycles) {
  const AdmissionLimits ms = AdmissionLimits::for_cycle_us(1000);
  EXPECT_EQ(ms.late_cycles, 1000U);
  EXPECT_EQ(ms.ahead_cycles, 3'600'000U);
  const AdmissionLimits two_ms = AdmissionLimits::for_cycle_us(2000);
  EXPECT_EQ(two_ms.late_cycles, 500U);
  EXPECT_EQ(two_ms.ahead_cycles, 1'800'000U);
}

TEST(OperatorAdmission, AnUnstampedCommandIsTakenAtAnyCycle) {
  const AdmissionLimits limits = AdmissionLimits::for_cycle_us(1000);
  EXPECT_EQ(admit(command(0), at(0), limits), OperatorRefusal::none);
  EXPECT_EQ(admit(command(0), at(123'456'789), limits), OperatorRefusal::none);
}

TEST(OperatorAdmission, AStampTooFarAheadIsRefusedAndOneInTheWindowTaken) {
  const AdmissionLimits limits = AdmissionLimits::for_cycle_us(1000);
  EXPECT_EQ(admit(command(std::numeric_limits<std::uint64_t>::max()), at(5000), limits),
            OperatorRefusal::too_far_ahead);
  EXPECT_EQ(admit(command(5000 + 3'600'001), at(5000), limits), OperatorRefusal::too_far_ahead);
  EXPECT_EQ(admit(command(5000 + 3'600'000), at(5000), limits), OperatorRefusal::none);
}

TEST(OperatorAdmission, AStampThatPassedMoreThanASecondAgoIsStale) {
  const AdmissionLimits limits = AdmissionLimits::for_cycle_us(1000);
  EXPECT_EQ(admit(command(1), at(5000), limits), OperatorRefusal::stale);
  EXPECT_EQ(admit(command(3999), at(5000), limits), OperatorRefusal::stale);
  EXPECT_EQ(admit(command(4000), at(5000), limits), OperatorRefusal::none);  // applied late
}

TEST(OperatorAdmission, ACommandOfAnEarlierRunIsRefusedOneOfThisOrTheNextTaken) {
  const AdmissionLimits limits = AdmissionLimits::for_cycle_us(1000);
  ArrivingCommand c = command(0);
  c.generation = 2;
  EXPECT_EQ(admit(c, at(10), limits), OperatorRefusal::earlier_run);
  c.generation = 3;
  EXPECT_EQ(admit(c, at(10), limits), OperatorRefusal::none);
  c.generation = 4;  // sent with a RUN_START that has not arrived yet
  EXPECT_EQ(admit(c, at(10), limits), OperatorRefusal::none);
}

TEST(OperatorAdmission, OnlyTheLauncherTheHmiAndTheCommandLineCommand) {
  const AdmissionLimits limits = AdmissionLimits::for_cycle_us(1000);
  ArrivingCommand c = command(0);
  for (const char* origin : {"launch", "hmi", "cli"}) {
    c.origin = origin;
    EXPECT_EQ(admit(c, at(10), limits), OperatorRefusal::none) << origin;
  }
  for (const char* origin : {"", "rogue", "HMI", "hmi "}) {
    c.origin = origin;
    EXPECT_EQ(admit(c, at(10), limits), OperatorRefusal::unknown_origin) << origin;
  }
}

TEST(OperatorAdmission, UnknownActionsAndTextsThatDoNotFitAreRefused) {
  const AdmissionLimits limits = AdmissionLimits::for_cycle_us(1000);
  EXPECT_EQ(admit(command(0, 0), at(10), limits), OperatorRefusal::unknown_action);
  EXPECT_EQ(admit(command(0, kAlarmAck + 1), at(10), limits), OperatorRefusal::unknown_action);
  EXPECT_EQ(admit(command(0, -1), at(10), limits), OperatorRefusal::unknown_action);
  EXPECT_EQ(admit(command(0, kAlarmAck), at(10), limits), OperatorRefusal::none);
  ArrivingCommand c = command(0, static_cast<int>(OperatorActionKind::mdi));
  c.text_size = OperatorRequest::kTextSize - 1;
  EXPECT_EQ(admit(c, at(10), limits), OperatorRefusal::none);
  c.text_size = OperatorRequest::kTextSize;
  EXPECT_EQ(admit(c, at(10), limits), OperatorRefusal::text_too_long);
}

TEST(OperatorAdmission, CommandsForLaterKeepOutOfTheReservedSlotsAndDueOnesGetIn) {
  const AdmissionLimits limits = AdmissionLimits::for_cycle_us(1000);
  const std::size_t later_room = OperatorInbox::kSlots - limits.reserved_slots;
  // The inbox holds as many commands for later as they may take.
  EXPECT_EQ(admit(command(900), at(10, later_room - 1, later_room - 1), limits),
            OperatorRefusal::none);
  EXPECT_EQ(admit(command(900), at(10, later_room, later_room), limits),
            OperatorRefusal::inbox_full);
  // The operator's commands, unstamped or due at the next cycle, still get in.
  EXPECT_EQ(admit(command(0), at(10, later_room, later_room), limits), OperatorRefusal::none);
  EXPECT_EQ(admit(command(11), at(10, later_room, later_room), limits), OperatorRefusal::none);
  EXPECT_EQ(admit(command(12), at(10, later_room, later_room), limits),
            OperatorRefusal::inbox_full);
  // Until the inbox holds all it can.
  EXPECT_EQ(admit(command(0), at(10, OperatorInbox::kSlots, later_room), limits),
            OperatorRefusal::inbox_full);
}

TEST(OperatorAdmission, TheInboxCountsTheCommandsDueOnlyAfterTheNextCycle) {
  OperatorInbox inbox;
  for (std::uint64_t stamp : {0, 5, 10, 11, 12, 4000}) {
    OperatorRequest r;
    r.cycle = stamp;
    r.action = OperatorActionKind::reset;
    ASSERT_TRUE(inbox.put(r));
  }
  EXPECT_EQ(inbox.count_due_after_next(10), 2U);  // 12 and 4000
  EXPECT_EQ(inbox.count_due_after_next(0), 5U);   // 5 on
}

TEST(OperatorAdmission, RefusalsAreNumberedAsOnTheWireAndUnknownNumbersAreNone) {
  EXPECT_EQ(refusal_numbered(0), OperatorRefusal::none);
  EXPECT_EQ(refusal_numbered(3), OperatorRefusal::too_far_ahead);
  EXPECT_EQ(refusal_numbered(7), OperatorRefusal::text_too_long);
  EXPECT_FALSE(refusal_numbered(8).has_value());
  EXPECT_FALSE(refusal_numbered(-1).has_value());
  EXPECT_STREQ(code_of(OperatorRefusal::stale), "stale");
}

TEST(OperatorScope, AChannelServesItsOwnAndTheMachinesCommandsAnAxisNodeOnlyResets) {
  const OperatorScope ch2 = OperatorScope::of_channel(2);
  EXPECT_TRUE(ch2.covers(2, kCycleStart));
  EXPECT_TRUE(ch2.covers(0, kCycleStart));
  EXPECT_FALSE(ch2.covers(1, kCycleStart));
  const OperatorScope node = OperatorScope::of_axis_node();
  EXPECT_TRUE(node.covers(1, kReset));
  EXPECT_TRUE(node.covers(0, kReset));
  EXPECT_FALSE(node.covers(1, kCycleStart));
}

config::MachineConfig twin_channels() {
  config::MachineConfig machine;
  for (int id : {1, 2}) {
    config::ChannelConfig ch;
    ch.id = id;
    ch.name = "CH" + std::to_string(id);
    machine.channels.push_back(ch);
  }
  for (const char* name : {"X1", "Z1"}) {
    config::AxisConfig axis;
    axis.name = name;
    machine.axes.push_back(axis);
  }
  return machine;
}

TEST(AnswerTally, TheChannelsACommandNamesAnswerItAndForAResetTheAxisNodesToo) {
  const config::MachineConfig machine = twin_channels();
  EXPECT_EQ(answering_processes(machine, 2, kCycleStart), (std::vector<std::string>{"CH2"}));
  EXPECT_EQ(answering_processes(machine, 0, kCycleStart), (std::vector<std::string>{"CH1", "CH2"}));
  EXPECT_EQ(answering_processes(machine, 1, kReset), (std::vector<std::string>{"CH1", "X1", "Z1"}));
}

TEST(AnswerTally, TakenOnlyOnceEveryProcessTookIt) {
  AnswerTally tally({"CH1", "X1"});
  EXPECT_EQ(tally.outcome(), AnswerTally::Outcome::pending);
  tally.add("CH1", OperatorRefusal::none, "");
  tally.add("CH1", OperatorRefusal::none, "");  // a repeat
  tally.add("Y9", OperatorRefusal::none, "");   // not asked
  EXPECT_EQ(tally.outcome(), AnswerTally::Outcome::pending);
  EXPECT_EQ(tally.unanswered_text(), "no answer from X1");
  tally.add("X1", OperatorRefusal::none, "");
  EXPECT_EQ(tally.outcome(), AnswerTally::Outcome::taken);
}

TEST(AnswerTally, OneRefusalRefusesTheCommandAndNamesWhoAndWhy) {
  AnswerTally tally({"CH1", "X1"});
  tally.add("X1", OperatorRefusal::inbox_full, reason_of(OperatorRefusal::inbox_full));
  EXPECT_EQ(tally.outcome(), AnswerTally::Outcome::refused);
  tally.add("CH1", OperatorRefusal::none, "");
  EXPECT_EQ(tally.outcome(), AnswerTally::Outcome::refused);
  EXPECT_EQ(tally.refused_by(), "X1");
  EXPECT_EQ(tally.refusal(), OperatorRefusal::inbox_full);
  EXPECT_EQ(tally.refusal_text(),
            "refused by X1 (inbox_full): the process holds as many commands as it keeps");
}

TEST(AnswerTally, ACommandNobodyServesIsNeverTaken) {
  AnswerTally tally({});
  tally.add("CH1", OperatorRefusal::none, "");
  EXPECT_EQ(tally.outcome(), AnswerTally::Outcome::pending);
  EXPECT_EQ(tally.unanswered_text(), "no process serves this command");
}

}  // namespace
}  // namespace mcnc::process
