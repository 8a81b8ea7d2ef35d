#pragma once
// The order in which a deciding process (an axis node, the PLC) takes requests that reached it
// in any order: the cycle they were sent, then the sender's channel number, then arrival. Every
// run of the same programs therefore decides the same way.
#include <array>
#include <cstddef>

namespace mcnc::cycle {

// Inserts `request` into `queue[0, count)` kept in decision order; false when full. `T` has
// `sent_cycle` and `channel`.
template <class T, std::size_t N>
bool insert_in_decision_order(std::array<T, N>& queue, std::size_t& count,
                              const T& request) noexcept {
  if (count == N) {
    return false;
  }
  std::size_t at = count;
  while (at > 0 && (queue[at - 1].sent_cycle > request.sent_cycle ||
                    (queue[at - 1].sent_cycle == request.sent_cycle &&
                     queue[at - 1].channel > request.channel))) {
    queue[at] = queue[at - 1];
    --at;
  }
  queue[at] = request;
  ++count;
  return true;
}

}  // namespace mcnc::cycle
