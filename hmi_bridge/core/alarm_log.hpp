#pragma once
// The alarms an HMI has seen, newest last, with whether an operator has acknowledged each.
// An alarm is known by its source process and that process's sequence number. Pure.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>

namespace mcnc::hmi {

struct AlarmEntry {
  std::string src;  // process name: CH1, X1, launch, ...
  std::uint64_t seq = 0;
  std::uint32_t number = 0;
  std::string text;
  std::int32_t channel = 0;  // channel id, 0: none
  std::int32_t axis = 0;
  std::int32_t line = 0;
  std::string program;      // the file `line` is in (a called program's), empty: none
  std::int32_t column = 0;  // 0: not known
  std::uint64_t cycle = 0;
  bool acknowledged = false;
};

class AlarmLog {
 public:
  static constexpr std::size_t kKept = 500;  // the oldest go first

  // False when that alarm is already in the log (DDS delivers a kept alarm to a late reader).
  bool add(AlarmEntry entry);
  // The acknowledged entry, or nullptr when the log does not hold it (or it was already).
  const AlarmEntry* acknowledge(std::string_view src, std::uint64_t seq);
  [[nodiscard]] const std::deque<AlarmEntry>& entries() const noexcept { return entries_; }

 private:
  AlarmEntry* find(std::string_view src, std::uint64_t seq);
  std::deque<AlarmEntry> entries_;
};

}  // namespace mcnc::hmi
