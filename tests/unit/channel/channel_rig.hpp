#pragma once
// A channel under test with its interpreter and planner, stepped against simulated axis nodes
// that a derived rig supplies (`step`): the loop, the program load and the alarms it raised.
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/loading/read_ahead.hpp"
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

// Channel 1 with two axes (X, Z, in position within 0.001) and one spindle.
inline ChannelSetup xz_spindle_setup(double cycle_s) {
  ChannelSetup s{2, {0.001, 0.001}, cycle_s};
  s.channel_id = 1;
  s.spindle_count = 1;
  return s;
}

// `count` axes and spindles that stand enabled and present, owned by `channel`.
inline std::vector<AxisFeedbackView> standing_feedback(std::size_t count, std::uint32_t channel) {
  std::vector<AxisFeedbackView> feedback(count);
  for (auto& f : feedback) {
    f.enabled = true;
    f.present = true;
    f.owner = channel;
  }
  return feedback;
}

// The first `axes` axis nodes follow every valid setpoint within the cycle.
inline void follow_setpoints(const CycleOutput& out, std::vector<AxisFeedbackView>& feedback,
                             std::size_t axes) {
  for (std::size_t a = 0; a < axes; ++a) {
    if (out.setpoints[a].valid) {
      feedback[a].cmd = feedback[a].act = out.setpoints[a].pos;
    }
  }
}

// The channel's commands come from its interpreter directly, or (`read_ahead`) as in the channel
// process: from the read-ahead thread, in lockstep.
class ChannelRig {
 public:
  ChannelRig(const interp::InterpreterConfig& interp, const motion::MotionConfig& motion,
             ChannelSetup setup, bool read_ahead = false)
      : config_(interp),
        source_(interp),
        read_ahead_(nullptr, nullptr),
        planner_(motion, interp::AxisVector{}),
        ctl_(std::move(setup),
             read_ahead ? static_cast<interp::CommandSource&>(read_ahead_) : source_, planner_),
        reads_ahead_(read_ahead) {
    if (read_ahead) {
      read_ahead_.set_lockstep(true);
      read_ahead_.start(source_);
    }
  }
  virtual ~ChannelRig() = default;
  ChannelRig(const ChannelRig&) = delete;
  ChannelRig& operator=(const ChannelRig&) = delete;

  void load(const std::string& text) {
    std::optional<interp::ProgramAlarm> alarm;
    if (reads_ahead_) {
      interp::CheckedProgram checked =
          interp::InterpreterSource::check(config_, text, "T.nc", false);
      alarm = checked.alarm;
      read_ahead_.adopt(std::move(checked));
    } else {
      alarm = source_.load(text, "T.nc");
    }
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
  virtual const CycleOutput& step() = 0;

  bool run_until(const std::function<bool(const CycleOutput&)>& done, int limit = 20000) {
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
        [](const CycleOutput& o) { return o.program_end || o.state == ChannelState::alarm; });
  }

  ChannelController& ctl() { return ctl_; }
  interp::InterpreterSource& source() { return source_; }
  ReadAhead& read_ahead() { return read_ahead_; }

  std::vector<int> alarms;  // numbers, in the order raised
  std::vector<int> alarm_lines;
  std::string alarm_text;  // the last one's

 protected:
  // The cycle of the channel, its alarms noted.
  const CycleOutput& channel_cycle(std::uint64_t cycle,
                                   std::span<const AxisFeedbackView> feedback) {
    const CycleOutput& out = ctl_.cycle(cycle, feedback);
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
  interp::InterpreterConfig config_;
  interp::InterpreterSource source_;
  ReadAhead read_ahead_;  // stopped before the source it reads goes
  motion::MotionPlanner planner_;
  ChannelController ctl_;
  bool reads_ahead_;
};

// A rig whose first `axes` axis nodes stand enabled, owned by channel 1, and follow the
// setpoints one cycle late, as in lockstep; `record` sees each cycle's output.
class LockstepRig : public ChannelRig {
 public:
  LockstepRig(const interp::InterpreterConfig& interp, const motion::MotionConfig& motion,
              ChannelSetup setup, std::size_t axes, bool read_ahead = false)
      : ChannelRig(interp, motion, std::move(setup), read_ahead),
        axes_(axes),
        feedback_(standing_feedback(axes, 1)) {}

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    follow_setpoints(previous_, feedback_, axes_);  // what the nodes reached: last cycle's
    previous_ = out;
    record(out);
    return out;
  }

 protected:
  virtual void record(const CycleOutput& out) = 0;

 private:
  std::size_t axes_;
  std::vector<AxisFeedbackView> feedback_;
  CycleOutput previous_{};
  std::uint64_t cycle_ = 0;
};

}  // namespace mcnc::channel
