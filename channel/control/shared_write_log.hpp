#pragma once
// The writes this channel made to the shared macro variables (#500-#999, #20000-#20999) since
// they were last sent to the other channels, in the order made. The interpreter appends while
// the channel pulls commands; the wire adapter sends up to kSentPerCycle of them each cycle,
// before that cycle's G04.1 arrival or G144 call, and the channel arrives or calls only once
// the log is empty, so a value written before a wait mark is seen after it (ARCHITECTURE.md
// §5). Fixed size, no allocation; a full log counts what it could not keep (an alarm).
#include "channel/interp/macro/variable_store.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::channel {

struct SharedWrite {
  std::int64_t number = 0;
  interp::macro::MacroValue value;
};

class SharedWriteLog final : public interp::macro::SharedWriteSink {
 public:
  static constexpr std::size_t kCapacity = 4096;
  // Sent per cycle at most, so that a burst never outruns the event topic's history.
  static constexpr std::size_t kSentPerCycle = 32;

  void on_shared_write(std::int64_t number, interp::macro::MacroValue value) noexcept override {
    if (count_ == kCapacity) {
      ++lost_;
      return;
    }
    writes_[(head_ + count_) % kCapacity] = SharedWrite{number, value};
    ++count_;
  }
  // Hands the oldest `max` writes to `fn` in order and forgets them.
  template <class Fn>
  void drain(Fn fn, std::size_t max = kCapacity) {
    for (; count_ > 0 && max > 0; --count_, --max, head_ = (head_ + 1) % kCapacity) {
      fn(writes_[head_]);
    }
  }
  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] std::uint64_t lost() const noexcept { return lost_; }

 private:
  std::array<SharedWrite, kCapacity> writes_{};
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  std::uint64_t lost_ = 0;
};

}  // namespace mcnc::channel
