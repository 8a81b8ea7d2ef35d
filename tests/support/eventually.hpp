#pragma once
// Waits for what another thread or process brings about (a DDS match, a sample, a file):
// polls `pred` until it holds or `timeout` has passed, and says which.
#include <chrono>
#include <thread>

namespace mcnc::test {

template <class Pred>
bool eventually(Pred pred, std::chrono::milliseconds timeout,
                std::chrono::milliseconds poll = std::chrono::milliseconds(20)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (pred()) {
      return true;
    }
    std::this_thread::sleep_for(poll);
  }
  return pred();
}

}  // namespace mcnc::test
