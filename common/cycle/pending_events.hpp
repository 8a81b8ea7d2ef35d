#pragma once
// Events that take effect from the cycle after the one they were sent in (ARCHITECTURE.md §4),
// kept in the order they arrived until then. Fixed capacity: no allocation, nothing throws.
#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::cycle {

template <class Event, std::size_t Capacity>
class PendingEvents {
 public:
  // False (and the event dropped) when full.
  bool push(const Event& event, std::uint64_t sent_cycle) noexcept {
    if (count_ == Capacity) {
      return false;
    }
    entries_[count_++] = Entry{event, sent_cycle};
    return true;
  }

  // Hands the events sent before `cycle` to `apply`, in arrival order, and forgets them.
  template <class Apply>
  void take_due(std::uint64_t cycle, Apply&& apply) noexcept {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < count_; ++i) {
      if (entries_[i].sent_cycle < cycle) {
        apply(entries_[i].event);
      } else {
        entries_[kept++] = entries_[i];
      }
    }
    count_ = kept;
  }

  // The same events, left in place.
  template <class Visit>
  void peek_due(std::uint64_t cycle, Visit&& visit) const noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      if (entries_[i].sent_cycle < cycle) {
        visit(entries_[i].event);
      }
    }
  }

  [[nodiscard]] std::size_t size() const noexcept { return count_; }

 private:
  struct Entry {
    Event event{};
    std::uint64_t sent_cycle = 0;
  };
  std::array<Entry, Capacity> entries_{};
  std::size_t count_ = 0;
};

}  // namespace mcnc::cycle
