#include "common/operator/operator_inbox.hpp"

namespace mcnc::process {

const char* to_string(OperatorActionKind action) noexcept {
  switch (action) {
    case OperatorActionKind::none:
      return "none";
    case OperatorActionKind::reset:
      return "reset";
    case OperatorActionKind::cycle_start:
      return "cycle_start";
    case OperatorActionKind::feed_hold:
      return "feed_hold";
    case OperatorActionKind::feed_override:
      return "feed_override";
    case OperatorActionKind::rapid_override:
      return "rapid_override";
    case OperatorActionKind::spindle_override:
      return "spindle_override";
    case OperatorActionKind::single_block:
      return "single_block";
    case OperatorActionKind::select_program:
      return "select_program";
    case OperatorActionKind::mdi:
      return "mdi";
    case OperatorActionKind::alarm_ack:
      return "alarm_ack";
  }
  return "none";
}

OperatorActionKind action_named(std::string_view name) noexcept {
  for (auto k = static_cast<int>(OperatorActionKind::reset);
       k <= static_cast<int>(OperatorActionKind::alarm_ack); ++k) {
    const auto action = static_cast<OperatorActionKind>(k);
    if (name == to_string(action)) {
      return action;
    }
  }
  return OperatorActionKind::none;
}

bool OperatorInbox::put(const OperatorRequest& request) noexcept {
  if (count_ == kSlots) {
    return false;
  }
  slots_[count_++] = request;
  return true;
}

std::size_t OperatorInbox::count_due_after_next(std::uint64_t cycle) const noexcept {
  std::size_t later = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    later += process::due_after_next(slots_[i].cycle, cycle) ? 1 : 0;
  }
  return later;
}

void OperatorInbox::remove(std::size_t index) noexcept {
  for (std::size_t i = index + 1; i < count_; ++i) {
    slots_[i - 1] = slots_[i];
  }
  --count_;
}

std::optional<OperatorRequest> OperatorInbox::take_due(std::uint64_t cycle,
                                                       std::uint64_t generation) noexcept {
  std::size_t i = 0;
  while (i < count_) {
    const OperatorRequest r = slots_[i];
    if (r.generation != 0 && r.generation != generation) {
      remove(i);
      continue;
    }
    if (r.cycle <= cycle) {
      remove(i);
      return r;
    }
    ++i;
  }
  return std::nullopt;
}

}  // namespace mcnc::process
