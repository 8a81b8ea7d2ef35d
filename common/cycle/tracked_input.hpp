#pragma once
// One cyclic input of a process as the lockstep rule sees it (ARCHITECTURE.md §4): the samples
// of its last Depth cycles, the writer they came from, whether that writer has left, and the
// input's slot in the process's LockstepGate. The one place where "a sample is in" and "its
// writer is gone" are kept for the gate: the adapters in each process's wire/ folder feed it
// from their DDS callbacks (under the node's wake-up lock) and the cycle reads it. Fixed
// capacity: no allocation, nothing throws.
#include "common/cycle/cycle_buffer.hpp"
#include "common/cycle/lockstep_gate.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mcnc::cycle {

template <class Sample, std::size_t Depth = 8>
class TrackedInput {
 public:
  // A DDS writer's GUID, as dds::WriterId carries it.
  using WriterId = std::array<std::uint8_t, 16>;

  TrackedInput() = default;
  explicit TrackedInput(std::size_t gate_input) noexcept : gate_input_(gate_input) {}

  // A sample stamped `cycle` from `writer`, announcing its sender's last event sequence number
  // (0 for a sender without events).
  void on_sample(const Sample& sample, std::uint64_t cycle, std::uint64_t announced_event_seq,
                 const WriterId& writer, LockstepGate& gate) noexcept {
    samples_.put(cycle, sample);
    writer_ = writer;
    heard_ = true;
    gate.on_sample(gate_input_, cycle, announced_event_seq);
  }
  // An event with sequence `seq` from this input's sender, for the gate.
  void on_event(std::uint64_t seq, LockstepGate& gate) const noexcept {
    gate.on_event(gate_input_, seq);
  }
  // A writer of the input's topic unmatched. When it is the one this input heard, the input is
  // lost and the gate expects it no more, so the process can go on to its safe state: true then.
  bool on_unmatched(const WriterId& writer, LockstepGate& gate) noexcept {
    if (!heard_ || writer != writer_) {
      return false;
    }
    lose(gate);
    return true;
  }
  // The input is lost for another reason (realtime: its samples stopped coming in time).
  void lose(LockstepGate& gate) noexcept {
    lost_ = true;
    gate.set_expected(gate_input_, false);
  }

  // The sample cycle `cycle` runs with: the one stamped cycle-1; in realtime the latest when
  // that one is not in. nullptr when there is none. A lost input keeps its last samples: the
  // caller decides what they still mean.
  [[nodiscard]] const Sample* for_cycle(std::uint64_t cycle, bool lockstep) const noexcept {
    const Sample* s = cycle > 0 ? samples_.at(cycle - 1) : nullptr;
    return s == nullptr && !lockstep ? samples_.latest() : s;
  }
  [[nodiscard]] const Sample* latest() const noexcept { return samples_.latest(); }

  [[nodiscard]] bool heard() const noexcept { return heard_; }
  [[nodiscard]] bool lost() const noexcept { return lost_; }
  // Lost, and not yet taken by take_loss().
  [[nodiscard]] bool loss_pending() const noexcept { return lost_ && !loss_taken_; }
  // True once, at the first call after the input was lost: to raise its alarm one time.
  [[nodiscard]] bool take_loss() noexcept {
    if (!loss_pending()) {
      return false;
    }
    loss_taken_ = true;
    return true;
  }
  [[nodiscard]] std::size_t gate_input() const noexcept { return gate_input_; }

 private:
  CycleBuffer<Sample, Depth> samples_;
  WriterId writer_{};
  std::size_t gate_input_ = 0;
  bool heard_ = false;
  bool lost_ = false;
  bool loss_taken_ = false;
};

// `count` inputs on the gate's slots `first` .. first + count - 1 (at set-up: it allocates).
template <class Sample, std::size_t Depth = 8>
std::vector<TrackedInput<Sample, Depth>> tracked_inputs(std::size_t first, std::size_t count) {
  std::vector<TrackedInput<Sample, Depth>> made;
  made.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    made.emplace_back(first + i);
  }
  return made;
}

}  // namespace mcnc::cycle
