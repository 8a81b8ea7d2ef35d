// A process still there after its exit deadline leaves with kExitTeardownHung; one that leaves
// in time keeps its own exit code.
#include "common/process/exit_deadline.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace mcnc::process {
namespace {

using namespace std::chrono_literals;

// Runs `body` in a child process and returns its exit status (-1: not a normal exit).
template <class Body>
int exit_status_of(Body body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    body();
    ::_exit(0);
  }
  int status = 0;
  if (pid < 0 || ::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) {
    return -1;
  }
  return WEXITSTATUS(status);
}

TEST(ExitDeadline, AProcessHungAfterItsWorkLeavesWithTheTeardownCode) {
  const auto start = std::chrono::steady_clock::now();
  const int status = exit_status_of([] {
    arm_exit_deadline("test", 100ms, kExitTeardownHung);
    std::this_thread::sleep_for(60s);  // a teardown that never ends
  });
  EXPECT_EQ(status, kExitTeardownHung);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 30s);
}

TEST(ExitDeadline, AProcessThatLeavesInTimeKeepsItsExitCode) {
  const int status = exit_status_of([] {
    arm_exit_deadline("test", 5s, kExitTeardownHung);
    std::this_thread::sleep_for(10ms);
    ::_exit(7);
  });
  EXPECT_EQ(status, 7);
}

}  // namespace
}  // namespace mcnc::process
