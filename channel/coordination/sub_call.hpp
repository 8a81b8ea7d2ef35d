#pragma once
// G144 / G145 (spec dafeng §3.4, ARCHITECTURE.md §5) as one channel sees them, on both sides:
//  - as caller: a G144 block checks its target (not this channel, not a caller that waits for
//    this channel's call, not gone, free: idle and running no call), waits while the target
//    still finishes an earlier call of this channel or is not up, sends the call and, with H1,
//    waits for its release; every outcome other than a release is an alarm;
//  - as target: calls come in, one is served at a time (others are refused), its caller is
//    released once, by G145, the called program's end (after its last repetition, L), its alarm
//    (failed) or a reset (aborted).
// What the channel does with a call it serves (loading and starting the program) is the
// channel's. Pure: partner statuses and events in, one step() per cycle, releases and calls out;
// no allocation, nothing throws.
#include "channel/coordination/channel_state.hpp"
#include "channel/coordination/coordination_alarm.hpp"
#include "channel/coordination/sync_barrier.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace mcnc::coordination {

inline constexpr int kCallArgs = 26;  // #1-#26

// A program started in another channel, and how the call ended.
enum class CallOutcome : std::uint8_t { released, refused, failed, aborted };
const char* to_string(CallOutcome outcome) noexcept;
struct CallRequest {
  std::uint64_t call_id = 0;  // caller << 40 | the caller's count of calls
  std::uint32_t caller = 0;
  std::uint32_t target = 0;
  int program = 0;
  bool wait = true;                      // H1
  int repeat = 1;                        // L
  std::array<double, kCallArgs> args{};  // #1-#26
  std::uint32_t args_given = 0;          // bit n-1: #n given
};
struct CallRelease {
  std::uint64_t call_id = 0;
  std::uint32_t caller = 0;
  std::uint32_t target = 0;  // the called channel, which sends the release
  CallOutcome outcome = CallOutcome::released;
};

// The call a channel serves: its request, the repetitions left, whether it released its caller.
struct ServedCall {
  CallRequest call;
  int repeats_left = 0;
  bool released = false;
};

enum class CallStep : std::uint8_t {
  pending,  // nothing to do this cycle (writes to go out first, or H1's release to come)
  waiting,  // the target is not free yet: the channel waits
  send,     // call() goes out; with call().wait the channel then waits for its release
  done,     // the block ends
  alarm,
};

class SubCall {
 public:
  static constexpr std::size_t kMaxIncoming = kMaxChannels;  // one per caller

  // `wait_cycles`: how long a call waits for its target to become free (0: as long as it takes).
  SubCall(std::uint32_t self, std::uint64_t wait_cycles) noexcept
      : self_(self), wait_cycles_(wait_cycles) {}

  // Partners, given before the cycle.
  void set_partner(std::uint32_t channel, const PartnerStatus& status) noexcept;
  // Calls to this channel; a call that finds the queue full is refused (returned).
  std::optional<CallRelease> on_call(const CallRequest& call) noexcept;
  void on_release(const CallRelease& release) noexcept;

  // --- caller side: a G144 block `call` (call_id not yet set) reached the front.
  void begin(const CallRequest& call) noexcept;
  // `lost`: partners whose process is gone; `writes_pending`: shared writes not out yet (the
  // called program sees what this channel wrote before the call).
  CallStep step(std::uint64_t cycle, const ChannelSet& lost, bool writes_pending) noexcept;
  void abandon() noexcept;  // no block under way (reset, new run): a late release is ignored
  [[nodiscard]] const CallRequest& call() const noexcept { return call_; }
  // H1: the channel the sent call waits for, 0 when none.
  [[nodiscard]] std::uint32_t waiting_for() const noexcept;
  // A call without wait (H0) that its target refused, once: the alarm to raise (while a program
  // runs), else nullptr.
  const CoordinationAlarm* take_refusal() noexcept;
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

  // --- target side.
  [[nodiscard]] std::span<const CallRequest> incoming() const noexcept {
    return {incoming_.data(), incoming_count_};
  }
  void clear_incoming() noexcept { incoming_count_ = 0; }
  [[nodiscard]] CallRelease refusal(const CallRequest& call) const noexcept {
    return CallRelease{call.call_id, call.caller, self_, CallOutcome::refused};
  }
  // Serves `call` from now on (the channel starts its program).
  void serve(const CallRequest& call) noexcept;
  [[nodiscard]] const ServedCall* served() const noexcept {
    return serving_ ? &*serving_ : nullptr;
  }
  // Ends the served call's hold on its caller, once: the release to send.
  std::optional<CallRelease> release_caller(CallOutcome outcome) noexcept;
  // The called program ended: true when it runs again (L), else the call is over.
  bool repeat_served() noexcept;
  void stop_serving() noexcept { serving_.reset(); }
  [[nodiscard]] std::uint64_t serving_call() const noexcept {
    return serving_ ? serving_->call.call_id : 0;
  }
  [[nodiscard]] std::uint32_t serving_caller() const noexcept {
    return serving_ ? serving_->call.caller : 0;
  }

 private:
  // The target is among the channels whose calls this channel runs (directly or through
  // others): calling it would wait for itself.
  [[nodiscard]] bool calls_back(std::uint32_t target) const noexcept;
  CallStep step_reached(std::uint64_t cycle, const ChannelSet& lost, bool writes_pending) noexcept;
  CallStep step_sent(const ChannelSet& lost) noexcept;

  std::uint32_t self_;
  std::uint64_t wait_cycles_;
  std::array<PartnerStatus, kMaxChannels + 1> partners_{};
  // A call sent and not yet seen running in the target's status nor ended: the target is not
  // free for another call from here until then.
  std::array<std::uint64_t, kMaxChannels + 1> outstanding_{};
  std::uint64_t calls_made_ = 0;
  // The block under way.
  bool active_ = false;
  CallRequest call_{};
  bool sent_ = false;
  bool waiting_for_target_ = false;  // the target still finishes an earlier call
  std::uint64_t waiting_since_ = 0;
  std::optional<CallRelease> ended_;    // the release of the call this channel waits for
  std::optional<CallRelease> refused_;  // a call without wait (H0) that the target refused
  CoordinationAlarm alarm_{};
  CoordinationAlarm refusal_{};
  // Served calls.
  std::array<CallRequest, kMaxIncoming> incoming_{};
  std::size_t incoming_count_ = 0;
  std::optional<ServedCall> serving_;
};

}  // namespace mcnc::coordination
