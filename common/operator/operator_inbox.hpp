#pragma once
// Operator commands waiting for the cycle they take effect at. Commands arrive at any time (a
// DDS thread); the cyclic loop takes the ones that are due. Deterministic in lockstep: a
// command stamped with a cycle takes effect at exactly that cycle, however early it arrived.
// Fixed size, no allocation.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace mcnc::process {

enum class OperatorActionKind : std::uint8_t {
  none,
  reset,
  cycle_start,
  feed_hold,
  feed_override,     // value: percent
  rapid_override,    // value: percent
  spindle_override,  // value: percent
  single_block,      // value: 1 on, 0 off
  select_program,    // text: a file of the program store
  mdi,               // text: one block
  alarm_ack          // value: the alarm's seq
};

const char* to_string(OperatorActionKind action) noexcept;
// The action of that name (to_string's), none when there is no such action.
OperatorActionKind action_named(std::string_view name) noexcept;

struct OperatorRequest {
  std::uint64_t seq = 0;
  std::uint64_t generation = 0;  // run generation it belongs to; 0: whichever runs
  std::uint64_t cycle = 0;       // takes effect at this cycle; 0: at the next one
  std::uint32_t channel = 0;     // 0: the whole machine
  OperatorActionKind action = OperatorActionKind::none;
  double value = 0.0;
  // SELECT_PROGRAM, MDI: NUL-terminated; a longer text does not fit and is refused on arrival.
  static constexpr std::size_t kTextSize = 128;
  std::array<char, kTextSize> text{};
  // For the channel with this id (an axis node: of its owner channel).
  [[nodiscard]] bool concerns(std::uint32_t channel_id) const noexcept {
    return channel == 0 || channel == channel_id;
  }
};

// A command stamped `stamp` waits past the next cycle after `cycle` (the last one run).
[[nodiscard]] constexpr bool due_after_next(std::uint64_t stamp, std::uint64_t cycle) noexcept {
  return stamp > cycle && stamp - cycle > 1;
}

class OperatorInbox {
 public:
  static constexpr std::size_t kSlots = 32;
  // Keeps the request until it is due; false (dropped) when the inbox is full.
  bool put(const OperatorRequest& request) noexcept;
  // The oldest request due at `cycle` (its cycle reached) in run `generation`; requests of
  // another run are dropped on the way.
  std::optional<OperatorRequest> take_due(std::uint64_t cycle, std::uint64_t generation) noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  // How many are due only after the next cycle after `cycle` (due_after_next).
  [[nodiscard]] std::size_t count_due_after_next(std::uint64_t cycle) const noexcept;

 private:
  void remove(std::size_t index) noexcept;

  std::array<OperatorRequest, kSlots> slots_{};  // in arrival order
  std::size_t count_ = 0;
};

}  // namespace mcnc::process
