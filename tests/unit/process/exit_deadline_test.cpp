// A process still there after its exit deadline leaves with kExitTeardownHung; one that leaves
// in time keeps its own exit code. A TeardownBound ends a hung teardown the same way, after its
// last work, and leaves one that ends in time alone.
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

// A teardown that hangs past its bound: `before_exit` runs, then the process leaves with the
// bound's exit code.
TEST(TeardownBound, AHungTeardownEndsAtTheBoundAfterItsLastWork) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const auto start = std::chrono::steady_clock::now();
  const int status = exit_status_of([&] {
    const TeardownBound bound(100ms, 5, [&] { (void)!::write(pipe_fds[1], "x", 1); });
    std::this_thread::sleep_for(60s);  // a teardown that never ends
  });
  EXPECT_EQ(status, 5);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 30s);
  char c = 0;
  EXPECT_EQ(::read(pipe_fds[0], &c, 1), 1) << "before_exit did not run";
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
}

// Disarmed in time (destroyed), it does nothing: the process goes on and leaves as it will.
TEST(TeardownBound, ATeardownThatEndsInTimeIsLeftAlone) {
  const int status = exit_status_of([] {
    {
      const TeardownBound bound(100ms, 5, [] { ::_exit(9); });
      std::this_thread::sleep_for(10ms);
    }
    std::this_thread::sleep_for(300ms);  // past the bound
    ::_exit(7);
  });
  EXPECT_EQ(status, 7);
}

}  // namespace
}  // namespace mcnc::process
