#include "hmi_bridge/core/alarm_log.hpp"

namespace mcnc::hmi {

AlarmEntry* AlarmLog::find(std::string_view src, std::uint64_t seq) {
  for (AlarmEntry& e : entries_) {
    if (e.seq == seq && e.src == src) {
      return &e;
    }
  }
  return nullptr;
}

bool AlarmLog::add(AlarmEntry entry) {
  if (find(entry.src, entry.seq) != nullptr) {
    return false;
  }
  entries_.push_back(std::move(entry));
  if (entries_.size() > kKept) {
    entries_.pop_front();
  }
  return true;
}

const AlarmEntry* AlarmLog::acknowledge(std::string_view src, std::uint64_t seq) {
  AlarmEntry* e = find(src, seq);
  if (e == nullptr || e->acknowledged) {
    return nullptr;
  }
  e->acknowledged = true;
  return e;
}

}  // namespace mcnc::hmi
