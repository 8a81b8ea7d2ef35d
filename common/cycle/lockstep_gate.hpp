#pragma once
// The lockstep cycle rule (ARCHITECTURE.md §4): a process runs cycle N only when every input it
// expects holds a sample stamped N-1, and every event those samples announce (the sender's last
// event sequence number) has arrived. Cycle 0 needs nothing. An input that is lost (its writer
// left) is no longer expected, so the consumer can go on to its safe state.
#include "common/cycle/cycle_buffer.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mcnc::cycle {

class LockstepGate {
 public:
  explicit LockstepGate(std::size_t inputs);  // allocates here, never afterwards

  // A cyclic sample from `input` stamped `cycle`, announcing its sender's last event sequence.
  void on_sample(std::size_t input, std::uint64_t cycle,
                 std::uint64_t announced_event_seq) noexcept;
  // An event with sequence `seq` (1, 2, ...) from `input`'s sender. Events may arrive out of
  // order; only a contiguous run from 1 counts as received.
  void on_event(std::size_t input, std::uint64_t seq) noexcept;
  void set_expected(std::size_t input, bool expected) noexcept;

  [[nodiscard]] bool may_run(std::uint64_t cycle) const noexcept;
  // The first expected input that keeps cycle `cycle` from running.
  [[nodiscard]] std::optional<std::size_t> first_missing(std::uint64_t cycle) const noexcept;
  [[nodiscard]] std::uint64_t events_received(std::size_t input) const noexcept;
  // Why cycle `cycle` cannot run, for a log line when a wait is slow: the first expected input
  // that keeps it, the latest cycle that input has a sample of, and the events the sample
  // stamped cycle-1 announces against those received in order.
  struct Wait {
    std::size_t input = 0;
    bool sample_missing = false;  // no sample stamped cycle-1 (else: its events are missing)
    bool any_sample = false;      // a sample of any cycle arrived
    std::uint64_t latest_cycle = 0;
    std::uint64_t events_announced = 0;
    std::uint64_t events_received = 0;
  };
  [[nodiscard]] std::optional<Wait> wait(std::uint64_t cycle) const noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return inputs_.size(); }

 private:
  [[nodiscard]] bool input_ready(std::size_t input, std::uint64_t cycle) const noexcept;

  struct Input {
    CycleBuffer<std::uint64_t, 16> announced;  // cycle -> announced event seq
    std::uint64_t events_contiguous = 0;       // highest seq with all before it received
    std::uint64_t events_ahead = 0;            // bit k: seq events_contiguous + 2 + k received
    bool expected = true;
  };
  std::vector<Input> inputs_;
};

}  // namespace mcnc::cycle
