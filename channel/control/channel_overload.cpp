// G10 L14 P7/P8 at run time (spec dafeng L4895-5093, decision 162): a drilling or tapping
// cycle's in-feed, held as a read-ahead stop, runs with its axes' loads watched by the rule of
// G10 L14 P1 (coordination::LoadMonitor over the G01 under way). On an overload the move stops
// at the planner's reset deceleration and the tool goes back along it to the hole's R point;
// then, as params 5100/5200 say: an alarm (1282), the block ended there and the program going
// on, or the in-feed again from R until it gets through. Without the retract (5100.2 = 0) the
// overload is the alarm where the tool stopped.
#include "channel/control/channel_coordination.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::channel {

namespace {

// Where the in-feed from `start` to `c.to` meets the hole's R point: c.overload_retract back
// from its end, along it.
interp::AxisVector retract_point(const interp::Command& c, const interp::AxisVector& start,
                                 std::size_t axis_count) noexcept {
  double length = 0.0;
  for (std::size_t i = 0; i < axis_count; ++i) {
    length += (start[i] - c.to[i]) * (start[i] - c.to[i]);
  }
  length = std::sqrt(length);
  if (std::fabs(length - c.overload_retract) < 1e-9) {
    return start;  // the in-feed began at R
  }
  interp::AxisVector at = c.to;
  for (std::size_t i = 0; i < axis_count && length > 0.0; ++i) {
    at[i] = c.to[i] + (start[i] - c.to[i]) / length * c.overload_retract;
  }
  return at;
}

bool same_place(const interp::AxisVector& a, const interp::AxisVector& b,
                std::size_t axis_count) noexcept {
  for (std::size_t i = 0; i < axis_count; ++i) {
    if (std::fabs(a[i] - b[i]) > 1e-9) {
      return false;
    }
  }
  return true;
}

}  // namespace

void ChannelCoordination::feed_in(OverloadStop& b) noexcept {
  coordination::LoadMonitor::Percent loads{};
  std::copy_n(b.command.overload_loads.begin(),
              std::min(b.command.overload_loads.size(), loads.size()), loads.begin());
  const auto cycles =
      static_cast<std::uint64_t>(std::ceil(b.command.overload_filter_s / setup_.cycle_s - 1e-9));
  overload_.set(coordination::LoadWatch::feed_moves, b.command.overload_axes, loads, cycles,
                b.command.overload_p);
  b.phase = OverloadPhase::feeding;
  if (!host_.queue_command(b.command)) {
    overload_.cancel();
    held_ = std::monostate{};  // the planner refused it: its alarm (source_alarm_) comes next
  }
}

void ChannelCoordination::watch_overload(std::span<const AxisFeedbackView> feedback) noexcept {
  auto* b = std::get_if<OverloadStop>(&held_);
  if (b == nullptr || b->phase != OverloadPhase::feeding) {
    return;
  }
  const auto axes = feedback.first(std::min(feedback.size(), setup_.axis_count));
  if (overload_.step(axes, under_way_)) {
    ++b->overloads;
    b->phase = OverloadPhase::stopping;
    host_.stop_move();  // and drop the rest of the in-feed
  }
}

void ChannelCoordination::run(OverloadStop& b, std::uint64_t /*cycle*/,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  using Outcome = interp::Command::Overload;
  switch (b.phase) {
    case OverloadPhase::start:
      b.start = commanded_;
      feed_in(b);
      return;
    case OverloadPhase::feeding:
      // The in-feed reached its end: the cycle goes on as programmed.
      overload_.cancel();
      host_.overload_result(b.overloads, 0);
      held_ = std::monostate{};
      return;
    case OverloadPhase::stopping:
      b.alarm = overload_.alarm();
      b.alarm.number = coordination::kAlarmCycleOverload;
      overload_.cancel();
      if (b.command.overload_outcome == Outcome::stop) {
        raise(b.alarm, b.command.line);  // where it stopped: no retract (param 5100.2 = 0)
        return;
      }
      {
        // Back along the in-feed to R at rapid (a tap: along its thread).
        interp::Command back = b.command;
        back.op = b.command.op == interp::Op::thread ? interp::Op::thread : interp::Op::rapid;
        back.to = retract_point(b.command, b.start, setup_.axis_count);
        back.overload_axes = 0;
        back.barrier = false;
        b.phase = OverloadPhase::retracting;
        if (!host_.queue_command(back)) {
          held_ = std::monostate{};
        }
        return;
      }
    case OverloadPhase::retracting:
      break;
  }
  // At R.
  switch (b.command.overload_outcome) {
    case Outcome::retry:
      if (!same_place(b.start, commanded_, setup_.axis_count)) {
        interp::Command to_start = b.command;  // back to where the in-feed began, at rapid
        to_start.op = interp::Op::rapid;
        to_start.to = b.start;
        to_start.overload_axes = 0;
        to_start.barrier = false;
        if (!host_.queue_command(to_start)) {
          held_ = std::monostate{};
          return;
        }
      }
      feed_in(b);
      return;
    case Outcome::go_on:
      host_.overload_result(b.overloads, b.command.overload_block);
      held_ = std::monostate{};
      return;
    case Outcome::alarm:
    case Outcome::stop:
      raise(b.alarm, b.command.line);
      return;
  }
}

}  // namespace mcnc::channel
