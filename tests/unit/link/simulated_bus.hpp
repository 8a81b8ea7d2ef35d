#pragma once
// The drive simulator on a bus in memory, for the drive link's tests: MemoryCanBus is both ends
// of one CAN bus (what one end sends, the other receives, in order; fixed capacity, a full
// queue refuses the frame; send never allocates), SimulatedBus the simulator answering on one
// end from a thread of its own.
#include "axisnode/drivesim/drive_bus_simulator.hpp"
#include "common/can/can_bus.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace mcnc::test {

class MemoryCanBus final : public can::CanBus {
 public:
  struct Queue {
    std::mutex mutex;
    std::condition_variable arrived;
    std::array<can::CanFrame, 4096> frames{};
    std::size_t head = 0;  // next to take
    std::size_t size = 0;
  };

  MemoryCanBus(std::shared_ptr<Queue> in, std::shared_ptr<Queue> out)
      : in_(std::move(in)), out_(std::move(out)) {}

  // The two ends of a new bus.
  static std::pair<std::unique_ptr<MemoryCanBus>, std::unique_ptr<MemoryCanBus>> pair() {
    auto a = std::make_shared<Queue>();
    auto b = std::make_shared<Queue>();
    return {std::make_unique<MemoryCanBus>(a, b), std::make_unique<MemoryCanBus>(b, a)};
  }

  can::BusResult send(const can::CanFrame& frame) noexcept override {
    {
      std::lock_guard<std::mutex> lock(out_->mutex);
      if (out_->size == out_->frames.size()) {
        return can::BusResult::error;
      }
      out_->frames[(out_->head + out_->size++) % out_->frames.size()] = frame;
    }
    out_->arrived.notify_all();
    return can::BusResult::ok;
  }
  can::BusResult receive(can::CanFrame& frame,
                         std::chrono::microseconds timeout) noexcept override {
    std::unique_lock<std::mutex> lock(in_->mutex);
    if (!in_->arrived.wait_for(lock, timeout, [&] { return in_->size > 0; })) {
      return can::BusResult::timeout;
    }
    frame = in_->frames[in_->head];
    in_->head = (in_->head + 1) % in_->frames.size();
    --in_->size;
    return can::BusResult::ok;
  }
  [[nodiscard]] unsigned long malformed_count() const noexcept override { return 0; }
  bool set_filters(std::span<const can::CanFilter>) noexcept override { return true; }
  [[nodiscard]] int native_handle() const noexcept override { return -1; }

 private:
  std::shared_ptr<Queue> in_;
  std::shared_ptr<Queue> out_;
};

// The simulator of one bus on a thread of its own, answering what the master sends.
class SimulatedBus {
 public:
  SimulatedBus(std::unique_ptr<can::CanBus> end, const drivesim::DriveParams& drive, double cycle_s)
      : end_(std::move(end)), sim_(std::vector<drivesim::DriveParams>{drive}, cycle_s) {
    std::array<can::CanFrame, 4> ignored{};
    sim_.power_on(ignored);  // powered before the master's first reset, its boot-up unheard
    thread_ = std::thread([this] {
      std::array<can::CanFrame, drivesim::DriveBusSimulator::kFramesPerDrive> out{};
      can::CanFrame in;
      const auto send_all = [&](std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
          end_->send(out[i]);
        }
      };
      while (!stop_) {
        // As mcnc-drivesim: the heartbeats of drives out of operational on the wall clock.
        send_all(sim_.heartbeats_out_of_operation(
            static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                           std::chrono::steady_clock::now().time_since_epoch())
                                           .count()),
            out));
        for (const can::CanFrame& frame : take_injected()) {
          send_all(sim_.handle(frame, out));
        }
        if (end_->receive(in, std::chrono::milliseconds(20)) != can::BusResult::ok) {
          continue;
        }
        send_all(sim_.handle(in, out));
      }
    });
  }
  ~SimulatedBus() {
    stop_ = true;
    thread_.join();
  }
  SimulatedBus(const SimulatedBus&) = delete;
  SimulatedBus& operator=(const SimulatedBus&) = delete;

  // A frame from a third node of the bus: the drives get it (within 20 ms) and, when
  // `to_master`, the master too.
  void inject(const can::CanFrame& frame, bool to_master) {
    {
      std::lock_guard<std::mutex> lock(injected_mutex_);
      injected_.push_back(frame);
    }
    if (to_master) {
      end_->send(frame);
    }
  }

 private:
  std::vector<can::CanFrame> take_injected() {
    std::lock_guard<std::mutex> lock(injected_mutex_);
    return std::exchange(injected_, {});
  }

  std::unique_ptr<can::CanBus> end_;
  drivesim::DriveBusSimulator sim_;
  std::atomic<bool> stop_{false};
  std::mutex injected_mutex_;
  std::vector<can::CanFrame> injected_;
  std::thread thread_;
};

}  // namespace mcnc::test
