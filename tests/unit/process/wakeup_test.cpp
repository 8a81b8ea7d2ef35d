#include "common/process/wakeup.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace mcnc::process {
namespace {

using namespace std::chrono_literals;

// Counts how often the waiter's condition is evaluated by the waiter itself: once on entry,
// then once per wake-up (or per 50 ms re-check).
TEST(Wakeup, UpdatesThatLeaveTheConditionFalseDoNotWakeTheWaiter) {
  Wakeup wake;
  int samples = 0;  // under the wake-up's lock
  std::atomic<int> checks_by_waiter{0};
  std::atomic<bool> waiting{false};
  const std::thread::id waiter_id_unset{};
  std::thread::id waiter_id = waiter_id_unset;
  std::atomic<bool> held{false};
  std::thread waiter([&] {
    waiter_id = std::this_thread::get_id();
    waiting = true;
    held = wake.wait_for(
        [&] {
          if (std::this_thread::get_id() == waiter_id) {
            ++checks_by_waiter;
          }
          return samples >= 100;
        },
        10s);
  });
  while (!waiting) {
    std::this_thread::yield();
  }
  std::this_thread::sleep_for(20ms);  // the waiter is in its wait
  for (int i = 0; i < 100; ++i) {
    wake.update([&] { ++samples; });
  }
  waiter.join();
  EXPECT_TRUE(held);
  // Its entry check, the wake-up by the 100th sample, and at most a few 50 ms re-checks: never
  // one per sample.
  EXPECT_LE(checks_by_waiter.load(), 5);
  EXPECT_GE(checks_by_waiter.load(), 2);
}

TEST(Wakeup, AConditionThatHoldsWakesTheWaiterAtOnce) {
  Wakeup wake;
  bool ready = false;
  std::atomic<bool> waiting{false};
  const auto start = std::chrono::steady_clock::now();
  std::chrono::steady_clock::duration took{};
  std::thread waiter([&] {
    waiting = true;
    EXPECT_TRUE(wake.wait_for([&] { return ready; }, 10s));
    took = std::chrono::steady_clock::now() - start;
  });
  while (!waiting) {
    std::this_thread::yield();
  }
  wake.update([&] { ready = true; });
  waiter.join();
  EXPECT_LT(took, 5s);
}

TEST(Wakeup, TimesOutWhenTheConditionNeverHolds) {
  Wakeup wake;
  EXPECT_FALSE(wake.wait_for([] { return false; }, 120ms));
  int n = 0;
  wake.update([&] { ++n; });  // no waiter: nothing to check
  EXPECT_EQ(n, 1);
}

TEST(Wakeup, TwoWaitersWithDifferentConditionsBothWake) {
  Wakeup wake;
  int a = 0;
  int b = 0;
  std::atomic<int> waiting{0};
  std::thread first([&] {
    ++waiting;
    EXPECT_TRUE(wake.wait_for([&] { return a > 0; }, 10s));
  });
  std::thread second([&] {
    ++waiting;
    EXPECT_TRUE(wake.wait_for([&] { return b > 0; }, 10s));
  });
  while (waiting < 2) {
    std::this_thread::yield();
  }
  std::this_thread::sleep_for(20ms);
  wake.update([&] { a = 1; });
  wake.update([&] { b = 1; });
  first.join();
  second.join();
}

}  // namespace
}  // namespace mcnc::process
