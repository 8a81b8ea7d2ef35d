#pragma once
// A channel under test with its interpreter and planner, stepped against simulated axis nodes
// that a derived rig supplies (`step`): the loop, the program load and the alarms it raised.
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/motion/motion_planner.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace mcnc::channel {

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

  ChannelController& ctl() { return ctl_; }

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
