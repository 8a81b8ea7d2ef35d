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
}

DriveLink::~DriveLink() {
  stop_sync_timer();
  stop_ = true;
  if (thread_.joinable()) {
    thread_.join();
  }
}

std::optional<std::string> DriveLink::configure(const canopen::NodeStartupConfig& config,
                                                std::chrono::milliseconds timeout) {
  if (thread_.joinable()) {
    return "node " + std::to_string(node_id_) + ": configured already";
  }
  // The receive thread unpacks by this layout from its start on.
  layout_ = config.pdos;
  thread_ = std::thread([this] {
    process::name_this_thread("can-rx");
    // The drive's answers close its loop: in realtime, at the cycle thread's priority.
    (void)clock::raise_realtime_thread(clock::kAxisCyclePriority);
    receive_loop();
  });
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
  can::CanFrame out;
  startup.begin(now_us(), out);
  bus_->send(out);
  std::deque<can::CanFrame> got;
  while (startup.status() == canopen::NodeStartup::Status::running &&
         std::chrono::steady_clock::now() - t0 < timeout) {
    wakeup_.wait_for([&] { return !startup_frames_.empty(); }, 10ms);
    wakeup_.with_lock([&] { got.swap(startup_frames_); });
    for (const can::CanFrame& frame : got) {
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
      lifecycle_ = DriveLifecycle::inactive;
      return std::nullopt;
    case canopen::NodeStartup::Status::failed:
      lifecycle_ = DriveLifecycle::failed;
      return std::string(startup.error());
    case canopen::NodeStartup::Status::running:
      break;
  }
  lifecycle_ = DriveLifecycle::failed;
  return "node " + std::to_string(node_id_) + ": start-up not finished within " +
         std::to_string(timeout.count()) + " ms";
}

void DriveLink::activate(const DriveActivation& activation) {
  activation_ = activation;
  lockstep_ = activation.lockstep;
  answers_read_ = snapshot_.latest().answers;
  wakeup_.update([&] {
    left_operational_ = false;
    watching_ = true;
  });
  if (activation.sync_timer && sync_producer_) {
    start_sync_timer(*activation.sync_timer);
  }
  lifecycle_ = DriveLifecycle::active;
}

void DriveLink::deactivate(const canopen::DriveCommand& last) noexcept {
  watching_ = false;
  stop_sync_timer();
  command_ = last;
  send_rpdos();
  bus_->send(canopen::encode_nmt(canopen::NmtCommand::enter_preoperational, node_id_));
  if (lifecycle_ == DriveLifecycle::active) {
    lifecycle_ = DriveLifecycle::inactive;
  }
}

DriveStatus DriveLink::read(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) noexcept {
  const Snapshot s = snapshot_.latest();
  state_.feedback = s.feedback;
  state_.fresh = s.answers > answers_read_;
  state_.answers = s.answers;
  state_.heartbeats = s.heartbeats;
  state_.last_emcy = s.last_emcy;
  state_.bus_off = s.bus_off;
  state_.foreign_syncs = s.foreign_syncs;
  answers_read_ = s.answers;
  if (lifecycle_ != DriveLifecycle::active || s.bus_off) {
    return DriveStatus::error;
  }
  return DriveStatus::ok;
}

DriveStatus DriveLink::write(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) noexcept {
  if (lifecycle_ != DriveLifecycle::active) {
    return DriveStatus::error;
  }
  send_rpdos();
  if (sync_producer_ && !lockstep_ && !sync_timer_running()) {
    send_sync();
  }
  if (!lockstep_) {
    return state_.bus_off ? DriveStatus::error : DriveStatus::ok;
  }
  // An abandoned wait goes on as the cycle would have (the SYNC still goes out, the answer is
  // waited for once more), so that every node of the bus winds down alike.
  bool waited = true;
  if (sync_producer_) {
    waited = wait_lockstep(
        [&](auto t) {
          return wakeup_.wait_for(
              [&] {
                return std::all_of(other_nodes_.begin(), other_nodes_.end(),
                                   [&](std::uint8_t node) { return rpdo_seen_.test(node); });
              },
              t);
        },
        "the RPDOs of the other nodes");
    send_sync();
  }
  // The drive answers the producer's SYNC: every node awaits that answer alone (a node that
  // does not produce the SYNC does not even receive it, bus_filters.hpp). A drive whose
  // heartbeat says it left NMT operational answers no more: the cycle goes on without its
  // answer, and the node's SYNC watchdog counts the cycles as in realtime (alarm 2004).
  const std::uint64_t seen = answers_read_;
  waited = wait_lockstep(
               [&](auto t) {
                 return wakeup_.wait_for(
                     [&] { return answers_.load() > seen || left_operational_.load(); }, t);
               },
               "the drive's answer to the SYNC") &&
           waited;
  return waited ? DriveStatus::ok : DriveStatus::abandoned;
}

template <class Arrived>
bool DriveLink::wait_lockstep(Arrived arrived, const char* what) noexcept {
  const auto since = std::chrono::steady_clock::now();
  bool warned = false;
  while (!arrived(std::chrono::milliseconds(100))) {
    if (activation_.abandon && activation_.abandon()) {
      return false;
    }
    if (!warned && std::chrono::steady_clock::now() - since > activation_.slow) {
      spdlog::warn("node {}: still waiting for {}", node_id_, what);
      warned = true;
    }
  }
  return true;
}

void DriveLink::send_rpdos() noexcept {
  can::CanFrame frame;
  // RPDO2 first: the SYNC producer waits for RPDO1, so both are in before the SYNC.
  if (layout_.rpdo2.count > 0 && canopen::pack_command(layout_.rpdo2, node_id_, command_, frame)) {
    bus_->send(frame);
  }
  if (layout_.rpdo1.count > 0 && canopen::pack_command(layout_.rpdo1, node_id_, command_, frame)) {
    bus_->send(frame);
  }
}

void DriveLink::start_sync_timer(const canopen::SyncSchedule& schedule) {
  stop_sync_timer();
  sync_stop_ = false;
  sync_late_ns_.assign(kLatenessRecords, 0);
  sync_late_count_ = 0;
  sync_start_ns_.store(schedule.start_ns());
  sent_index_plus_one_.store(0);
  sync_thread_ = std::thread([this, schedule = canopen::SyncSchedule(schedule)]() mutable {
    process::name_this_thread("can-sync");
    (void)clock::raise_realtime_thread(clock::kSyncPriority);
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
      const std::int64_t due = schedule.due(index);
      sync_late_ns_[sync_late_count_++ % kLatenessRecords] = woke - due;
      sent_due_ns_[index % kSentSlots].store(due);
      sent_late_ns_[index % kSentSlots].store(woke - due);
      sent_index_plus_one_.store(index + 1);
      next = index + 1;
      schedule.follow_start(sync_start_ns_.load());  // for the SYNCs from next on
    }
  });
}

void DriveLink::stop_sync_timer() {
  if (sync_thread_.joinable()) {
    sync_stop_ = true;
    sync_thread_.join();
  }
}

bool DriveLink::latest_sync(SentSync& out) const noexcept {
  const std::uint64_t n = sent_index_plus_one_.load();
  if (n == 0) {
    return false;
  }
  out.index = n - 1;
  out.due_ns = sent_due_ns_[out.index % kSentSlots].load();
  out.late_ns = sent_late_ns_[out.index % kSentSlots].load();
  return true;
}

std::vector<std::int64_t> DriveLink::sync_lateness() const {
  std::vector<std::int64_t> out;
  const std::uint64_t n = std::min<std::uint64_t>(sync_late_count_, kLatenessRecords);
  for (std::uint64_t i = sync_late_count_ - n; i < sync_late_count_; ++i) {
    out.push_back(sync_late_ns_[i % kLatenessRecords]);
  }
  return out;
}

void DriveLink::publish() {
  snapshot_.publish(received_);
}

void DriveLink::on_tpdo(const can::CanFrame& frame, const canopen::PdoMapping& mapping,
                        std::uint64_t& count) {
  if (!canopen::unpack_feedback(mapping, frame, received_.feedback)) {
    ++malformed_;
    return;
  }
  ++count;
  // An answer is complete with each of its TPDOs, in whichever order they came.
  const bool paired = layout_.tpdo2.count > 0;
  received_.answers = paired ? std::min(tpdo1_count_, tpdo2_count_) : tpdo1_count_;
  publish();
  wakeup_.update([&] { answers_ = received_.answers; });
}

void DriveLink::receive_loop() {
  can::CanFrame frame;
  while (!stop_) {
    const can::BusResult result = bus_->receive(frame, 50ms);
    if (result == can::BusResult::malformed) {
      ++malformed_;
      continue;
    }
    if (result == can::BusResult::bus_off) {
      if (!received_.bus_off) {
        spdlog::error("node {}: the CAN controller went bus off", node_id_);
        received_.bus_off = true;
        publish();
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
        // Our own SYNC is not received back: this one comes from another producer. It is
        // counted for the node to alarm (2011); the RPDOs seen are kept, so a flood of such
        // frames cannot hold this node's SYNC back for ever (issue 25).
        if (watching_) {
          ++received_.foreign_syncs;
          publish();
          wakeup_.notify();
        }
        break;
      case canopen::FrameKind::rpdo1:
        if (cls.node != node_id_ && cls.node < 128) {
          ++other_rpdos_;
          wakeup_.update([&] { rpdo_seen_.set(cls.node); });
        }
        break;
      case canopen::FrameKind::tpdo1:
        if (cls.node == node_id_ && layout_.tpdo1.count > 0) {
          on_tpdo(frame, layout_.tpdo1, tpdo1_count_);
        }
        break;
      case canopen::FrameKind::tpdo2:
        if (cls.node == node_id_ && layout_.tpdo2.count > 0) {
          on_tpdo(frame, layout_.tpdo2, tpdo2_count_);
        }
        break;
      case canopen::FrameKind::heartbeat:
        if (cls.node == node_id_) {
          if (const auto state = canopen::decode_heartbeat(frame)) {
            ++received_.heartbeats;
            if (watching_ && *state != canopen::NmtState::operational && !left_operational_) {
              spdlog::error("node {}: the drive left NMT operational (heartbeat state 0x{:02x})",
                            node_id_, static_cast<unsigned>(*state));
              wakeup_.update([&] { left_operational_ = true; });
            }
            publish();
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
            received_.last_emcy = emcy->error_code;
            ++emcys_;
            publish();
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

void DriveLink::send_sync(bool timed) noexcept {
  sync_counter_ = static_cast<std::uint8_t>(sync_counter_ % 240 + 1);
  // Our own frames are not received back: the RPDOs seen are forgotten here, in lockstep before
  // the SYNC goes out (the next cycle's RPDOs may come back at once). Only the lockstep wait reads
  // them, so the timer (realtime) does not take the lock at all: it is shared with non-realtime
  // threads, and the SYNC's time on the bus is what must not wait.
  if (!timed) {
    wakeup_.update([&] { rpdo_seen_.reset(); });
  }
  bus_->send(canopen::encode_sync(sync_counter_));
}

std::uint64_t DriveLink::malformed_count() const noexcept {
  return malformed_.load() + bus_->malformed_count();
}

}  // namespace mcnc::axisnode
