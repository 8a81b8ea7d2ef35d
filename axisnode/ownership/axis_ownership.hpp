#pragma once
// Who may command one axis: the axis node is the authority (ARCHITECTURE.md §5), so that an
// axis has exactly one writer at any time, also when two channels race for it. The channels ask
// with G140 (release), G141 (acquire; P1 forces) and G142 (restore the configured owner), spec
// dafeng §3.3; the node decides once per cycle from the requests sent before that cycle, in a
// fixed order (the cycle they were sent, then the channel number), so every run of the same
// programs gives the same owners. Pure and fixed-size: requests in, the owner out; no
// allocation, no exceptions.
//
// What this decides:
//  - release: only the owner releases; the axis then has no owner until someone acquires it.
//  - acquire: granted at once when the axis has no owner (or the asker owns it); otherwise the
//    asker waits, in order, until the owner releases. A forced acquire takes the axis from its
//    owner as soon as the axis is at rest (spec "decide" 4: not in the middle of a move).
//  - restore: a channel that owns the axis, or released it to its present owner, gives it back
//    to the configured (home) owner once it is at rest (spec "decide" 1); the home channel
//    itself takes its axis back from anyone. Waiting acquires of that channel are dropped.
//  - withdraw: the channel no longer waits; it goes before anything of its cycle is granted.
//  - an axis granted in a decision is not taken away (forced or restored) in the same
//    decision, before its new owner has heard of it; a release goes to the first in line
//    before any request of the same cycle.
//  - a reset or an E-stop changes nothing (spec L5635-5637); a restart of the node starts with
//    the configured owner.
//  - a channel that is gone (its process ended) loses its waiting requests; an axis it owns
//    stays owned (and stopped by the node's own safety) until a restore or a forced acquire.
#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::ownership {

// withdraw: the channel no longer waits (a reset ended its G141); drops its waiting requests.
enum class OwnershipRequestKind : std::uint8_t { release, acquire, restore, withdraw };

struct OwnershipRequest {
  OwnershipRequestKind kind = OwnershipRequestKind::acquire;
  std::uint32_t channel = 0;  // 1-based channel number
  bool force = false;         // acquire: G141 P1
  std::uint64_t sent_cycle = 0;
};

// What a request came to, for the asking channel.
enum class OwnershipAnswer : std::uint8_t {
  none,     // nothing decided yet (a waiting acquire, a forced one while the axis moves)
  granted,  // acquire: the channel owns the axis; restore: the home owner has it again
  released,
  refused,  // release or restore by a channel with no say over the axis
  full,     // more waiting requests than the node keeps (an alarm in the asker)
};

struct OwnershipChange {
  bool changed = false;        // the owner is another one than before this cycle
  std::uint32_t previous = 0;  // 0: none
  std::uint32_t owner = 0;     // 0: released, nobody commands the axis
  bool forced = false;         // taken from its owner by G141 P1
};

class AxisOwnership {
 public:
  static constexpr std::size_t kMaxWaiting = 64;

  explicit AxisOwnership(std::uint32_t home) noexcept : home_(home), owner_(home) {}

  // A request to decide in the next decide(). False when the cycle's queue is full: the asker
  // is then answered `full` (full_channels()) by that decide().
  bool request(const OwnershipRequest& request) noexcept;
  // Decides this cycle's requests in order, then the waiting acquires; `at_rest`: the axis
  // stands (no motion commanded), so a forced acquire or a restore may take it now.
  OwnershipChange decide(bool at_rest) noexcept;
  // The answers of the last decide(): one per channel that got one (request order).
  struct Answer {
    std::uint32_t channel = 0;
    OwnershipRequestKind kind = OwnershipRequestKind::acquire;
    OwnershipAnswer answer = OwnershipAnswer::none;
  };
  [[nodiscard]] const Answer* answers() const noexcept { return answers_.data(); }
  [[nodiscard]] std::size_t answer_count() const noexcept { return answer_count_; }
  // The channels whose latest request was refused, and those whose latest did not fit in the
  // queue (bit c-1 for channel c, 1-64; a channel above 64 is never refused for lack of a
  // bit: it has none). The node sends both in its feedback, so the asker alarms instead of
  // waiting for ever. A bit stays until the channel's next request is decided: a reader of the
  // newest feedback alone (realtime) does not miss it.
  [[nodiscard]] std::uint64_t refused_channels() const noexcept { return refused_; }
  [[nodiscard]] std::uint64_t full_channels() const noexcept { return full_; }

  // The channel whose process is gone: its waiting requests are dropped.
  void channel_gone(std::uint32_t channel) noexcept;

  [[nodiscard]] std::uint32_t owner() const noexcept { return owner_; }
  [[nodiscard]] std::uint32_t home() const noexcept { return home_; }
  // The channel that released the axis to its present state (0: the configured assignment).
  [[nodiscard]] std::uint32_t released_by() const noexcept { return released_by_; }
  [[nodiscard]] bool waiting(std::uint32_t channel) const noexcept;
  [[nodiscard]] std::size_t waiting_count() const noexcept { return waiting_count_; }

 private:
  void answer(std::uint32_t channel, OwnershipRequestKind kind, OwnershipAnswer a) noexcept;
  void wait(const OwnershipRequest& r) noexcept;
  void drop_waiting(std::uint32_t channel) noexcept;
  void set_owner(std::uint32_t owner, bool forced) noexcept;

  std::uint32_t home_;
  std::uint32_t owner_;
  std::uint32_t released_by_ = 0;
  // This cycle's requests, then the ones waiting from earlier cycles (each in order).
  std::array<OwnershipRequest, kMaxWaiting> incoming_{};
  std::size_t incoming_count_ = 0;
  std::array<OwnershipRequest, kMaxWaiting> waiting_{};
  std::size_t waiting_count_ = 0;
  std::array<Answer, 2 * kMaxWaiting> answers_{};
  std::size_t answer_count_ = 0;
  std::uint64_t refused_ = 0;
  std::uint64_t full_ = 0;
  std::uint64_t full_pending_ = 0;  // requests of this cycle that did not fit
  OwnershipChange change_{};
  bool granted_now_ = false;  // the axis got an owner in this decision: nobody takes it now
};

}  // namespace mcnc::ownership
