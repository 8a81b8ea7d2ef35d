#pragma once
// G140 / G141 / G142 (spec dafeng §3.3) as one channel sees them, and what the channel does with
// each of its axis slots meanwhile. The axis node is the authority on ownership (ARCHITECTURE.md
// §5): the channel asks, and reads the answer from the node's feedback. A slot is commanded,
// virtual, away, follows or under speed control (SlotUse); this unit keeps that table for the
// channel:
//  - a commanded axis that another channel took (G141 P1), or whose node follows a master
//    (G51.4), stops being commanded; the channel learns which (update()) to stop a program that
//    still moves it;
//  - a borrowed axis granted after the channel stopped waiting for it is given back at once;
//  - at a program start and at G141's / G142's end, owned slots are taken over from where their
//    axes stand.
// A release ends once the node shows another owner, an acquire once it shows this channel, a
// restore once no axis is away on this channel's account; a refusal, or a node that cannot keep
// the request, is an alarm. Pure: one step() per cycle with that cycle's feedback; requests go
// out through requests(); no allocation, nothing throws.
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/coordination_alarm.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace mcnc::coordination {

// G140/G141/G142 as the channel asks its axis nodes.
enum class AxisRequestKind : std::uint8_t { release, acquire, restore, withdraw };
const char* to_string(AxisRequestKind kind) noexcept;
struct AxisRequestOut {
  AxisRequestKind kind = AxisRequestKind::acquire;
  std::size_t slot = 0;  // restore: kAllSlots
  bool force = false;    // G141 P1
  static constexpr std::size_t kAllSlots = ~std::size_t{0};
};

struct ExchangeSetup {
  std::uint32_t channel_id = 1;
  std::size_t axis_count = 0;
  std::vector<AxisSlot> slots;                // empty: every axis is the channel's own for good
  std::optional<std::size_t> spindle_c_slot;  // under SpindleMode's rule, not this one's
};

enum class ExchangeStep : std::uint8_t {
  sent,     // the request is out (requests()): the channel waits
  waiting,  // for the answer in the feedback
  done,     // the block ends; took_over(): owned slots were taken over (positions moved)
  alarm,
};

// A slot the channel stopped commanding this cycle, and why ("was taken by channel 2: ...").
struct SlotLoss {
  std::size_t slot = 0;
  std::array<char, 64> why{};
};

class AxisExchange {
 public:
  static constexpr std::size_t kMaxSlots = 8;
  static constexpr std::size_t kMaxRequests = 4;  // requests out in one cycle at most

  explicit AxisExchange(ExchangeSetup setup);

  [[nodiscard]] bool exchanges() const noexcept { return !setup_.slots.empty(); }
  [[nodiscard]] SlotUse use(std::size_t slot) const noexcept { return use_[slot]; }
  [[nodiscard]] std::span<const SlotUse> uses() const noexcept { return use_; }
  void set_use(std::size_t slot, SlotUse use) noexcept { use_[slot] = use; }

  // Cycle start: this cycle's requests are none yet.
  void begin_cycle() noexcept { request_count_ = 0; }
  // What slot `slot`'s feedback `f` says (each slot, before anything else in the cycle): the
  // slot the channel stops commanding, if it does.
  std::optional<SlotLoss> update(std::size_t slot, const AxisFeedbackView& f) noexcept;
  // Owned slots are taken over from where their axes stand (into `commanded`); the others are
  // virtual (exchange slots) or away (the channel's own axes).
  void settle(std::span<const AxisFeedbackView> feedback, std::span<double> commanded) noexcept;
  // The first slot a move from `from` to `to` moves and the channel does not command (away,
  // following its master, or the spindle under speed control).
  [[nodiscard]] std::optional<std::size_t> foreign_slot(std::span<const double> from,
                                                        std::span<const double> to) const noexcept;
  // Why a block may not move `slot` (foreign_slot()), as the program alarm it raises.
  [[nodiscard]] CoordinationAlarm foreign_move_alarm(
      std::size_t slot, std::span<const AxisFeedbackView> feedback) const noexcept;

  // A block G140 (release) / G141 (acquire, `force`: P1) of `slot`, or G142 (restore).
  void begin(AxisRequestKind kind, std::size_t slot, bool force) noexcept;
  ExchangeStep step(std::uint64_t cycle, std::span<const AxisFeedbackView> feedback,
                    std::span<double> commanded) noexcept;
  // The channel stops waiting (alarm, reset): a sent G141/G142 is withdrawn at the nodes.
  void withdraw() noexcept;
  // No block under way any more.
  void abandon() noexcept { active_ = false; }
  [[nodiscard]] bool took_over() const noexcept { return took_over_; }
  // The block's G code (140, 141, 142) while its request is out, else 0; and its slot.
  [[nodiscard]] int waiting_g() const noexcept;
  [[nodiscard]] std::size_t waiting_slot() const noexcept {
    return kind_ == AxisRequestKind::restore ? AxisRequestOut::kAllSlots : slot_;
  }

  [[nodiscard]] std::span<const AxisRequestOut> requests() const noexcept {
    return {requests_.data(), request_count_};
  }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  void push(AxisRequestKind kind, std::size_t slot, bool force) noexcept;
  // Slot `s`'s axis is away on this channel's account (G142 waits until none is): its own axis
  // elsewhere, or one it borrowed or released not back home.
  [[nodiscard]] bool away_on_own_account(std::size_t s, const AxisFeedbackView& f) const noexcept;
  // Alarm 1232 when an axis node refused the block's request or could not keep it.
  bool refused(std::span<const AxisFeedbackView> feedback) noexcept;

  ExchangeSetup setup_;
  std::array<SlotUse, kMaxSlots> use_{};
  std::array<bool, kMaxSlots> unasked_released_{};  // a grant it did not wait for, given back
  std::array<AxisRequestOut, kMaxRequests> requests_{};
  std::size_t request_count_ = 0;
  // The block under way.
  bool active_ = false;
  AxisRequestKind kind_ = AxisRequestKind::restore;
  std::size_t slot_ = 0;
  bool force_ = false;
  bool sent_ = false;
  std::uint64_t sent_cycle_ = 0;
  bool took_over_ = false;
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
