#pragma once
// G04.1 meetings from the channels' arrival events, for the HMI's timeline: the partners of a
// mark meet when the last of them arrives there in the same round. Taken from the events, not
// from sampled states, so that a mark passed within a state frame still shows. Pure.
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>

namespace mcnc::hmi {

struct Meeting {
  std::int32_t p = 0;
  std::uint64_t channels = 0;  // bit c-1 for channel c
  std::uint64_t cycle = 0;     // the last arrival's
};

class MeetingTracker {
 public:
  // One channel's arrival at mark `p` in its round `round`, with the mark's participants as it
  // names them. The meeting, when this was the last of them.
  std::optional<Meeting> arrive(std::uint32_t channel, std::int32_t p, std::uint64_t round,
                                std::uint64_t participants, std::uint64_t cycle);

 private:
  struct Gathering {
    std::uint64_t arrived = 0;
    std::uint64_t cycle = 0;
  };
  // By mark, round and participants; a meeting is forgotten once complete.
  std::map<std::tuple<std::int32_t, std::uint64_t, std::uint64_t>, Gathering> open_;
};

}  // namespace mcnc::hmi
