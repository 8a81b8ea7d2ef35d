// Which ends of a child after the run's stop fail the run, and which are Fast DDS teardown.
#include "launch/child_end.hpp"

#include "common/process/exit_deadline.hpp"

#include <gtest/gtest.h>

#include <csignal>

namespace mcnc::launch {
namespace {

ChildExit exit_with(int code, bool announced_stop, bool killed_by_launcher = false,
                    bool run_failed = false) {
  ChildExit e;
  e.exit_code = code;
  e.announced_stop = announced_stop;
  e.killed_by_launcher = killed_by_launcher;
  e.run_failed = run_failed;
  return e;
}

TEST(ChildEnd, ExitCodeZeroIsClean) {
  EXPECT_EQ(classify_child_end(exit_with(0, true)), ChildEnd::clean);
  EXPECT_EQ(classify_child_end(exit_with(0, false)), ChildEnd::clean);
}

TEST(ChildEnd, LeavingByTheExitDeadlineIsTeardownEvenWhenTheStopWasNotSeen) {
  // The stop announcement may be lost in the very teardown that hangs; the deadline is armed
  // only after the end work, so the exit code alone says it.
  EXPECT_EQ(classify_child_end(exit_with(process::kExitTeardownHung, false)), ChildEnd::teardown);
  EXPECT_EQ(classify_child_end(exit_with(process::kExitTeardownHung, true, false, true)),
            ChildEnd::teardown);
  // Alarms it raised may be lost in the hang: the run fails.
  EXPECT_EQ(classify_child_end(exit_with(process::kExitTeardownHungAfterAlarms, true)),
            ChildEnd::failed);
}

TEST(ChildEnd, AnAbortAfterTheStopIsTeardownAndBeforeItOnlyInARunThatHadNotFailed) {
  EXPECT_EQ(classify_child_end(exit_with(-SIGABRT, true)), ChildEnd::teardown);
  EXPECT_EQ(classify_child_end(exit_with(-SIGABRT, true, false, true)), ChildEnd::teardown);
  EXPECT_EQ(classify_child_end(exit_with(-SIGABRT, false)), ChildEnd::teardown_early);
  EXPECT_EQ(classify_child_end(exit_with(-SIGABRT, false, false, true)), ChildEnd::failed);
}

TEST(ChildEnd, AKillCountsAsTeardownOnlyWhenTheLauncherKilledAChildThatHadStopped) {
  EXPECT_EQ(classify_child_end(exit_with(-SIGKILL, true, true)), ChildEnd::teardown);
  EXPECT_EQ(classify_child_end(exit_with(-SIGKILL, false, true)), ChildEnd::failed);
  EXPECT_EQ(classify_child_end(exit_with(-SIGKILL, true, false)), ChildEnd::failed);
}

TEST(ChildEnd, OtherEndsFailTheRun) {
  EXPECT_EQ(classify_child_end(exit_with(1, true)), ChildEnd::failed);
  EXPECT_EQ(classify_child_end(exit_with(2, false)), ChildEnd::failed);
  EXPECT_EQ(classify_child_end(exit_with(-SIGSEGV, true, true)), ChildEnd::failed);
  EXPECT_EQ(classify_child_end(exit_with(-SIGTERM, true)), ChildEnd::failed);
}

}  // namespace
}  // namespace mcnc::launch
