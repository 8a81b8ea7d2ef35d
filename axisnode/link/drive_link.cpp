#include "axisnode/link/drive_link.hpp"

#include "canopen/bus_filters.hpp"
#include "common/clock/cycle_clock.hpp"
#include "common/process/thread_name.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace mcnc::axisnode {

using namespace std::chrono_literals;

DriveLink::DriveLink(std::unique_ptr<can::CanBus> bus, std::uint8_t node_id, bool sync_producer,
                     std::vector<std::uint8_t> other_nodes, process::Wakeup& wakeup)
    : bus_(std::move(bus)),
      node_id_(node_id),
      sync_producer_(sync_producer),
      other_nodes_(std::move(other_nodes)),
      wakeup_(wakeup) {
  // Only what this node's master needs reaches it (in the kernel on SocketCAN).
  std::array<can::CanFilter, can::kMaxFilters> filters{};
  const std::size_t n = canopen::master_filters(node_id_, sync_producer_, other_nodes_, filters);
  if (!bus_->set_filters(std::span(filters.data(), n))) {
    spdlog::warn("node {}: the bus refused the receive filter; receiving every frame", node_id_);
  }
  thread_ = std::thread([this] {
    process::name_this_thread("can-rx");
    // The drive's answers close its loop: in realtime, at the cycle thread's priority.
    (void)clock::raise_realtime_thread(clock::kAxisCyclePriority);
    receive_loop();
  });
}

DriveLink::~DriveLink() {
  stop_sync_timer();
  stop_ = true;
  thread_.join();
}

void DriveLink::start_sync_timer(const canopen::SyncSchedule& schedule) {
  stop_sync_timer();
  sync_stop_ = false;
  sync_late_ns_.assign(kLatenessRecords, 0);
  sync_late_count_ = 0;
  sync_thread_ = std::thread([this, schedule] {
    process::name_this_thread("can-sync");
    (void)clock::raise_realtime_thread(clock::kAxisCyclePriority);
    std::uint64_t next = 0;
    while (!sync_stop_) {
      // Wake at the due time, or within 50 ms to notice a stop.
      const std::int64_t now = clock::monotonic_ns();
      clock::sleep_until_ns(std::min(schedule.due(next), now + 50'000'000));
      std::uint64_t index = 0;
      const std::int64_t woke = clock::monotonic_ns();
      if (sync_stop_ || !schedule.to_send(woke, next, index)) {
        continue;
      }
      send_sync(true);
      syncs_skipped_ += index - next;
      sync_late_ns_[sync_late_count_++ % kLatenessRecords] = woke - schedule.due(index);
      next = index + 1;
    }
  });
}

void DriveLink::stop_sync_timer() {
  if (sync_thread_.joinable()) {
    sync_stop_ = true;
    sync_thread_.join();
  }
}

std::vector<std::int64_t> DriveLink::sync_lateness() const {
  std::vector<std::int64_t> out;
  const std::uint64_t n = std::min<std::uint64_t>(sync_late_count_, kLatenessRecords);
  for (std::uint64_t i = sync_late_count_ - n; i < sync_late_count_; ++i) {
    out.push_back(sync_late_ns_[i % kLatenessRecords]);
  }
  return out;
}

void DriveLink::receive_loop() {
  canopen::CanFrame frame;
  while (!stop_) {
    const can::BusResult result = bus_->receive(frame, 50ms);
    if (result == can::BusResult::malformed) {
      ++malformed_;
      continue;
    }
    if (result == can::BusResult::bus_off) {
      if (!bus_off_.exchange(true)) {
        spdlog::error("node {}: the CAN controller went bus off", node_id_);
      }
      wakeup_.notify();
      continue;
    }
    if (result != can::BusResult::ok) {
      continue;
    }
    const canopen::FrameClass cls = canopen::classify(frame);
    switch (cls.kind) {
      case canopen::FrameKind::sync:
        wakeup_.update([&] { rpdo_seen_.reset(); });  // another SYNC source on the bus
        break;
      case canopen::FrameKind::rpdo1:
        if (cls.node != node_id_ && cls.node < 128) {
          wakeup_.update([&] { rpdo_seen_.set(cls.node); });
        }
        break;
      case canopen::FrameKind::tpdo1:
        if (cls.node == node_id_) {
          if (auto pdo = canopen::decode_tpdo_csp(frame, with_mode_)) {
            const bool paired = tpdo2_velocity_ || tpdo2_following_error_ || tpdo2_torque_;
            wakeup_.update([&] {
              tpdo_statusword_ = pdo->statusword;
              tpdo_position_ = pdo->position_actual;
              tpdo_mode_display_ = pdo->mode_display;
              ++tpdo1_count_;
              // An answer is complete with both of its TPDOs, in whichever order they came.
              tpdo_count_ = paired ? std::min(tpdo1_count_, tpdo2_count_) : tpdo1_count_;
            });
          } else {
            ++malformed_;
          }
        }
        break;
      case canopen::FrameKind::tpdo2:
        if (cls.node == node_id_ && (tpdo2_velocity_ || tpdo2_following_error_ || tpdo2_torque_)) {
          const std::size_t want = (tpdo2_velocity_ ? 4U : 0U) +
                                   (tpdo2_following_error_ ? 4U : 0U) + (tpdo2_torque_ ? 2U : 0U);
          if (frame.dlc != want) {
            ++malformed_;
            break;
          }
          const auto i32 = [&](std::size_t at) {
            return static_cast<std::int32_t>(static_cast<std::uint32_t>(frame.data[at]) |
                                             static_cast<std::uint32_t>(frame.data[at + 1]) << 8 |
                                             static_cast<std::uint32_t>(frame.data[at + 2]) << 16 |
                                             static_cast<std::uint32_t>(frame.data[at + 3]) << 24);
          };
          // In the order the start-up mapped them: velocity, following error, torque.
          const std::size_t torque_at = want - 2U;
          wakeup_.update([&] {
            tpdo2_velocity_value_ = tpdo2_velocity_ ? i32(0) : 0;
            tpdo2_following_error_value_ =
                tpdo2_following_error_ ? i32(tpdo2_velocity_ ? 4 : 0) : 0;
            tpdo2_torque_value_ =
                tpdo2_torque_ ? static_cast<std::int16_t>(
                                    static_cast<std::uint16_t>(frame.data[torque_at]) |
                                    static_cast<std::uint16_t>(frame.data[torque_at + 1] << 8))
                              : std::int16_t{0};
            ++tpdo2_count_;
            tpdo_count_ = std::min(tpdo1_count_, tpdo2_count_);
          });
        }
        break;
      case canopen::FrameKind::heartbeat:
        if (cls.node == node_id_) {
          auto state = canopen::decode_heartbeat(frame);
          if (state && *state == canopen::NmtState::bootup) {
            wakeup_.update([&] { ++bootups_; });
          }
          if (state) {
            ++heartbeats_;
          } else {
            ++malformed_;
          }
          wakeup_.update([&] {
            if (starting_) {
              startup_frames_.push_back(frame);
            }
          });
        }
        break;
      case canopen::FrameKind::emcy:
        if (cls.node == node_id_) {
          if (auto emcy = canopen::decode_emcy(frame)) {
            last_emcy_ = emcy->error_code;
            ++emcys_;
            spdlog::warn("EMCY from node {}: error code 0x{:04x}", node_id_, emcy->error_code);
          }
        }
        break;
      case canopen::FrameKind::other:
        if (frame.id == canopen::kSdoResponseBase + node_id_) {
          wakeup_.update([&] {
            if (starting_) {
              startup_frames_.push_back(frame);
            }
          });
        }
        break;
      default:
        break;
    }
  }
}

std::optional<std::string> DriveLink::bring_up(const canopen::NodeStartupConfig& config,
                                               std::chrono::milliseconds timeout) {
  canopen::NodeStartup startup(config);
  const auto t0 = std::chrono::steady_clock::now();
  const auto now_us = [&] {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0)
            .count());
  };
  wakeup_.update([&] {
    startup_frames_.clear();
    starting_ = true;
  });
  canopen::CanFrame out;
  startup.begin(now_us(), out);
  bus_->send(out);
  std::deque<canopen::CanFrame> got;
  while (startup.status() == canopen::NodeStartup::Status::running &&
         std::chrono::steady_clock::now() - t0 < timeout) {
    wakeup_.wait_for([&] { return !startup_frames_.empty(); }, 10ms);
    wakeup_.with_lock([&] { got.swap(startup_frames_); });
    for (const canopen::CanFrame& frame : got) {
      if (startup.on_frame(frame, now_us(), out)) {
        bus_->send(out);
      }
    }
    got.clear();
    if (startup.on_time(now_us(), out)) {
      bus_->send(out);
    }
  }
  wakeup_.update([&] { starting_ = false; });
  switch (startup.status()) {
    case canopen::NodeStartup::Status::done:
      return std::nullopt;
    case canopen::NodeStartup::Status::failed:
      return std::string(startup.error());
    case canopen::NodeStartup::Status::running:
      break;
  }
  return "node " + std::to_string(node_id_) + ": start-up not finished within " +
         std::to_string(timeout.count()) + " ms";
}

void DriveLink::send_rpdo(const DriveCommand& command) noexcept {
  if (!with_mode_) {
    bus_->send(canopen::encode_rpdo_csp(
        node_id_, canopen::RxPdoCsp{command.controlword, command.target_counts}));
    return;
  }
  const canopen::RxPdoSpindle pdo{command.controlword, command.target_counts, command.mode,
                                  command.target_velocity_counts};
  // RPDO2 first: the SYNC producer waits for RPDO1, so both are in before the SYNC.
  if (with_velocity_) {
    bus_->send(canopen::encode_rpdo2_spindle(node_id_, pdo));
  }
  bus_->send(canopen::encode_rpdo1_spindle(node_id_, pdo));
}

void DriveLink::send_sync(bool timed) noexcept {
  sync_counter_ = static_cast<std::uint8_t>(sync_counter_ % 240 + 1);
  // Our own frames are not received back: the RPDOs seen are forgotten here, in lockstep before
  // the SYNC goes out (the next cycle's RPDOs may come back at once). The timer (realtime, no
  // RPDO bookkeeping) sends first: the lock is shared with non-realtime threads, and the SYNC's
  // time on the bus is what must not wait.
  const auto forget_rpdos = [&] { wakeup_.update([&] { rpdo_seen_.reset(); }); };
  if (timed) {
    bus_->send(canopen::encode_sync(sync_counter_));
    forget_rpdos();
  } else {
    forget_rpdos();
    bus_->send(canopen::encode_sync(sync_counter_));
  }
}

void DriveLink::send_nmt(canopen::NmtCommand command) noexcept {
  bus_->send(canopen::encode_nmt(command, node_id_));
}

void DriveLink::exchange(const DriveCommand& command, bool lockstep, std::uint64_t tpdos_seen,
                         const std::function<bool()>& abandon, std::chrono::milliseconds slow) {
  const auto wait = [&](auto&& arrived, const char* what) {
    const auto since = std::chrono::steady_clock::now();
    bool warned = false;
    while (!arrived(std::chrono::milliseconds(100))) {
      if (abandon()) {
        return;
      }
      if (!warned && std::chrono::steady_clock::now() - since > slow) {
        spdlog::warn("node {}: still waiting for {}", node_id_, what);
        warned = true;
      }
    }
  };
  send_rpdo(command);
  if (sync_producer_ && !lockstep && !sync_timer_running()) {
    send_sync();
  }
  if (!lockstep) {
    return;
  }
  if (sync_producer_) {
    wait([&](auto t) { return wait_other_rpdos(t); }, "the RPDOs of the other nodes");
    send_sync();
  }
  // The drive answers the producer's SYNC: every node awaits that answer alone (a node that
  // does not produce the SYNC does not even receive it, bus_filters.hpp).
  wait([&](auto t) { return wait_tpdo_after(tpdos_seen, t); }, "the drive's answer to the SYNC");
}

bool DriveLink::wait_other_rpdos(std::chrono::milliseconds timeout) {
  return wakeup_.wait_for(
      [&] {
        for (std::uint8_t node : other_nodes_) {
          if (!rpdo_seen_.test(node)) {
            return false;
          }
        }
        return true;
      },
      timeout);
}

bool DriveLink::wait_tpdo_after(std::uint64_t tpdos_seen, std::chrono::milliseconds timeout) {
  return wakeup_.wait_for([&] { return tpdo_count_.load() > tpdos_seen; }, timeout);
}

TpdoSample DriveLink::tpdo() noexcept {
  TpdoSample sample;
  // Under the lock the receive thread writes with: statusword, position and count of one frame.
  wakeup_.with_lock([&] {
    sample.pdo.statusword = tpdo_statusword_.load();
    sample.pdo.position_actual = tpdo_position_.load();
    sample.pdo.mode_display = tpdo_mode_display_.load();
    sample.pdo.has_mode_display = with_mode_;
    sample.velocity_actual = tpdo2_velocity_value_.load();
    sample.following_error_actual = tpdo2_following_error_value_.load();
    sample.torque_actual = tpdo2_torque_value_.load();
    sample.count = tpdo_count_.load();
  });
  return sample;
}

std::uint64_t DriveLink::malformed_count() const noexcept {
  return malformed_.load() + bus_->malformed_count();
}

}  // namespace mcnc::axisnode
