#pragma once
// A channel under test with its interpreter and planner, stepped against simulated axis nodes
// that a derived rig supplies (`step`): the loop, the program load and the alarms it raised.
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/motion/motion_planner.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace mcnc::channel {

// A planner for `axes` axes that move alike: 100 units/s, 1000 units/s^2, 50000 units/s^3.
inline motion::MotionConfig alike_axes(std::size_t axes, double cycle_s) {
  motion::MotionConfig c;
  c.axis_count = axes;
  for (std::size_t i = 0; i < axes; ++i) {
    c.axes[i] = motion::AxisDynamics{100.0, 1000.0, 50000.0};
    c.rapid_rate[i] = 100.0;
  }
  c.cycle_s = cycle_s;
  return c;
}

class ChannelRig {
 public:
  ChannelRig(const interp::InterpreterConfig& interp, const motion::MotionConfig& motion,
             ChannelSetup setup)
      : source_(interp),
        planner_(motion, interp::AxisVector{}),
        ctl_(std::move(setup), source_, planner_) {}
  virtual ~ChannelRig() = default;
  ChannelRig(const ChannelRig&) = delete;
  ChannelRig& operator=(const ChannelRig&) = delete;

  void load(const std::string& text) {
    const auto alarm = source_.load(text, "T.nc");
    ASSERT_FALSE(alarm.has_value()) << alarm->number << " " << alarm->text;
  }
  // A program whose load finds an alarm: reported to the channel as the real one does.
  std::optional<interp::ProgramAlarm> load_with_alarm(const std::string& text) {
    auto alarm = source_.load(text, "T.nc");
    if (alarm) {
      ctl_.report_alarm(*alarm);
    }
    return alarm;
  }

  // One cycle of the channel and of the rig's axis nodes.
  virtual const ChannelOutput& step() = 0;

  bool run_until(const std::function<bool(const ChannelOutput&)>& done, int limit = 20000) {
    for (int i = 0; i < limit; ++i) {
      if (done(step())) {
        return true;
      }
    }
    return false;
  }

  // Cycle start, then cycles until the program ends or stops in an alarm.
  bool run_to_end() {
    ctl_.request_start();
    return run_until(
        [](const ChannelOutput& o) { return o.program_end || o.state == ChannelState::alarm; });
  }

  ChannelController& ctl() { return ctl_; }
  interp::InterpreterSource& source() { return source_; }

  std::vector<int> alarms;  // numbers, in the order raised
  std::vector<int> alarm_lines;
  std::string alarm_text;  // the last one's

 protected:
  // The cycle of the channel, its alarms noted.
  const ChannelOutput& channel_cycle(std::uint64_t cycle,
                                     std::span<const AxisFeedbackView> feedback) {
    const ChannelOutput& out = ctl_.cycle(cycle, feedback);
    for (std::size_t e = 0; e < out.event_count; ++e) {
      if (out.events[e].kind == ChannelEventKind::alarm) {
        alarms.push_back(out.events[e].alarm_number);
        alarm_lines.push_back(out.events[e].line);
        alarm_text = ctl_.last_alarm().text.data();
      }
    }
    return out;
  }

 private:
  interp::InterpreterSource source_;
  motion::MotionPlanner planner_;
  ChannelController ctl_;
};

}  // namespace mcnc::channel
