#pragma once
// A host's clock against machine time from two-way exchanges, as PTP's delay request
// mechanism measures it (docs/multichannel.md "One machine clock"). Pure: the times come in,
// the estimate goes out.
//
// An exchange: the host sends at t1 (its clock), the reference receives at t2 and answers at
// t3 (machine time), the host receives at t4. With the one-way delays d1 (there) and d2
// (back), t2 - t1 = d1 - offset and t4 - t3 = d2 + offset, where offset is the host's clock
// minus machine time. Their difference gives the offset up to (d2 - d1) / 2, which is at most
// half the round trip (t4 - t1) - (t3 - t2): the exchange with the shortest round trip bounds
// the offset most tightly, and a loaded host or a repaired sample only lengthens a round trip.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace mcnc::clock {

struct ClockExchange {
  std::int64_t t1_ns = 0;  // host: the probe sent
  std::int64_t t2_ns = 0;  // reference: the probe received
  std::int64_t t3_ns = 0;  // reference: the answer sent
  std::int64_t t4_ns = 0;  // host: the answer received
};

struct ClockOffset {
  std::int64_t offset_ns = 0;  // the host's clock minus machine time
  std::int64_t error_ns = 0;   // the true offset is within offset_ns +- error_ns
  std::uint32_t samples = 0;   // exchanges in the window
};

// The estimate it gives is held: a window whose best exchange bounds the offset less tightly
// than the held estimate, allowing for the clocks' drift since (kDriftPpm), does not replace it.
// A host whose launcher is starved for a while (a realtime machine on its cores) then keeps
// the good estimate it had instead of taking one off by half a long round trip.
class ClockOffsetFilter {
 public:
  // The drift allowed between two hosts' clocks: crystals are within 50 ppm each.
  static constexpr std::int64_t kDriftPpm = 100;
  // The window: the latest kWindow exchanges. Short, so that a host clock's drift against the
  // reference (a few ppm between crystals) moves the estimate within seconds.
  static constexpr std::size_t kWindow = 16;
  // No estimate before this many exchanges: a single one may have met a busy host.
  static constexpr std::uint32_t kMinSamples = 8;

  // Adds an exchange; false (and ignored) when its times cannot be: an answer before its
  // probe, or a reference that answered before it received.
  bool add(const ClockExchange& exchange) noexcept;
  // The held estimate: from the exchange of the window with the shortest round trip, once
  // kMinSamples exchanges are in, kept until a window bounds the offset at least as tightly
  // (with the drift allowance since); none before.
  [[nodiscard]] std::optional<ClockOffset> estimate() const noexcept { return held_; }

 private:
  struct Entry {
    std::int64_t offset_ns;
    std::int64_t round_trip_ns;
  };
  std::array<Entry, kWindow> window_{};
  std::size_t next_ = 0;
  std::uint32_t count_ = 0;
  std::optional<ClockOffset> held_;
  std::int64_t held_at_ns_ = 0;  // the host's clock when the held estimate was taken
};

}  // namespace mcnc::clock
