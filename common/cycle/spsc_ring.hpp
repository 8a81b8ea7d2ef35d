#pragma once
// A fixed-capacity ring from one producer thread to one consumer thread, without a lock. Its
// slots are built once and reused: the producer fills the slot claim() gives it in place and
// publishes it; the consumer reads the slot front() gives it in place and pops it. A slot's
// members keep their capacity from one use to the next, so a producer that assigns into them
// allocates only when a value is larger than any before it, and the consumer never does.
// The consumer may wait for the next slot (C++20 atomic wait: a futex, never a mutex), which a
// real-time consumer does not do; a producer waiting for room needs a signal of its own.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace mcnc::cycle {

template <class T, std::size_t Capacity>
class SpscRing {
  static_assert(Capacity > 0 && (Capacity & (Capacity - 1)) == 0, "a power of two");

 public:
  SpscRing() = default;
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  // Producer: the next free slot, or nullptr when the ring is full. It is the consumer's only
  // after publish().
  [[nodiscard]] T* claim() noexcept {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    // Pairs with pop_was_full(): a producer that finds the ring full, or the consumer that pops
    // it, sees the other's last write.
    std::atomic_thread_fence(std::memory_order_seq_cst);
    if (tail - head_.load(std::memory_order_acquire) == Capacity) {
      return nullptr;
    }
    return &slots_[tail % Capacity];
  }
  // Producer: hands the claimed slot to the consumer.
  void publish() noexcept {
    tail_.store(tail_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
    tail_.notify_one();
  }
  // Consumer: the oldest published slot, or nullptr when there is none.
  [[nodiscard]] T* front() noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (tail_.load(std::memory_order_acquire) == head) {
      return nullptr;
    }
    return &slots_[head % Capacity];
  }
  // Consumer: gives the front slot back to the producer.
  void pop() noexcept {
    head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  // Consumer: pop(), and whether the ring was full before it. A producer waits for room only
  // after claim() found it full, so only such a pop needs to wake it: a consumer that tells it
  // of every pop pays a wake-up of the producer's thread per slot for nothing.
  [[nodiscard]] bool pop_was_full() noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    head_.store(head + 1, std::memory_order_release);
    std::atomic_thread_fence(std::memory_order_seq_cst);
    return tail_.load(std::memory_order_relaxed) - head == Capacity;
  }
  // Consumer: waits until a slot is published.
  void wait_for_item() const noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    for (std::uint64_t tail = tail_.load(std::memory_order_acquire); tail == head;
         tail = tail_.load(std::memory_order_acquire)) {
      tail_.wait(tail, std::memory_order_acquire);
    }
  }

  [[nodiscard]] std::size_t size() const noexcept {
    return static_cast<std::size_t>(tail_.load(std::memory_order_acquire) -
                                    head_.load(std::memory_order_acquire));
  }
  static constexpr std::size_t capacity() noexcept { return Capacity; }

 private:
  std::array<T, Capacity> slots_{};
  alignas(64) std::atomic<std::uint64_t> head_{0};  // popped so far (the consumer's)
  alignas(64) std::atomic<std::uint64_t> tail_{0};  // published so far (the producer's)
};

}  // namespace mcnc::cycle
