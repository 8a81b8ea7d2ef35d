#pragma once
// A value one thread publishes and another takes whole, without a lock: two slots, each with a
// sequence number (odd while written). The writer fills the slot that is not the latest and
// then names it the latest; the reader copies the latest and checks that it is still the
// latest and its sequence number did not move meanwhile, else copies again. A writer stopped in the
// middle of a write (preempted by the reader's higher priority) never holds the reader up: the slot
// it writes is not the one read. One writer; readers on any thread. T is trivially copyable. Never
// allocates.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace mcnc::cycle {

template <class T>
class DoubleBuffer {
  static_assert(std::is_trivially_copyable_v<T>, "a DoubleBuffer copies its value bytewise");

 public:
  explicit DoubleBuffer(const T& initial = T{}) noexcept {
    publish(initial);
    publish(initial);
  }
  DoubleBuffer(const DoubleBuffer&) = delete;
  DoubleBuffer& operator=(const DoubleBuffer&) = delete;

  // The writer's thread only.
  void publish(const T& value) noexcept {
    const std::uint32_t next = 1U - latest_.load(std::memory_order_relaxed);
    Slot& slot = slots_[next];
    const std::uint64_t seq = slot.seq.load(std::memory_order_relaxed);
    slot.seq.store(seq + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    std::array<std::uint64_t, kWords> words{};
    std::memcpy(words.data(), &value, sizeof(T));
    for (std::size_t i = 0; i < kWords; ++i) {
      slot.words[i].store(words[i], std::memory_order_relaxed);
    }
    slot.seq.store(seq + 2, std::memory_order_release);
    latest_.store(next, std::memory_order_release);
  }

  // The latest value published, whole.
  [[nodiscard]] T latest() const noexcept {
    std::array<std::uint64_t, kWords> words{};
    for (;;) {
      const std::uint32_t index = latest_.load(std::memory_order_acquire);
      const Slot& slot = slots_[index];
      const std::uint64_t before = slot.seq.load(std::memory_order_acquire);
      if ((before & 1U) != 0) {
        continue;  // the writer came round to this slot again: take the newer one
      }
      for (std::size_t i = 0; i < kWords; ++i) {
        words[i] = slot.words[i].load(std::memory_order_relaxed);
      }
      std::atomic_thread_fence(std::memory_order_acquire);
      // Still the latest, and not written meanwhile: else the slot named latest when the read
      // began may have been filled anew, ahead of the other's turn, and be newer than what
      // the next read would find.
      if (slot.seq.load(std::memory_order_relaxed) == before &&
          latest_.load(std::memory_order_relaxed) == index) {
        break;
      }
    }
    T value;
    std::memcpy(static_cast<void*>(&value), words.data(), sizeof(T));
    return value;
  }

 private:
  static constexpr std::size_t kWords =
      (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);
  struct Slot {
    std::atomic<std::uint64_t> seq{0};
    std::array<std::atomic<std::uint64_t>, kWords> words{};
  };
  std::array<Slot, 2> slots_{};
  std::atomic<std::uint32_t> latest_{0};
};

}  // namespace mcnc::cycle
