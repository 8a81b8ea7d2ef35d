#pragma once
// The one wake-up of a process: DDS callbacks and other receive threads change the state the
// cycle waits on under its lock, and the cycle thread waits until a condition on that state
// holds. The condition of the thread that waits is checked by the thread that changes the
// state, and the waiter is woken only once it holds: the many samples of a lockstep cycle (each
// other channel's status, each axis's feedback) cost one wake-up of the cycle thread, not one
// each.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>

namespace mcnc::process {

class Wakeup {
 public:
  // Wakes every waiter to check its condition again.
  void notify() noexcept {
    { std::lock_guard<std::mutex> lock(mutex_); }
    cv_.notify_all();
  }
  // Waits until pred() holds, re-checking when an update makes it hold, at every notify and at
  // least every 50 ms (a signal handler cannot notify); false on timeout. pred() may be called
  // by the updating thread, under the lock: it reads state, it changes nothing.
  template <class Pred>
  bool wait_for(Pred pred, std::chrono::microseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::unique_lock<std::mutex> lock(mutex_);
    ++waiters_;
    const Condition previous = waiting_;
    waiting_ = Condition{[](const void* p) { return (*static_cast<const Pred*>(p))(); }, &pred};
    bool held = true;
    while (!pred()) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= deadline) {
        held = false;
        break;
      }
      cv_.wait_for(lock, std::min<std::chrono::steady_clock::duration>(
                             deadline - now, std::chrono::milliseconds(50)));
    }
    waiting_ = previous;
    --waiters_;
    return held;
  }
  // Runs fn under the lock the waiter uses, without waking anyone (to read shared state).
  template <class Fn>
  void with_lock(Fn fn) {
    std::lock_guard<std::mutex> lock(mutex_);
    fn();
  }
  // Runs fn under the same lock the waiter uses (for state the condition reads), then wakes the
  // waiter if its condition now holds. With more than one waiter, it wakes them all.
  template <class Fn>
  void update(Fn fn) {
    bool wake = true;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      fn();
      wake = waiters_ > 1 || (waiters_ == 1 && waiting_.holds());
    }
    if (wake) {
      cv_.notify_all();
    }
  }

 private:
  struct Condition {
    bool (*check)(const void*) = nullptr;
    const void* pred = nullptr;
    [[nodiscard]] bool holds() const { return check == nullptr || check(pred); }
  };
  std::mutex mutex_;
  std::condition_variable cv_;
  int waiters_ = 0;
  Condition waiting_;  // the condition of the latest waiter
};

}  // namespace mcnc::process
