#pragma once
// Every frame on a CAN bus, in the order they came, from a listener of its own on the bus (the
// machine's simulated bus: a UDP multicast group the test joins as one more node).
#include "common/can/can_bus.hpp"

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace mcnc::test {

// Listens from its construction to its end.
class BusRecorder {
 public:
  explicit BusRecorder(const std::string& uri) : bus_(mcnc::can::open_can_bus(uri)) {
    thread_ = std::thread([this] {
      mcnc::can::CanFrame frame;
      while (!stop_) {
        if (bus_->receive(frame, std::chrono::milliseconds(50)) == mcnc::can::BusResult::ok) {
          std::lock_guard<std::mutex> lock(mutex_);
          frames_.push_back(frame);
        }
      }
    });
  }
  ~BusRecorder() {
    stop_ = true;
    thread_.join();
  }
  BusRecorder(const BusRecorder&) = delete;
  BusRecorder& operator=(const BusRecorder&) = delete;
  [[nodiscard]] std::vector<mcnc::can::CanFrame> frames() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return frames_;
  }

 private:
  std::unique_ptr<mcnc::can::CanBus> bus_;
  mutable std::mutex mutex_;
  std::vector<mcnc::can::CanFrame> frames_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace mcnc::test
