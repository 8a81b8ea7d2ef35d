#include "channel/control/channel_controller.hpp"
#include "channel/control/shared_write_log.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/motion/motion_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <vector>

namespace mcnc::coordination {

// Readable states in failure messages (found by argument-dependent lookup in the namespace of
// ChannelState).
static void PrintTo(ChannelState state, std::ostream* os) {
  *os << to_string(state);
}

}  // namespace mcnc::coordination

namespace mcnc::channel {
namespace {

using interp::Command;
using interp::Op;
using interp::ProgramAlarm;

constexpr double kDt = 0.001;
constexpr double kInPos = 0.01;
// Axis 0: X (diameter programmed), axis 1: Z.
constexpr double kRapid[2] = {100.0, 200.0};

motion::MotionConfig lathe_motion() {
  motion::MotionConfig c;
  c.axis_count = 2;
  c.axes[0] = motion::AxisDynamics{50.0, 1000.0, 50000.0};
  c.axes[1] = motion::AxisDynamics{100.0, 2000.0, 100000.0};
  c.rapid_rate = {kRapid[0], kRapid[1]};
  c.cycle_s = kDt;
  return c;
}

AxisVector xz(double x, double z) {
  AxisVector v{};
  v[0] = x;
  v[1] = z;
  return v;
}

// A scripted command source: hands out a fixed list of results, then nothing.
class ScriptedSource final : public interp::CommandSource {
 public:
  explicit ScriptedSource(std::vector<interp::PullResult> script) : script_(std::move(script)) {}
  void rewind(const AxisVector& current) override {
    cursor_ = 0;
    rewound_at_ = current;
    ++rewinds_;
  }
  std::optional<interp::PullResult> next() override {
    if (cursor_ >= script_.size()) {
      return std::nullopt;
    }
    return script_[cursor_++];
  }
  [[nodiscard]] std::size_t block_count() const noexcept override { return script_.size(); }

  AxisVector rewound_at_{};
  int rewinds_ = 0;

 private:
  std::vector<interp::PullResult> script_;
  std::size_t cursor_ = 0;
};

// A scripted block stops exactly at its end, as every block of the walking skeleton did.
Command command(Op op, const AxisVector& target, int line, std::size_t block, double feed = 0.0) {
  Command c;
  c.op = op;
  c.to = target;
  c.feed = feed;
  c.line = line;
  c.n = block;
  c.exact_stop = true;
  return c;
}

Command program_end(int line, std::size_t block, int code = 30) {
  Command c;
  c.op = Op::end;
  c.code = code;
  c.line = line;
  c.n = block;
  return c;
}

struct LoggedEvent {
  std::uint64_t cycle = 0;
  ChannelEvent event;
};

// The channel with two simulated axes. The axes follow the last valid setpoint with a one-cycle
// delay: the feedback used at cycle N is what the channel commanded at cycle N-1.
interp::InterpreterConfig xz_channel() {
  interp::InterpreterConfig c;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z', false}};
  return c;
}

class Rig {
 public:
  explicit Rig(interp::CommandSource* scripted = nullptr, AxisVector start = xz(0.0, 0.0),
               int spindles = 0)
      : interp_([&] {
          interp::InterpreterConfig c = xz_channel();
          c.spindles = spindles;
          return c;
        }()),
        planner_(lathe_motion(), AxisVector{}),
        ctl_(
            [&] {
              ChannelSetup setup{2, {kInPos, kInPos}, kDt};
              setup.spindle_count = static_cast<std::size_t>(spindles);
              return setup;
            }(),
            scripted != nullptr ? *scripted : static_cast<interp::CommandSource&>(interp_),
            planner_) {
    feedback_.resize(2 + static_cast<std::size_t>(spindles));
    for (std::size_t i = 0; i < feedback_.size(); ++i) {
      feedback_[i].cmd = start[i];
      feedback_[i].act = start[i];
      feedback_[i].enabled = true;
      feedback_[i].present = true;
    }
  }

  void load(const std::string& text) {
    const auto alarm = interp_.load(text, "T.nc");
    ASSERT_FALSE(alarm.has_value())
        << alarm->number << " " << alarm->text << " line " << alarm->line;
  }

  const CycleOutput& step() {
    if (act_override) {
      act_override(feedback_);
    }
    const CycleOutput& out = ctl_.cycle(cycle_, feedback_);
    EXPECT_LE(out.event_count, CycleOutput::kMaxEvents);
    for (std::size_t e = 0; e < out.event_count && e < CycleOutput::kMaxEvents; ++e) {
      events.push_back({cycle_, out.events[e]});
    }
    last = out;
    outputs.push_back(out);
    for (std::size_t i = 0; i < 2; ++i) {
      if (out.setpoints[i].valid && follow) {
        feedback_[i].act = out.setpoints[i].pos;
        feedback_[i].cmd = out.setpoints[i].pos;
      }
    }
    ++cycle_;
    return last;
  }

  // Steps until `done` holds after a cycle or `limit` cycles passed; true when it held.
  bool run_until(const std::function<bool(const CycleOutput&)>& done, int limit = 200000) {
    for (int i = 0; i < limit; ++i) {
      if (done(step())) {
        return true;
      }
    }
    return false;
  }

  bool run_to_end(int limit = 200000) {
    return run_until([](const CycleOutput& o) { return o.program_end; }, limit);
  }

  std::vector<ChannelEvent> events_of(ChannelEventKind kind) const {
    std::vector<ChannelEvent> out;
    for (const auto& e : events) {
      if (e.event.kind == kind) {
        out.push_back(e.event);
      }
    }
    return out;
  }

  std::optional<std::uint64_t> first_cycle_of(ChannelEventKind kind, int line) const {
    for (const auto& e : events) {
      if (e.event.kind == kind && e.event.line == line) {
        return e.cycle;
      }
    }
    return std::nullopt;
  }

  interp::InterpreterSource interp_;
  motion::MotionPlanner planner_;
  ChannelController ctl_;
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 1;
  bool follow = true;
  std::function<void(std::vector<AxisFeedbackView>&)> act_override;
  std::vector<LoggedEvent> events;
  std::vector<CycleOutput> outputs;
  CycleOutput last{};
};

// The largest per-cycle setpoint change of each axis over the recorded outputs.
void expect_no_jumps(const std::vector<CycleOutput>& outputs) {
  for (std::size_t k = 1; k < outputs.size(); ++k) {
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& a = outputs[k - 1].setpoints[i];
      const auto& b = outputs[k].setpoints[i];
      if (!a.valid || !b.valid) {
        continue;
      }
      const double bound = kRapid[i] * kDt * (1.0 + 1e-9) + 1e-12;
      ASSERT_LE(std::fabs(b.pos - a.pos), bound) << "axis " << i << " at output " << k;
    }
  }
}

TEST(ChannelController, StateSequenceResetIdleRunningIdle) {
  Rig rig;
  rig.load("G00 X40 Z10\nM30\n");
  for (auto& f : rig.feedback_) {
    f.enabled = false;
  }
  // Not every axis enabled: reset, nothing commanded.
  for (int i = 0; i < 5; ++i) {
    const auto& out = rig.step();
    EXPECT_EQ(out.state, ChannelState::reset);
    EXPECT_FALSE(out.setpoints[0].valid);
    EXPECT_FALSE(out.setpoints[1].valid);
  }
  ASSERT_FALSE(rig.events.empty());
  EXPECT_EQ(rig.events.front().event.kind, ChannelEventKind::state_changed);
  EXPECT_EQ(rig.events.front().event.state, ChannelState::reset);
  EXPECT_EQ(rig.events.front().cycle, 1u);

  // One axis enabled is not enough.
  rig.feedback_[0].enabled = true;
  EXPECT_EQ(rig.step().state, ChannelState::reset);
  EXPECT_FALSE(rig.last.setpoints[0].valid);

  rig.feedback_[1].enabled = true;
  const std::uint64_t idle_cycle = rig.cycle_;
  EXPECT_EQ(rig.step().state, ChannelState::idle);
  ASSERT_GE(rig.last.event_count, 1u);
  EXPECT_EQ(rig.last.events[0].kind, ChannelEventKind::state_changed);
  EXPECT_EQ(rig.last.events[0].state, ChannelState::idle);
  EXPECT_TRUE(rig.last.setpoints[0].valid);

  // Idle stays idle without a start.
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::idle);
  }
  EXPECT_EQ(rig.ctl_.state(), ChannelState::idle);

  rig.ctl_.request_start();
  EXPECT_EQ(rig.step().state, ChannelState::running);
  EXPECT_EQ(rig.last.events[0].kind, ChannelEventKind::state_changed);
  EXPECT_EQ(rig.last.events[0].state, ChannelState::running);

  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.last.state, ChannelState::idle);
  EXPECT_EQ(rig.last.end_code, 30);
  const auto ends = rig.events_of(ChannelEventKind::program_end);
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(ends[0].end_code, 30);
  EXPECT_EQ(ends[0].line, 2);

  std::vector<ChannelState> states;
  for (const auto& e : rig.events_of(ChannelEventKind::state_changed)) {
    states.push_back(e.state);
  }
  EXPECT_EQ(states, (std::vector<ChannelState>{ChannelState::reset, ChannelState::idle,
                                               ChannelState::running, ChannelState::idle}));
  EXPECT_GT(rig.cycle_, idle_cycle);

  // Idle after the end holds the end point and stays idle.
  for (int i = 0; i < 20; ++i) {
    const auto& out = rig.step();
    EXPECT_EQ(out.state, ChannelState::idle);
    EXPECT_EQ(out.setpoints[0].pos, 20.0);
    EXPECT_EQ(out.setpoints[1].pos, 10.0);
  }
}

TEST(ChannelController, StartPositionComesFromFeedbackCmd) {
  Rig rig(nullptr, xz(5.0, -3.0));
  rig.load("G01 W1 F600\nM30\n");
  // act differs from cmd (inside the in-position width): the channel must take cmd.
  rig.feedback_[0].act = 5.004;
  rig.feedback_[1].act = -3.006;
  rig.feedback_[1].enabled = false;
  rig.follow = false;
  rig.ctl_.request_start();  // latched until the axes are enabled
  for (int i = 0; i < 3; ++i) {
    const auto& out = rig.step();
    EXPECT_EQ(out.state, ChannelState::reset);
    EXPECT_FALSE(out.setpoints[0].valid);
    EXPECT_FALSE(out.setpoints[1].valid);
  }
  rig.feedback_[1].enabled = true;
  rig.follow = true;
  const auto& out = rig.step();
  EXPECT_EQ(out.state, ChannelState::running);
  EXPECT_TRUE(out.setpoints[0].valid);
  EXPECT_TRUE(out.setpoints[1].valid);
  EXPECT_EQ(out.setpoints[0].pos, 5.0);
  EXPECT_EQ(rig.ctl_.commanded()[0], 5.0);
  // The first motion sample starts from cmd, not from act.
  EXPECT_GE(out.setpoints[1].pos, -3.0);
  EXPECT_LT(out.setpoints[1].pos, -3.0 + 0.01);

  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.last.setpoints[0].pos, 5.0);
  EXPECT_EQ(rig.last.setpoints[1].pos, -2.0);
}

TEST(ChannelController, BlockEventsInProgramOrderWithFileLines) {
  Rig rig;
  rig.load(
      "%\n"
      "O0001 (test)\n"
      "N10 G00 X20 Z5\n"
      "\n"
      "(a comment line)\n"
      "N20 G01 Z-10 F3000\n"
      "N30 G04 P100\n"
      "N40 U10 W2\n"
      "N50 M30\n"
      "%\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());

  const auto started = rig.events_of(ChannelEventKind::block_started);
  const auto ended = rig.events_of(ChannelEventKind::block_ended);
  const std::vector<int> lines{3, 6, 7, 8, 9};
  ASSERT_EQ(started.size(), lines.size());
  ASSERT_EQ(ended.size(), lines.size());
  const std::vector<AxisVector> ends{xz(10, 5), xz(10, -10), xz(10, -10), xz(15, -8), xz(15, -8)};
  for (std::size_t b = 0; b < lines.size(); ++b) {
    SCOPED_TRACE(b);
    EXPECT_EQ(started[b].line, lines[b]);
    EXPECT_EQ(started[b].block, b + 1);
    EXPECT_EQ(ended[b].line, lines[b]);
    EXPECT_EQ(ended[b].block, b + 1);
    EXPECT_EQ(ended[b].pos[0], ends[b][0]);
    EXPECT_EQ(ended[b].pos[1], ends[b][1]);
  }
  // Strict alternation: started(b), ended(b), started(b+1) ...
  std::vector<std::pair<ChannelEventKind, int>> seq;
  for (const auto& e : rig.events) {
    if (e.event.kind == ChannelEventKind::block_started ||
        e.event.kind == ChannelEventKind::block_ended) {
      seq.emplace_back(e.event.kind, e.event.line);
    }
  }
  ASSERT_EQ(seq.size(), 2 * lines.size());
  for (std::size_t b = 0; b < lines.size(); ++b) {
    EXPECT_EQ(seq[2 * b].first, ChannelEventKind::block_started);
    EXPECT_EQ(seq[2 * b].second, lines[b]);
    EXPECT_EQ(seq[2 * b + 1].first, ChannelEventKind::block_ended);
    EXPECT_EQ(seq[2 * b + 1].second, lines[b]);
  }
  // program_end comes after the last block ended.
  ASSERT_FALSE(rig.events.empty());
  std::size_t end_index = 0;
  std::size_t last_ended = 0;
  for (std::size_t i = 0; i < rig.events.size(); ++i) {
    if (rig.events[i].event.kind == ChannelEventKind::program_end) {
      end_index = i;
    }
    if (rig.events[i].event.kind == ChannelEventKind::block_ended) {
      last_ended = i;
    }
  }
  EXPECT_GT(end_index, last_ended);
}

TEST(ChannelController, OutputLineAndBlockFollowTheRunningBlock) {
  Rig rig;
  rig.load("G00 Z20\n\nG00 X10\nM30\n");
  rig.ctl_.request_start();
  rig.step();
  rig.step();
  EXPECT_EQ(rig.last.line, 1);
  EXPECT_EQ(rig.last.block, 1u);
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.line == 3; }));
  EXPECT_EQ(rig.last.block, 2u);
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.last.line, 4);
  EXPECT_EQ(rig.last.block, 3u);
}

TEST(ChannelController, BlockEndsOnlyWhenEveryAxisIsInPosition) {
  Rig rig;
  rig.load("G00 X20 Z10\nG00 Z0\nM30\n");
  rig.ctl_.request_start();
  // Half way, the axes stop following: Z lags outside its width, X is in.
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.setpoints[1].pos >= 5.0; }));
  rig.follow = false;
  rig.feedback_[0].act = 10.0;
  rig.feedback_[1].act = 10.0 - 5 * kInPos;
  // Until the planner has reached the end point of block 1: the block must not end.
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) {
    return o.setpoints[0].pos == 10.0 && o.setpoints[1].pos == 10.0;
  }));
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_ended).empty());
  for (int i = 0; i < 30; ++i) {
    const auto& out = rig.step();
    EXPECT_EQ(out.state, ChannelState::running);
    EXPECT_EQ(out.setpoints[0].pos, 10.0);
    EXPECT_EQ(out.setpoints[1].pos, 10.0);
    EXPECT_TRUE(out.setpoints[1].valid);
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_ended).empty());
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_started).size() == 1u);

  // Z in, X now out on the other side: still not ended.
  rig.feedback_[1].act = 10.0 + 0.5 * kInPos;
  rig.feedback_[0].act = 10.0 + 2 * kInPos;
  for (int i = 0; i < 10; ++i) {
    rig.step();
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_ended).empty());

  // Both inside their width (not exactly on the point): the block ends in this very cycle.
  rig.feedback_[0].act = 10.0 - 0.5 * kInPos;
  const std::uint64_t in_cycle = rig.cycle_;
  rig.step();
  const auto ended = rig.events_of(ChannelEventKind::block_ended);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(rig.first_cycle_of(ChannelEventKind::block_ended, 1), in_cycle);
  EXPECT_EQ(ended[0].pos[0], 10.0);
  EXPECT_EQ(ended[0].pos[1], 10.0);
  // The next block starts at once.
  EXPECT_EQ(rig.first_cycle_of(ChannelEventKind::block_started, 2), in_cycle);

  rig.follow = true;
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.last.setpoints[1].pos, 0.0);
}

TEST(ChannelController, ProgramEndWaitsForInPosition) {
  Rig rig;
  rig.load("M30\n");
  rig.follow = false;
  rig.feedback_[0].act = 3 * kInPos;  // cmd stays 0, act outside the width
  rig.ctl_.request_start();
  for (int i = 0; i < 20; ++i) {
    EXPECT_FALSE(rig.step().program_end);
    EXPECT_EQ(rig.last.state, ChannelState::running);
  }
  rig.feedback_[0].act = 0.0;
  EXPECT_TRUE(rig.step().program_end);
  EXPECT_EQ(rig.last.state, ChannelState::idle);
  EXPECT_EQ(rig.last.end_code, 30);
}

TEST(ChannelController, SetpointsNeverJumpAndReachEndPointsExactly) {
  Rig rig(nullptr, xz(1.0, 2.0));
  rig.load(
      "G00 X-30 Z47.5\n"
      "G01 U7.25 W-13.125 F4500\n"
      "G00 Z0.001\n"
      "G01 X0.3 F2400\n"
      "M02\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  expect_no_jumps(rig.outputs);
  const auto ended = rig.events_of(ChannelEventKind::block_ended);
  ASSERT_EQ(ended.size(), 5u);
  EXPECT_EQ(ended[0].pos[0], -15.0);
  EXPECT_EQ(ended[0].pos[1], 47.5);
  EXPECT_EQ(ended[1].pos[0], -15.0 + 7.25 / 2.0);
  EXPECT_EQ(ended[1].pos[1], 47.5 + -13.125);
  EXPECT_EQ(ended[2].pos[1], 0.001);
  EXPECT_EQ(ended[3].pos[0], 0.3 / 2.0);
  EXPECT_EQ(rig.last.setpoints[0].pos, 0.15);
  EXPECT_EQ(rig.last.setpoints[1].pos, 0.001);
  EXPECT_EQ(rig.last.end_code, 2);
  EXPECT_EQ(rig.events_of(ChannelEventKind::program_end).at(0).end_code, 2);
  // Every block's end point appears as a setpoint exactly.
  for (const auto& e : ended) {
    bool seen = false;
    for (const auto& o : rig.outputs) {
      seen = seen || (o.setpoints[0].pos == e.pos[0] && o.setpoints[1].pos == e.pos[1]);
    }
    EXPECT_TRUE(seen) << e.line;
  }
}

TEST(ChannelController, SetpointsDoNotJumpWhenFeedbackLagsByOneCycle) {
  // The axes report the setpoint of the cycle before: the same program must still finish.
  Rig rig;
  rig.load("G00 X50 Z-20\nG01 W40 F6000\nM30\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  expect_no_jumps(rig.outputs);
  EXPECT_EQ(rig.last.setpoints[0].pos, 25.0);
  EXPECT_EQ(rig.last.setpoints[1].pos, 20.0);
  // G01 at 6000/min = 100/s: 40 units take at least 0.4 s.
  const auto s = rig.first_cycle_of(ChannelEventKind::block_started, 2);
  const auto e = rig.first_cycle_of(ChannelEventKind::block_ended, 2);
  ASSERT_TRUE(s && e);
  EXPECT_GE(*e - *s, 400u);
  // No velocity above the programmed feed on Z during block 2.
  for (std::uint64_t c = *s; c < *e; ++c) {
    EXPECT_LE(std::fabs(rig.outputs[c - 1].setpoints[1].vel), 100.0 * (1 + 1e-9));
  }
}

TEST(ChannelController, DwellHoldsPositionForItsTime) {
  Rig rig;
  rig.load("G00 Z1\nG04 P500\nG00 Z2\nM30\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  const auto s = rig.first_cycle_of(ChannelEventKind::block_started, 2);
  const auto e = rig.first_cycle_of(ChannelEventKind::block_started, 3);
  ASSERT_TRUE(s && e);
  const auto cycles = static_cast<long>(*e - *s);
  EXPECT_GE(cycles, 499);
  EXPECT_LE(cycles, 501);
  for (std::uint64_t c = *s; c < *e; ++c) {
    const auto& o = rig.outputs[c - 1];  // outputs[0] is cycle 1
    EXPECT_EQ(o.setpoints[1].pos, 1.0) << c;
    EXPECT_EQ(o.setpoints[0].pos, 0.0) << c;
    EXPECT_EQ(o.setpoints[1].vel, 0.0) << c;
  }
  EXPECT_EQ(rig.last.setpoints[1].pos, 2.0);
}

TEST(ChannelController, ReportedAlarmStopsAtNextCycleAndHolds) {
  Rig rig;
  rig.load("G00 Z50\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 50; ++i) {
    rig.step();
  }
  ASSERT_EQ(rig.last.state, ChannelState::running);
  const double z_before = rig.last.setpoints[1].pos;
  ASSERT_GT(z_before, 0.0);
  ASSERT_LT(z_before, 50.0);

  rig.ctl_.report_alarm(ProgramAlarm{1105, "G01 without feed", "T.nc", 7, 3});
  const auto& out = rig.step();
  EXPECT_EQ(out.state, ChannelState::alarm);
  bool alarm_event = false;
  for (std::size_t e = 0; e < out.event_count; ++e) {
    if (out.events[e].kind == ChannelEventKind::alarm) {
      alarm_event = true;
      EXPECT_EQ(out.events[e].alarm_number, 1105);
      EXPECT_EQ(out.events[e].line, 7);
    }
  }
  EXPECT_TRUE(alarm_event);
  EXPECT_EQ(rig.ctl_.last_alarm().number, 1105);
  EXPECT_EQ(rig.ctl_.last_alarm().line, 7);
  EXPECT_EQ(rig.ctl_.last_alarm().column, 3);
  EXPECT_STREQ(rig.ctl_.last_alarm().text.data(), "G01 without feed");
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
  for (int i = 0; i < 100; ++i) {
    const auto& o = rig.step();
    EXPECT_EQ(o.state, ChannelState::alarm);
    EXPECT_EQ(o.setpoints[1].pos, z_before);
    EXPECT_EQ(o.setpoints[0].pos, 0.0);
    EXPECT_FALSE(o.program_end);
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::program_end).empty());
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
}

TEST(ChannelController, ReportedAlarmBeforeStartPreventsTheRun) {
  Rig rig;
  rig.load("G00 Z50\nM30\n");
  rig.step();
  ASSERT_EQ(rig.last.state, ChannelState::idle);
  rig.ctl_.report_alarm(ProgramAlarm{1010, "program end missing", "T.nc", 4, 0});
  rig.ctl_.request_start();
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::alarm);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::alarm);
    EXPECT_EQ(rig.last.setpoints[1].pos, 0.0);
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_started).empty());
  EXPECT_EQ(rig.ctl_.last_alarm().number, 1010);
}

TEST(ChannelController, AxisAlarmDuringRunStopsMotion) {
  Rig rig;
  rig.load("G00 X10\nG00 X40 Z80\nM30\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.line == 2; }));
  for (int i = 0; i < 30; ++i) {
    rig.step();
  }
  const double x = rig.last.setpoints[0].pos;
  const double z = rig.last.setpoints[1].pos;
  ASSERT_GT(z, 0.0);
  ASSERT_LT(z, 80.0);

  rig.feedback_[1].alarm = true;
  const auto& out = rig.step();
  EXPECT_EQ(out.state, ChannelState::alarm);
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmAxisAlarm);
  EXPECT_EQ(rig.ctl_.last_alarm().axis, 2);
  EXPECT_EQ(rig.ctl_.last_alarm().line, 2);
  const auto alarms = rig.events_of(ChannelEventKind::alarm);
  ASSERT_EQ(alarms.size(), 1u);
  EXPECT_EQ(alarms[0].alarm_number, kAlarmAxisAlarm);
  // Motion stops: the setpoint stays where it was, from this cycle on.
  for (int i = 0; i < 200; ++i) {
    const auto& o = i == 0 ? rig.last : rig.step();
    EXPECT_EQ(o.state, ChannelState::alarm);
    EXPECT_EQ(o.setpoints[0].pos, x);
    EXPECT_EQ(o.setpoints[1].pos, z);
  }
  // The alarm clearing on the axis does not restart the program.
  rig.feedback_[1].alarm = false;
  rig.ctl_.request_start();
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::alarm);
    EXPECT_EQ(rig.last.setpoints[1].pos, z);
  }
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
}

TEST(ChannelController, AxisLostRaises1202) {
  Rig rig;
  rig.load("G00 Z80\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 40; ++i) {
    rig.step();
  }
  const double z = rig.last.setpoints[1].pos;
  rig.ctl_.axis_lost(0);
  rig.ctl_.axis_lost(1);  // only the first loss is reported
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::alarm);
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmAxisLost);
  EXPECT_EQ(rig.ctl_.last_alarm().axis, 1);
  EXPECT_EQ(rig.ctl_.last_alarm().line, 1);
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rig.step().setpoints[1].pos, z);
  }
}

// Across hosts an owned axis's loss and the launchers' E-stop for the host that went come
// together, in either order: the channel still says which axis it lost.
TEST(ChannelController, AnAxisLostWithTheEmergencyStopIsStillTold) {
  Rig rig;
  rig.load("G00 Z80\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 40; ++i) {
    rig.step();
  }
  rig.ctl_.axis_lost(1);
  rig.ctl_.emergency_stop();
  rig.step();
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmAxisLost);
  EXPECT_EQ(rig.ctl_.last_alarm().axis, 2);
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
  EXPECT_EQ(rig.last.state, ChannelState::reset);  // the E-stop stands over the alarm
  EXPECT_FALSE(rig.last.setpoints[1].valid);
  for (int i = 0; i < 20; ++i) {
    rig.step();
  }
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);  // told once
}

TEST(ChannelController, AnAxisLostAfterTheEmergencyStopIsStillTold) {
  Rig rig;
  rig.load("G00 Z80\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 40; ++i) {
    rig.step();
  }
  rig.ctl_.emergency_stop();
  for (int i = 0; i < 5; ++i) {
    rig.step();
  }
  ASSERT_EQ(rig.ctl_.alarm_count(), 0u);
  rig.ctl_.axis_lost(0);
  rig.step();
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmAxisLost);
  EXPECT_EQ(rig.ctl_.last_alarm().axis, 1);
  EXPECT_FALSE(rig.last.setpoints[0].valid);
  for (int i = 0; i < 20; ++i) {
    EXPECT_FALSE(rig.step().setpoints[0].valid);
  }
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
}

TEST(ChannelController, EmergencyStopGoesToResetAndStays) {
  Rig rig;
  rig.load("G00 Z80\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 40; ++i) {
    rig.step();
  }
  ASSERT_EQ(rig.last.state, ChannelState::running);
  rig.ctl_.emergency_stop();
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::reset);
  EXPECT_FALSE(rig.last.setpoints[0].valid);
  EXPECT_FALSE(rig.last.setpoints[1].valid);
  bool reset_event = false;
  for (std::size_t e = 0; e < rig.last.event_count; ++e) {
    reset_event = reset_event || (rig.last.events[e].kind == ChannelEventKind::state_changed &&
                                  rig.last.events[e].state == ChannelState::reset);
  }
  EXPECT_TRUE(reset_event);
  // Axes still enabled, a new start asked for: the channel stays in reset, commanding nothing.
  rig.ctl_.request_start();
  for (int i = 0; i < 100; ++i) {
    const auto& o = rig.step();
    EXPECT_EQ(o.state, ChannelState::reset);
    EXPECT_FALSE(o.setpoints[0].valid);
    EXPECT_FALSE(o.setpoints[1].valid);
    EXPECT_FALSE(o.program_end);
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::program_end).empty());
}

TEST(ChannelController, EmergencyStopBeforeAxesEnabledIsNotForgotten) {
  // "Emergency stop: the channel goes to reset and stays there" also when it comes while the
  // channel is still waiting for its axes.
  Rig rig;
  rig.load("G00 Z80\nM30\n");
  for (auto& f : rig.feedback_) {
    f.enabled = false;
  }
  rig.step();
  ASSERT_EQ(rig.last.state, ChannelState::reset);
  rig.ctl_.emergency_stop();
  rig.step();
  for (auto& f : rig.feedback_) {
    f.enabled = true;
  }
  rig.ctl_.request_start();
  for (int i = 0; i < 100; ++i) {
    const auto& o = rig.step();
    ASSERT_EQ(o.state, ChannelState::reset) << "cycle " << i;
    ASSERT_FALSE(o.setpoints[1].valid) << "cycle " << i;
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_started).empty());
}

TEST(ChannelController, StartRequestedWhileRunningDoesNotRunTheProgramAgain) {
  Rig rig;
  rig.load("G00 W5\nM30\n");
  rig.ctl_.request_start();
  rig.step();
  ASSERT_EQ(rig.last.state, ChannelState::running);
  rig.ctl_.request_start();  // pressed again while the program runs
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.last.setpoints[1].pos, 5.0);
  for (int i = 0; i < 500; ++i) {
    ASSERT_EQ(rig.step().state, ChannelState::idle) << "cycle " << i;
  }
  EXPECT_EQ(rig.last.setpoints[1].pos, 5.0);
  EXPECT_EQ(rig.events_of(ChannelEventKind::program_end).size(), 1u);
}

TEST(ChannelController, RestartAfterEndRunsFromTheCurrentPosition) {
  Rig rig;
  rig.load("G00 W5\nM30\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.last.setpoints[1].pos, 5.0);
  rig.step();
  rig.ctl_.request_start();
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::running);
  EXPECT_FALSE(rig.last.program_end);
  EXPECT_EQ(rig.last.end_code, -1);
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.last.setpoints[1].pos, 10.0);
  EXPECT_EQ(rig.events_of(ChannelEventKind::program_end).size(), 2u);
}

TEST(ChannelController, ScriptedSourceAlarmMidProgram) {
  ProgramAlarm bad{1101, "G02 is not supported yet", "S.nc", 12, 4};
  ScriptedSource source({interp::PullResult{command(Op::rapid, xz(0, 5), 10, 1)},
                         interp::PullResult{bad}, interp::PullResult{program_end(14, 3)}});
  Rig rig(&source);
  rig.ctl_.request_start();
  ASSERT_TRUE(
      rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }, 10000));
  EXPECT_EQ(source.rewinds_, 1);
  EXPECT_EQ(rig.ctl_.last_alarm().number, 1101);
  EXPECT_EQ(rig.ctl_.last_alarm().line, 12);
  EXPECT_EQ(rig.ctl_.last_alarm().column, 4);
  EXPECT_STREQ(rig.ctl_.last_alarm().file.data(), "S.nc");
  EXPECT_STREQ(rig.ctl_.last_alarm().text.data(), "G02 is not supported yet");
  const auto alarms = rig.events_of(ChannelEventKind::alarm);
  ASSERT_EQ(alarms.size(), 1u);
  EXPECT_EQ(alarms[0].alarm_number, 1101);
  EXPECT_EQ(alarms[0].line, 12);
  // Block 1 ran to its end before the alarm; nothing after it started.
  ASSERT_EQ(rig.events_of(ChannelEventKind::block_ended).size(), 1u);
  EXPECT_EQ(rig.events_of(ChannelEventKind::block_started).size(), 1u);
  EXPECT_EQ(rig.last.setpoints[1].pos, 5.0);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::alarm);
    EXPECT_EQ(rig.last.setpoints[1].pos, 5.0);
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::program_end).empty());
}

// An alarm that names no file (an axis's, raised by the channel) is in the file of the block
// under way: here a called program's, not the main program's.
TEST(ChannelController, AnAlarmWithoutAFileIsInTheFileOfTheBlockUnderWay) {
  const std::string called = "progs/O2000.nc";
  Command in_called = command(Op::rapid, xz(0, 80), 3, 1);
  in_called.file = &called;
  ScriptedSource source({interp::PullResult{in_called}, interp::PullResult{program_end(4, 2)}});
  Rig rig(&source);
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.line == 3; }));
  EXPECT_STREQ(rig.last.file.data(), "progs/O2000.nc");
  rig.feedback_[1].alarm = true;
  EXPECT_EQ(rig.step().state, ChannelState::alarm);
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmAxisAlarm);
  EXPECT_EQ(rig.ctl_.last_alarm().line, 3);
  EXPECT_STREQ(rig.ctl_.last_alarm().file.data(), "progs/O2000.nc");
}

TEST(ChannelController, PlannerRejectingABlockGives1200) {
  ScriptedSource source({interp::PullResult{command(Op::linear, xz(0, 5), 3, 1, 0.0)},
                         interp::PullResult{program_end(4, 2)}});
  Rig rig(&source, xz(1.0, 2.0));
  rig.ctl_.request_start();
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::alarm);
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmPlannerRejected);
  EXPECT_EQ(rig.ctl_.last_alarm().line, 3);
  for (int i = 0; i < 20; ++i) {
    rig.step();
    EXPECT_EQ(rig.last.state, ChannelState::alarm);
    EXPECT_EQ(rig.last.setpoints[0].pos, 1.0);
    EXPECT_EQ(rig.last.setpoints[1].pos, 2.0);
  }
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_ended).empty());
}

TEST(ChannelController, SourceEndingWithoutProgramEndGives1200) {
  ScriptedSource source({interp::PullResult{command(Op::rapid, xz(0, 1), 1, 1)}});
  Rig rig(&source);
  rig.ctl_.request_start();
  ASSERT_TRUE(
      rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }, 10000));
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmPlannerRejected);
  EXPECT_EQ(rig.last.setpoints[1].pos, 1.0);
  EXPECT_FALSE(rig.last.program_end);
}

TEST(ChannelController, InterpreterLoadAlarmComesOutOfTheSource) {
  Rig rig;
  const auto alarm = rig.interp_.load("G00 X1\nG01 Z2\nM30\n", "T.nc");
  ASSERT_TRUE(alarm.has_value());
  rig.ctl_.request_start();
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::alarm);
  EXPECT_EQ(rig.ctl_.last_alarm().number, interp::alarm::kFeedMissing);
  EXPECT_EQ(rig.ctl_.last_alarm().line, 2);
  EXPECT_TRUE(rig.events_of(ChannelEventKind::block_started).empty());
}

TEST(ChannelController, AllEventsOfABusyCycleFitAndKeepTheirOrder) {
  Rig rig;
  rig.load("M30\n");
  rig.ctl_.request_start();
  const auto& out = rig.step();
  ASSERT_LE(out.event_count, CycleOutput::kMaxEvents);
  std::vector<ChannelEventKind> kinds;
  for (std::size_t e = 0; e < out.event_count; ++e) {
    kinds.push_back(out.events[e].kind);
  }
  using K = ChannelEventKind;
  EXPECT_EQ(kinds,
            (std::vector<K>{K::state_changed, K::state_changed, K::state_changed, K::block_started,
                            K::block_ended, K::program_end, K::state_changed}));
  ASSERT_EQ(out.event_count, 7u);
  EXPECT_EQ(out.events[0].state, ChannelState::reset);
  EXPECT_EQ(out.events[1].state, ChannelState::idle);
  EXPECT_EQ(out.events[2].state, ChannelState::running);
  EXPECT_EQ(out.events[5].end_code, 30);
  EXPECT_EQ(out.events[6].state, ChannelState::idle);
  // The next cycle starts with an empty event list.
  EXPECT_EQ(rig.step().event_count, 0u);
}

TEST(ChannelController, RandomProgramsEndExactlyOnTheirLastPoint) {
  std::mt19937 rng(20240611u);
  std::uniform_int_distribution<int> coord(-20000, 20000);  // thousandths
  std::uniform_int_distribution<int> moves(1, 5);
  std::uniform_int_distribution<int> feed(1200, 6000);
  std::uniform_int_distribution<int> pick(0, 99);
  for (int program = 0; program < 300; ++program) {
    SCOPED_TRACE(program);
    std::ostringstream text;
    AxisVector expected = xz(0.0, 0.0);
    const int n = moves(rng);
    int line = 0;
    std::size_t blocks = 0;  // lines that program an axis (the others carry no command)
    for (int m = 0; m < n; ++m) {
      bool any_axis = false;
      const bool linear = pick(rng) < 50;
      text << (linear ? "G01" : "G00");
      for (std::size_t axis = 0; axis < 2; ++axis) {
        const int r = pick(rng);
        if (r < 20) {
          continue;  // axis not programmed
        }
        const int k = coord(rng);
        const double value = k / 1000.0;
        const bool incremental = r >= 60;
        const char letter = axis == 0 ? (incremental ? 'U' : 'X') : (incremental ? 'W' : 'Z');
        char word[32];
        std::snprintf(word, sizeof word, " %c%s%d.%03d", letter, k < 0 ? "-" : "",
                      std::abs(k) / 1000, std::abs(k) % 1000);
        text << word;
        any_axis = true;
        const double physical = axis == 0 ? value / 2.0 : value;
        expected[axis] = incremental ? expected[axis] + physical : physical;
      }
      if (linear) {
        text << " F" << feed(rng);
      }
      text << '\n';
      ++line;
      blocks += any_axis ? 1 : 0;
    }
    text << "M30\n";
    ++line;
    ++blocks;

    Rig rig;
    rig.load(text.str());
    if (::testing::Test::HasFatalFailure()) {
      return;
    }
    rig.ctl_.request_start();
    ASSERT_TRUE(rig.run_to_end()) << text.str();
    EXPECT_EQ(rig.last.state, ChannelState::idle) << text.str();
    EXPECT_EQ(rig.last.end_code, 30);
    EXPECT_EQ(rig.last.setpoints[0].pos, expected[0]) << text.str();
    EXPECT_EQ(rig.last.setpoints[1].pos, expected[1]) << text.str();
    const auto ends = rig.events_of(ChannelEventKind::program_end);
    ASSERT_EQ(ends.size(), 1u);
    EXPECT_EQ(ends[0].end_code, 30);
    EXPECT_EQ(ends[0].line, line);
    EXPECT_EQ(rig.events_of(ChannelEventKind::block_started).size(), blocks);
    EXPECT_EQ(rig.ctl_.alarm_count(), 0u);
    expect_no_jumps(rig.outputs);
  }
}

TEST(ChannelController, ReportsTheCyclesItsProgramStartedAndEnded) {
  Rig rig;
  rig.load("G00 W2.\nG04 P100\nM30\n");
  for (int i = 0; i < 3; ++i) {
    rig.step();  // idle, not started yet
  }
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  std::optional<std::uint64_t> running;
  std::optional<std::uint64_t> ended;
  for (const auto& e : rig.events) {
    if (!running && e.event.kind == ChannelEventKind::state_changed &&
        e.event.state == ChannelState::running) {
      running = e.cycle;
    }
    if (e.event.kind == ChannelEventKind::program_end) {
      ended = e.cycle;
    }
  }
  ASSERT_TRUE(running && ended);
  EXPECT_EQ(rig.last.run_start_cycle, *running);
  EXPECT_EQ(rig.last.end_cycle, *ended);
  EXPECT_GE(rig.last.end_cycle - rig.last.run_start_cycle, 100U);  // the dwell alone
  // Both stay as reported until the next start.
  for (int i = 0; i < 5; ++i) {
    rig.step();
  }
  EXPECT_EQ(rig.last.run_start_cycle, *running);
  EXPECT_EQ(rig.last.end_cycle, *ended);
}

namespace mcnc::channel {
namespace {

// Start and end events alternate in program order, one block at a time.
void expect_alternating(const std::vector<LoggedEvent>& events, std::size_t blocks) {
  std::vector<std::pair<ChannelEventKind, std::size_t>> seq;
  for (const auto& e : events) {
    if (e.event.kind == ChannelEventKind::block_started ||
        e.event.kind == ChannelEventKind::block_ended) {
      seq.emplace_back(e.event.kind, e.event.block);
    }
  }
  ASSERT_EQ(seq.size(), 2 * blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    EXPECT_EQ(seq[2 * b].first, ChannelEventKind::block_started) << b;
    EXPECT_EQ(seq[2 * b + 1].first, ChannelEventKind::block_ended) << b;
    EXPECT_EQ(seq[2 * b].second, seq[2 * b + 1].second) << b;
    if (b > 0) {
      EXPECT_GT(seq[2 * b].second, seq[2 * b - 1].second) << b;
    }
  }
}

TEST(ChannelController, BlendedBlocksEndBeforeTheNextStarts) {
  Rig rig;
  rig.load("G01 X10 Z-10 F600\nX20 Z-10\nX20 Z-20\nX30 Z-25\nM30\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  expect_alternating(rig.events, 5);
}

TEST(ChannelController, ManyBlocksThatDoNotMoveLoseNoEvents) {
  std::string program = "G01 X10 Z-10 F600\n";
  for (int i = 0; i < 100; ++i) {
    program += "G01 X10 Z-10\n";  // already there
  }
  program += "G01 X20 Z-20\nM30\n";
  Rig rig;
  rig.load(program);
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  expect_alternating(rig.events, 103);
  EXPECT_EQ(rig.events_of(ChannelEventKind::program_end).size(), 1U);
  // The blocks that do not move (lines 2-101) end before the last move (line 102) ends.
  const auto still_done = rig.first_cycle_of(ChannelEventKind::block_ended, 101);
  const auto last_done = rig.first_cycle_of(ChannelEventKind::block_ended, 102);
  ASSERT_TRUE(still_done && last_done);
  EXPECT_LT(*still_done + 10, *last_done);
}

TEST(ChannelController, ASecondRunReportsItsOwnBlocks) {
  Rig rig;
  rig.load("G01 X10 Z-10 F600\nX20 Z-20\nM30\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  const std::size_t first_run = rig.events.size();
  rig.ctl_.request_start();
  const std::uint64_t start = rig.cycle_;
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::running; }));
  ASSERT_TRUE(rig.run_to_end());
  std::size_t ended_in_first_cycles = 0;
  for (std::size_t i = first_run; i < rig.events.size(); ++i) {
    if (rig.events[i].event.kind == ChannelEventKind::block_ended &&
        rig.events[i].cycle <= start + 2) {
      ++ended_in_first_cycles;
    }
  }
  EXPECT_EQ(ended_in_first_cycles, 0U);
}

}  // namespace
}  // namespace mcnc::channel

TEST(ChannelController, ResetAfterAnAxisAlarmWaitsForTheAxesThenRunsTheProgramAgain) {
  Rig rig;
  rig.load("G00 X10\nG00 X40 Z80\nM30\n");
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.line == 2; }));
  rig.feedback_[1].alarm = true;
  rig.feedback_[1].enabled = false;
  rig.step();
  ASSERT_EQ(rig.last.state, ChannelState::alarm);
  const double z = rig.last.setpoints[1].pos;

  // Reset while the axis still reports its alarm (its reset is on the way): the channel goes to
  // reset, commands nothing and raises nothing more.
  rig.ctl_.request_reset();
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::reset);
  EXPECT_FALSE(rig.last.program_end);
  for (int i = 0; i < 20; ++i) {
    const auto& o = rig.step();
    EXPECT_EQ(o.state, ChannelState::reset);
    EXPECT_FALSE(o.setpoints[1].valid);
  }
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
  // The axis is back: idle, from where the axis stands, without moving.
  rig.feedback_[1].alarm = false;
  rig.feedback_[1].enabled = true;
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::idle);
  EXPECT_EQ(rig.last.setpoints[1].pos, z);
  // A cycle start runs the program from its start, to its end.
  rig.ctl_.request_start();
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_NEAR(rig.last.setpoints[0].pos, 20.0, 1e-9);  // X40 in diameter
  EXPECT_NEAR(rig.last.setpoints[1].pos, 80.0, 1e-9);
  EXPECT_EQ(rig.ctl_.alarm_count(), 1u);
  EXPECT_TRUE(rig.first_cycle_of(ChannelEventKind::block_started, 1).has_value());
}

TEST(ChannelController, ResetWhileMovingRampsDownThenRewinds) {
  Rig rig;
  rig.load("G01 Z200 F6000\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 600; ++i) {
    rig.step();
  }
  ASSERT_EQ(rig.last.state, ChannelState::running);
  const std::size_t from = rig.outputs.size();
  rig.ctl_.request_reset();
  // Reset, and at once idle again (the axes are enabled without alarms).
  ASSERT_TRUE(
      rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }, 5000));
  const auto changes = rig.events_of(ChannelEventKind::state_changed);
  ASSERT_GE(changes.size(), 2u);
  EXPECT_EQ(changes[changes.size() - 2].state, ChannelState::reset);
  // The ramp: no jump and more than a few cycles from full feed to rest.
  std::vector<CycleOutput> ramp(rig.outputs.begin() + static_cast<long>(from) - 1,
                                rig.outputs.end());
  expect_no_jumps(ramp);
  EXPECT_GT(ramp.size(), 10u);
  const double stopped = rig.last.setpoints[1].pos;
  EXPECT_LT(stopped, 200.0);
  for (int i = 0; i < 20; ++i) {
    rig.step();
  }
  EXPECT_EQ(rig.last.state, ChannelState::idle);
  EXPECT_EQ(rig.last.setpoints[1].pos, stopped);
  EXPECT_EQ(rig.ctl_.alarm_count(), 0u);
  EXPECT_TRUE(rig.events_of(ChannelEventKind::program_end).empty());
}

TEST(ChannelController, TheSpindleTurnsAsTheBlocksRunAndStopsWithoutAProgram) {
  Rig rig(nullptr, xz(0.0, 0.0), 1);
  rig.load("M03 S600\nG01 Z10 F600\nM04 S300\nG01 Z20\nM05\nG01 Z30\nM30\n");
  EXPECT_EQ(rig.step().spindle_direction, 0);  // idle: stopped
  rig.ctl_.request_start();
  std::vector<std::pair<double, int>> seen;  // (rpm, direction) as they change
  ASSERT_TRUE(rig.run_until([&](const CycleOutput& o) {
    if (o.state == ChannelState::running &&
        (seen.empty() || seen.back() != std::pair{o.spindle_rpm, o.spindle_direction})) {
      seen.emplace_back(o.spindle_rpm, o.spindle_direction);
    }
    // Each speed holds while its move runs.
    if (o.setpoints[1].pos > 2.0 && o.setpoints[1].pos < 8.0) {
      EXPECT_EQ(o.spindle_direction, 1);
    }
    if (o.setpoints[1].pos > 12.0 && o.setpoints[1].pos < 18.0) {
      EXPECT_EQ(o.spindle_direction, -1);
      EXPECT_EQ(o.spindle_rpm, 300.0);
    }
    return o.program_end;
  }));
  ASSERT_GE(seen.size(), 3u);
  EXPECT_EQ(seen[0], (std::pair<double, int>{600.0, 1}));
  EXPECT_EQ(seen[1], (std::pair<double, int>{300.0, -1}));
  EXPECT_EQ(seen.back().second, 0);
  EXPECT_EQ(rig.step().spindle_direction, 0);
}

TEST(ChannelController, SpindleOrientationAndOtherSpindlesAreAlarmsBeforeTheRun) {
  for (const char* program : {"M19\nM30\n", "M103 S2=500\nM30\n"}) {
    interp::InterpreterConfig c = xz_channel();
    c.spindles = 1;
    interp::InterpreterSource source(c);
    const auto alarm = source.load(program, "T.nc");
    ASSERT_TRUE(alarm.has_value()) << program;
    EXPECT_EQ(alarm->line, 1) << program;
  }
  // Without a spindle in the machine file, M03 is still for the PLC node.
  interp::InterpreterSource none(xz_channel());
  ASSERT_TRUE(none.load("M03 S600\nM30\n", "T.nc").has_value());
}

TEST(ChannelController, ASpindleAlarmStopsTheChannelAndHoldsItAfterAReset) {
  Rig rig(nullptr, xz(0.0, 0.0), 1);
  rig.load("M03 S600\nG01 Z50 F600\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 200; ++i) {
    rig.step();
  }
  ASSERT_EQ(rig.last.state, ChannelState::running);
  rig.feedback_[2].alarm = true;  // the spindle's node
  rig.feedback_[2].enabled = false;
  rig.step();
  EXPECT_EQ(rig.last.state, ChannelState::alarm);
  EXPECT_EQ(rig.ctl_.last_alarm().number, kAlarmAxisAlarm);
  EXPECT_NE(std::string(rig.ctl_.last_alarm().text.data()).find("spindle 1"), std::string::npos);
  EXPECT_EQ(rig.last.spindle_direction, 0);
  // Reset with the spindle still in fault: the channel stays in reset, a start does nothing.
  rig.ctl_.request_reset();
  rig.ctl_.request_start();
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::reset);
  }
  // The spindle back: idle, and the start asked for after the reset runs the program.
  rig.feedback_[2].alarm = false;
  rig.feedback_[2].enabled = true;
  ASSERT_TRUE(rig.run_to_end());
}

TEST(ChannelController, AnEmergencyStopDuringAResetRampStaysAnEmergencyStop) {
  Rig rig;
  rig.load("G01 Z200 F6000\nM30\n");
  rig.ctl_.request_start();
  for (int i = 0; i < 600; ++i) {
    rig.step();
  }
  rig.ctl_.request_reset();
  rig.step();  // ramping down
  rig.ctl_.emergency_stop();
  for (int i = 0; i < 300; ++i) {
    const auto& o = rig.step();
    EXPECT_EQ(o.state, ChannelState::reset);
    EXPECT_FALSE(o.setpoints[1].valid);
  }
  // A later reset does not undo it either.
  rig.ctl_.request_reset();
  rig.ctl_.request_start();
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::reset);
  }
}

}  // namespace
}  // namespace mcnc::channel

namespace mcnc::channel {
namespace {

// Counts the pulls of the interpreter behind it: what the channel has had evaluated so far.
class CountingSource final : public interp::CommandSource {
 public:
  explicit CountingSource(interp::CommandSource& inner) : inner_(inner) {}
  void rewind(const AxisVector& current) override { inner_.rewind(current); }
  std::optional<interp::PullResult> next() override {
    auto r = inner_.next();
    if (r) {
      if (const auto* c = std::get_if<Command>(&*r)) {
        last_line = c->line;
      }
    }
    return r;
  }
  [[nodiscard]] std::size_t block_count() const noexcept override { return inner_.block_count(); }
  int last_line = 0;  // the line of the last command handed out

 private:
  interp::CommandSource& inner_;
};

coordination::SyncArrival partner_arrival(std::uint32_t channel, int p,
                                          std::initializer_list<int> participants) {
  coordination::SyncArrival a;
  a.channel = channel;
  a.p = p;
  a.generation = 1;
  for (const int c : participants) {
    a.participants.set(static_cast<std::size_t>(c));
  }
  return a;
}

coordination::ChannelSet channels(std::initializer_list<int> list) {
  coordination::ChannelSet s;
  for (const int c : list) {
    s.set(static_cast<std::size_t>(c));
  }
  return s;
}

struct SyncRig {
  explicit SyncRig(const std::string& program, int spindles = 0)
      : interp([&] {
          interp::InterpreterConfig c = xz_channel();
          c.spindles = spindles;
          return c;
        }()),
        counting(interp),
        rig(&counting, xz(0.0, 0.0), spindles) {
    const auto alarm = interp.load(program, "S.nc");
    EXPECT_FALSE(alarm.has_value()) << alarm->text;
    rig.ctl_.set_partner(2, PartnerStatus{true, ChannelState::running});
    rig.ctl_.request_start();
  }
  bool run_to_arrival() {
    return rig.run_until([](const CycleOutput& o) { return o.arrival_due; });
  }
  interp::InterpreterSource interp;
  CountingSource counting;
  Rig rig;
};

TEST(ChannelSync, ArrivesWhenTheBlocksBeforeEndedAndReadsNothingAfterTheMarkUntilReleased) {
  SyncRig s("G01 X10 Z5 F300\nG04.1 P1 Q12\n#100=7\nG01 Z[#100]\nM30\n");
  ASSERT_TRUE(s.run_to_arrival());
  const CycleOutput& at = s.rig.last;
  EXPECT_EQ(at.state, ChannelState::waiting);
  EXPECT_EQ(at.arrival.p, 1);
  EXPECT_EQ(at.arrival.generation, 1U);
  EXPECT_EQ(at.arrival.participants, channels({1, 2}));
  EXPECT_EQ(at.arrival.channel, 1U);
  // The move before the mark ended in position before the arrival.
  ASSERT_TRUE(s.rig.first_cycle_of(ChannelEventKind::block_ended, 1).has_value());
  EXPECT_NEAR(s.rig.feedback_[1].act, 5.0, kInPos);
  // Read-ahead stopped at the mark: nothing after it was evaluated.
  EXPECT_EQ(s.counting.last_line, 2);
  const std::uint64_t arrived = s.rig.cycle_ - 1;
  for (int i = 0; i < 50; ++i) {
    const CycleOutput& o = s.rig.step();
    EXPECT_EQ(o.state, ChannelState::waiting);
    EXPECT_FALSE(o.arrival_due);  // arrives once
    EXPECT_TRUE(o.setpoints[1].valid);
    EXPECT_DOUBLE_EQ(o.setpoints[1].pos, 5.0);
  }
  EXPECT_EQ(s.counting.last_line, 2);
  EXPECT_EQ(s.rig.ctl_.sync().missing(), channels({2}));
  s.rig.ctl_.on_arrival(partner_arrival(2, 1, {1, 2}));
  s.rig.step();
  const auto released = s.rig.first_cycle_of(ChannelEventKind::sync_release, 2);
  ASSERT_TRUE(released.has_value());
  EXPECT_GT(*released, arrived + 50);
  EXPECT_EQ(s.rig.last.state, ChannelState::running);
  ASSERT_TRUE(s.rig.run_to_end());
  EXPECT_NEAR(s.rig.feedback_[1].act, 7.0, kInPos);  // #100 evaluated after the release
  EXPECT_GT(*s.rig.first_cycle_of(ChannelEventKind::block_started, 4), *released);
}

TEST(ChannelSync, APartnerThatArrivedFirstReleasesAtOnce) {
  SyncRig s("G01 Z2 F300\nG04.1 P3 Q12\nG01 Z4\nM30\n");
  s.rig.ctl_.on_arrival(partner_arrival(2, 3, {1, 2}));
  ASSERT_TRUE(s.run_to_arrival());
  EXPECT_EQ(s.rig.last.state, ChannelState::running);  // arrived and released in one cycle
  EXPECT_EQ(s.rig.events_of(ChannelEventKind::sync_release).size(), 1U);
  ASSERT_TRUE(s.rig.run_to_end());
}

TEST(ChannelSync, WithoutPTheMarkOnlyStopsReadAhead) {
  SyncRig s("G01 Z3 F300\nG04.1\n#100=9\nG01 Z[#100]\nM30\n");
  // While the move before runs, nothing after the mark is evaluated.
  ASSERT_TRUE(s.rig.run_until([&](const CycleOutput& o) { return o.setpoints[1].pos > 1.0; }));
  EXPECT_EQ(s.counting.last_line, 2);
  ASSERT_TRUE(s.rig.run_to_end());
  EXPECT_TRUE(s.rig.events_of(ChannelEventKind::sync_arrive).empty());
  for (const CycleOutput& o : s.rig.outputs) {
    EXPECT_NE(o.state, ChannelState::waiting);
  }
  EXPECT_GT(*s.rig.first_cycle_of(ChannelEventKind::block_started, 2),
            *s.rig.first_cycle_of(ChannelEventKind::block_ended, 1) - 1);
  EXPECT_NEAR(s.rig.feedback_[1].act, 9.0, kInPos);
}

TEST(ChannelSync, WaitsInACircleAndMismatchesAreAlarms) {
  {
    SyncRig s("G04.1 P1 Q12\nM30\n");
    ASSERT_TRUE(s.run_to_arrival());
    s.rig.ctl_.on_arrival(partner_arrival(2, 2, {1, 2}));  // CH2 waits at P2 for CH1
    s.rig.step();
    EXPECT_EQ(s.rig.last.state, ChannelState::alarm);
    EXPECT_EQ(s.rig.ctl_.last_alarm().number, kAlarmSyncDeadlock);
    EXPECT_EQ(s.rig.ctl_.last_alarm().line, 1);
  }
  {
    SyncRig s("G04.1 P1 Q12\nM30\n");
    s.rig.ctl_.on_arrival(partner_arrival(2, 1, {1, 2, 3}));
    ASSERT_TRUE(
        s.rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }, 100));
    EXPECT_EQ(s.rig.ctl_.last_alarm().number, kAlarmSyncMismatch);
  }
}

TEST(ChannelSync, APartnerGoneWhileWaitedForIsAnAlarm) {
  SyncRig s("G04.1 P1 Q12\nM30\n");
  ASSERT_TRUE(s.run_to_arrival());
  s.rig.ctl_.partner_lost(3);  // not a participant: nothing happens
  s.rig.step();
  EXPECT_EQ(s.rig.last.state, ChannelState::waiting);
  s.rig.ctl_.partner_lost(2);
  s.rig.step();
  EXPECT_EQ(s.rig.last.state, ChannelState::alarm);
  EXPECT_EQ(s.rig.ctl_.last_alarm().number, kAlarmSyncPartnerLost);
}

TEST(ChannelSync, APartnerGoneWithTheEmergencyStopIsStillTold) {
  SyncRig s("G04.1 P1 Q12\nM30\n");
  ASSERT_TRUE(s.run_to_arrival());
  s.rig.ctl_.partner_lost(2);
  s.rig.ctl_.emergency_stop();
  s.rig.step();
  EXPECT_EQ(s.rig.ctl_.last_alarm().number, kAlarmSyncPartnerLost);
  EXPECT_EQ(s.rig.ctl_.alarm_count(), 1u);
  EXPECT_EQ(s.rig.last.state, ChannelState::reset);
}

TEST(ChannelSync, TheEmergencyStopAloneEndsTheWaitWithoutAlarm) {
  SyncRig s("G04.1 P1 Q12\nM30\n");
  ASSERT_TRUE(s.run_to_arrival());
  s.rig.ctl_.partner_lost(3);  // not a participant
  s.rig.ctl_.emergency_stop();
  s.rig.step();
  EXPECT_EQ(s.rig.ctl_.alarm_count(), 0u);
  EXPECT_EQ(s.rig.last.state, ChannelState::reset);
}

TEST(ChannelSync, ResetWhileWaitingEndsTheWaitAndTheNextRunArrivesInTheNextRound) {
  SyncRig s("G04.1 P1 Q12\nG01 Z1 F300\nM30\n");
  ASSERT_TRUE(s.run_to_arrival());
  s.rig.ctl_.request_reset();
  ASSERT_TRUE(
      s.rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }, 100));
  EXPECT_FALSE(s.rig.ctl_.sync().waiting());
  s.rig.ctl_.request_start();
  ASSERT_TRUE(s.run_to_arrival());
  EXPECT_EQ(s.rig.last.arrival.generation, 2U);
  s.rig.ctl_.on_arrival(partner_arrival(2, 1, {1, 2}));  // CH2's round 1 does not release it
  s.rig.step();
  EXPECT_EQ(s.rig.last.state, ChannelState::waiting);
}

TEST(ChannelSync, TheSpindleKeepsTurningWhileTheChannelWaits) {
  SyncRig s("M03 S800\nG04.1 P1 Q12\nM05\nM30\n", 1);
  ASSERT_TRUE(s.run_to_arrival());
  for (int i = 0; i < 20; ++i) {
    const CycleOutput& o = s.rig.step();
    EXPECT_EQ(o.state, ChannelState::waiting);
    EXPECT_EQ(o.spindle_direction, 1);
    EXPECT_EQ(o.spindle_rpm, 800.0);
  }
}

}  // namespace
}  // namespace mcnc::channel

namespace mcnc::channel {
namespace {

// A command source whose called programs are scripts too.
class CallableSource final : public interp::CommandSource {
 public:
  CallableSource(std::vector<interp::PullResult> own,
                 std::map<int, std::vector<interp::PullResult>> store)
      : own_(std::move(own)), store_(std::move(store)) {}
  void rewind(const AxisVector&) override {
    script_ = &own_;
    cursor_ = 0;
  }
  std::optional<interp::PullResult> next() override {
    if (script_ == nullptr || cursor_ >= script_->size()) {
      return std::nullopt;
    }
    return (*script_)[cursor_++];
  }
  [[nodiscard]] std::size_t block_count() const noexcept override { return own_.size(); }
  std::optional<interp::ProgramAlarm> call(int number, std::span<const std::pair<int, double>> args,
                                           const AxisVector&) override {
    calls.emplace_back(number, std::vector<std::pair<int, double>>(args.begin(), args.end()));
    auto it = store_.find(number);
    if (it == store_.end()) {
      return interp::ProgramAlarm{1150, "program not found", "", 0, 0};
    }
    script_ = &it->second;
    cursor_ = 0;
    return std::nullopt;
  }
  std::vector<std::pair<int, std::vector<std::pair<int, double>>>> calls;

 private:
  std::vector<interp::PullResult> own_;
  std::map<int, std::vector<interp::PullResult>> store_;
  const std::vector<interp::PullResult>* script_ = nullptr;
  std::size_t cursor_ = 0;
};

Command g144(int line, std::size_t n, int target, int program, bool wait, int repeat = 1) {
  Command c;
  c.op = Op::subcall;
  c.line = line;
  c.n = n;
  c.channel = target;
  c.program = program;
  c.wait = wait;
  c.repeat = repeat;
  c.args = {{17, 10.0}};
  return c;
}

Command g145(int line, std::size_t n) {
  Command c;
  c.op = Op::subcall_release;
  c.line = line;
  c.n = n;
  return c;
}

// Two channels wired as the runtime wires them: what one sends at cycle N the other gets
// before its cycle N+1, with the other's status stamped N.
struct TwoChannels {
  TwoChannels(std::vector<interp::PullResult> ch1, std::vector<interp::PullResult> ch2,
              std::map<int, std::vector<interp::PullResult>> store,
              std::uint64_t call_wait_cycles = 0)
      : src1(std::move(ch1), {}), src2(std::move(ch2), std::move(store)) {
    ch[0] = std::make_unique<Node>(1, src1, call_wait_cycles);
    ch[1] = std::make_unique<Node>(2, src2, call_wait_cycles);
  }
  struct Node {
    Node(std::uint32_t id, interp::CommandSource& source, std::uint64_t call_wait_cycles)
        : planner(lathe_motion(), AxisVector{}),
          ctl(
              [&] {
                ChannelSetup s{2, {kInPos, kInPos}, kDt};
                s.channel_id = id;
                s.call_wait_cycles = call_wait_cycles;
                return s;
              }(),
              source, planner) {
      for (auto& f : feedback) {
        f.enabled = true;
        f.present = true;
      }
    }
    motion::MotionPlanner planner;
    ChannelController ctl;
    std::array<AxisFeedbackView, 2> feedback{};
    CycleOutput last{};
    std::vector<LoggedEvent> events;
  };
  void step() {
    for (int i = 0; i < 2; ++i) {
      Node& other = *ch[1 - i];
      PartnerStatus p{true, other.last.state, other.ctl.serving_call(), other.ctl.serving_caller()};
      ch[i]->ctl.set_partner(static_cast<std::uint32_t>(2 - i), p);
    }
    std::array<CycleOutput, 2> outs;
    for (int i = 0; i < 2; ++i) {
      Node& n = *ch[i];
      outs[i] = n.ctl.cycle(cycle, n.feedback);
      for (std::size_t e = 0; e < outs[i].event_count; ++e) {
        n.events.push_back({cycle, outs[i].events[e]});
      }
      for (std::size_t a = 0; a < 2; ++a) {
        if (outs[i].setpoints[a].valid) {
          n.feedback[a].cmd = n.feedback[a].act = outs[i].setpoints[a].pos;
        }
      }
    }
    for (int i = 0; i < 2; ++i) {
      Node& other = *ch[1 - i];
      if (outs[i].call_due) {
        other.ctl.on_call(outs[i].call);
      }
      for (std::size_t r = 0; r < outs[i].release_count; ++r) {
        other.ctl.on_call_release(outs[i].releases[r]);
      }
      ch[i]->last = outs[i];
    }
    ++cycle;
  }
  std::optional<std::uint64_t> first(int c, ChannelEventKind kind, int line = -1) const {
    for (const auto& e : ch[c - 1]->events) {
      if (e.event.kind == kind && (line < 0 || e.event.line == line)) {
        return e.cycle;
      }
    }
    return std::nullopt;
  }
  ChannelController& ctl(int c) { return ch[c - 1]->ctl; }
  CycleOutput& last(int c) { return ch[c - 1]->last; }

  CallableSource src1;
  CallableSource src2;
  std::array<std::unique_ptr<Node>, 2> ch;
  std::uint64_t cycle = 1;
};

std::vector<interp::PullResult> called_program(bool with_g145) {
  std::vector<interp::PullResult> p{command(Op::linear, xz(4.0, 0.0), 3, 1, 600.0)};
  if (with_g145) {
    p.emplace_back(g145(4, 2));
  }
  p.emplace_back(command(Op::linear, xz(0.0, 0.0), 5, 3, 600.0));
  p.emplace_back(program_end(6, 4, 99));
  return p;
}

TEST(ChannelCall, TheCallerWaitsForG145AndTheCalledProgramGoesOn) {
  TwoChannels m({g144(3, 1, 2, 2000, true), command(Op::linear, xz(0.0, 3.0), 4, 2, 600.0),
                 program_end(5, 3)},
                {}, {{2000, called_program(true)}});
  m.ctl(1).request_start();
  for (int i = 0; i < 3000 && !(m.last(1).program_end && m.ctl(2).serving_call() == 0 && i > 10);
       ++i) {
    m.step();
  }
  ASSERT_TRUE(m.last(1).program_end);
  ASSERT_EQ(m.src2.calls.size(), 1U);
  EXPECT_EQ(m.src2.calls[0].first, 2000);
  EXPECT_EQ(m.src2.calls[0].second, (std::vector<std::pair<int, double>>{{17, 10.0}}));
  const auto g145_at = m.first(2, ChannelEventKind::block_started, 4);
  ASSERT_TRUE(g145_at.has_value());
  EXPECT_GT(*m.first(1, ChannelEventKind::block_started, 4), *g145_at);
  // CH2 went on after its G145 while CH1 moved.
  EXPECT_LT(*m.first(2, ChannelEventKind::block_started, 5),
            *m.first(1, ChannelEventKind::program_end));
  EXPECT_EQ(m.ctl(2).serving_call(), 0U);  // the call ended with O2000
}

TEST(ChannelCall, ABusyTargetIsAnAlarmAndACallNotWaitedForGoesOnAtOnce) {
  // CH2 runs its own program: busy.
  TwoChannels busy({g144(3, 1, 2, 2000, true), program_end(4, 2)},
                   {command(Op::linear, xz(0.0, 50.0), 3, 1, 300.0), program_end(4, 2)},
                   {{2000, called_program(true)}});
  busy.ctl(2).request_start();
  for (int i = 0; i < 5; ++i) {
    busy.step();
  }
  busy.ctl(1).request_start();
  for (int i = 0; i < 20; ++i) {
    busy.step();
  }
  EXPECT_EQ(busy.last(1).state, ChannelState::alarm);
  EXPECT_EQ(busy.ctl(1).last_alarm().number, kAlarmCallBusy);
  EXPECT_TRUE(busy.src2.calls.empty());

  // H0: the caller's next block starts while the called program runs.
  TwoChannels h0({g144(3, 1, 2, 2000, false), command(Op::linear, xz(0.0, 3.0), 4, 2, 600.0),
                  program_end(5, 3)},
                 {}, {{2000, called_program(false)}});
  h0.ctl(1).request_start();
  for (int i = 0; i < 3000 && !(h0.last(1).program_end && h0.last(2).program_end); ++i) {
    h0.step();
  }
  ASSERT_TRUE(h0.first(1, ChannelEventKind::block_started, 4).has_value());
  EXPECT_LT(*h0.first(1, ChannelEventKind::block_started, 4),
            *h0.first(2, ChannelEventKind::block_started, 5));
}

TEST(ChannelCall, AResetOfTheCalledChannelReleasesTheCallerWithAnAlarm) {
  TwoChannels m({g144(3, 1, 2, 2000, true), program_end(4, 2)}, {}, {{2000, called_program(true)}});
  m.ctl(1).request_start();
  for (int i = 0; i < 20; ++i) {
    m.step();
  }
  ASSERT_EQ(m.last(2).state, ChannelState::running);
  ASSERT_EQ(m.last(1).state, ChannelState::waiting);
  m.ctl(2).request_reset();
  for (int i = 0; i < 200 && m.last(1).state != ChannelState::alarm; ++i) {
    m.step();
  }
  EXPECT_EQ(m.last(1).state, ChannelState::alarm);
  EXPECT_EQ(m.ctl(1).last_alarm().number, kAlarmCallFailed);
  EXPECT_EQ(m.ctl(2).serving_call(), 0U);
}

TEST(ChannelCall, ACallerResetWhileWaitingLeavesTheCalledProgramRunning) {
  TwoChannels m({g144(3, 1, 2, 2000, true), program_end(4, 2)}, {}, {{2000, called_program(true)}});
  m.ctl(1).request_start();
  for (int i = 0; i < 20; ++i) {
    m.step();
  }
  m.ctl(1).request_reset();
  for (int i = 0; i < 3000 && !m.last(2).program_end; ++i) {
    m.step();
  }
  EXPECT_TRUE(m.last(2).program_end);
  EXPECT_NE(m.last(1).state, ChannelState::alarm);
  EXPECT_NE(m.last(1).state, ChannelState::waiting);
}

TEST(ChannelCall, RepeatsRunTheProgramAgainAndOnlyTheFirstG145Releases) {
  TwoChannels m({g144(3, 1, 2, 2000, true, 3), program_end(4, 2)}, {},
                {{2000, called_program(true)}});
  m.ctl(1).request_start();
  for (int i = 0; i < 20000 && !(m.last(1).program_end && m.ctl(2).serving_call() == 0); ++i) {
    m.step();
  }
  int releases = 0;
  int program_ends = 0;
  for (const auto& e : m.ch[1]->events) {
    releases += e.event.kind == ChannelEventKind::subcall_release ? 1 : 0;
    program_ends += e.event.kind == ChannelEventKind::program_end ? 1 : 0;
  }
  EXPECT_EQ(m.src2.calls.size(), 3U);
  EXPECT_EQ(program_ends, 3);
  EXPECT_EQ(releases, 1);
  EXPECT_TRUE(m.last(1).program_end);
}

}  // namespace
}  // namespace mcnc::channel

namespace mcnc::channel {
namespace {

TEST(SharedWriteLog, DrainsInTheOrderWrittenAndCountsWhatDoesNotFit) {
  SharedWriteLog log;
  for (int i = 0; i < 3; ++i) {
    log.on_shared_write(500 + i, interp::macro::MacroValue::of(i));
  }
  std::vector<std::int64_t> seen;
  log.drain([&](const SharedWrite& w) { seen.push_back(w.number); });
  EXPECT_EQ(seen, (std::vector<std::int64_t>{500, 501, 502}));
  EXPECT_EQ(log.size(), 0U);
  for (std::size_t i = 0; i < SharedWriteLog::kCapacity + 5; ++i) {
    log.on_shared_write(600, interp::macro::MacroValue::of(1.0));
  }
  EXPECT_EQ(log.size(), SharedWriteLog::kCapacity);
  EXPECT_EQ(log.lost(), 5U);
}

}  // namespace
}  // namespace mcnc::channel

namespace mcnc::channel {
namespace {

TEST(ChannelSync, ACycleStartWhileWaitingIsIgnored) {
  SyncRig s("G04.1 P1 Q12\nM30\n");
  ASSERT_TRUE(s.run_to_arrival());
  s.rig.ctl_.request_start();  // the operator presses cycle start while the channel waits
  s.rig.ctl_.on_arrival(partner_arrival(2, 1, {1, 2}));
  ASSERT_TRUE(s.rig.run_to_end(100));
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(s.rig.step().state, ChannelState::idle);  // the program does not run again
  }
}

TEST(ChannelSync, TheChannelArrivesOnlyOnceItsSharedWritesAreOut) {
  SharedWriteLog log;
  interp::InterpreterSource source(xz_channel());
  ChannelSetup setup{2, {kInPos, kInPos}, kDt};
  setup.shared_writes = &log;
  motion::MotionPlanner planner(lathe_motion(), AxisVector{});
  ChannelController ctl(setup, source, planner);
  ASSERT_FALSE(source.load("G04.1 P1 Q12\nM30\n", "W.nc").has_value());
  std::vector<AxisFeedbackView> fb(2);
  for (auto& f : fb) {
    f.enabled = f.present = true;
  }
  ctl.set_partner(2, PartnerStatus{true, ChannelState::running});
  ctl.request_start();
  log.on_shared_write(500, interp::macro::MacroValue::of(1.0));  // not sent yet
  std::uint64_t cycle = 1;
  int starts = 0;  // the mark's block starts once, however long it waits for the writes
  auto count = [&](const CycleOutput& o) {
    for (std::size_t e = 0; e < o.event_count; ++e) {
      starts += o.events[e].kind == ChannelEventKind::block_started ? 1 : 0;
    }
    return o.arrival_due;
  };
  for (; cycle < 20; ++cycle) {
    EXPECT_FALSE(count(ctl.cycle(cycle, fb)));
  }
  log.drain([](const SharedWrite&) {});
  EXPECT_TRUE(count(ctl.cycle(cycle, fb)));
  EXPECT_EQ(starts, 1);
}

// Spec dafeng §3.4 decide 7: a called program may call again, but not back into its caller.
TEST(ChannelCall, ACalledProgramCallingItsCallerIsACallCycleAlarm) {
  TwoChannels m({g144(3, 1, 2, 2000, true), program_end(4, 2)}, {},
                {{2000, {g144(7, 1, 1, 1000, true), program_end(8, 2, 99)}}});
  m.ctl(1).request_start();
  for (int i = 0; i < 200 && m.last(1).state != ChannelState::alarm; ++i) {
    m.step();
  }
  EXPECT_EQ(m.ctl(2).last_alarm().number, kAlarmCallCycle);
  EXPECT_EQ(m.ctl(2).last_alarm().line, 7);
  EXPECT_NE(std::string(m.ctl(2).last_alarm().text.data()).find("call cycle"), std::string::npos);
  EXPECT_TRUE(m.src1.calls.empty());  // nothing was sent to channel 1
  // The caller learns that its call failed instead of waiting for ever.
  EXPECT_EQ(m.last(1).state, ChannelState::alarm);
  EXPECT_EQ(m.ctl(1).last_alarm().number, kAlarmCallFailed);
}

// The circle through a third channel: channel 3 called channel 2, which called channel 1 (this
// one); channel 1's called program calling channel 3 would close it.
TEST(ChannelCall, ACallCycleThroughAnotherChannelIsFoundFromThePartnersStatus) {
  CallableSource source({}, {{1000, {g144(7, 1, 3, 3000, true), program_end(8, 2, 99)}}});
  motion::MotionPlanner planner(lathe_motion(), AxisVector{});
  ChannelSetup setup{2, {kInPos, kInPos}, kDt};
  setup.channel_id = 1;
  ChannelController ctl(setup, source, planner);
  std::array<AxisFeedbackView, 2> fb{};
  for (auto& f : fb) {
    f.enabled = f.present = true;
  }
  const std::uint64_t from_3 = (std::uint64_t{3} << 40) | 1;
  const std::uint64_t from_2 = (std::uint64_t{2} << 40) | 1;
  ctl.set_partner(2, PartnerStatus{true, ChannelState::waiting, from_3, 3});
  ctl.set_partner(3, PartnerStatus{true, ChannelState::waiting, 0, 0});
  std::uint64_t cycle = 1;
  for (; cycle < 5; ++cycle) {
    ctl.cycle(cycle, fb);  // up to idle
  }
  CallRequest call;
  call.call_id = from_2;
  call.caller = 2;
  call.target = 1;
  call.program = 1000;
  ctl.on_call(call);
  for (; cycle < 100 && ctl.state() != ChannelState::alarm; ++cycle) {
    ctl.cycle(cycle, fb);
  }
  EXPECT_EQ(ctl.last_alarm().number, kAlarmCallCycle);
  EXPECT_EQ(ctl.last_alarm().line, 7);
  // Without channel 2's call from channel 3 there is no circle: channel 3 is only waiting.
  CallableSource plain({}, {{1000, {g144(7, 1, 3, 3000, true), program_end(8, 2, 99)}}});
  motion::MotionPlanner planner2(lathe_motion(), AxisVector{});
  ChannelController ok(setup, plain, planner2);
  ok.set_partner(2, PartnerStatus{true, ChannelState::waiting, 0, 0});
  ok.set_partner(3, PartnerStatus{true, ChannelState::running, 0, 0});
  for (cycle = 1; cycle < 5; ++cycle) {
    ok.cycle(cycle, fb);
  }
  ok.on_call(call);
  for (; cycle < 100 && ok.state() != ChannelState::alarm; ++cycle) {
    ok.cycle(cycle, fb);
  }
  EXPECT_EQ(ok.last_alarm().number, kAlarmCallBusy);  // channel 3 runs its own program
}

// Decide 1: a target still running this channel's earlier call is waited for, up to the
// machine's call_wait_timeout_ms.
TEST(ChannelCall, WaitingForATargetStillBusyWithTheEarlierCallEndsAfterTheTimeout) {
  const std::vector<interp::PullResult> twice{g144(3, 1, 2, 2000, false), g144(4, 2, 2, 2000, true),
                                              program_end(5, 3)};
  const std::map<int, std::vector<interp::PullResult>> slow{
      {2000, {command(Op::linear, xz(0.0, 50.0), 3, 1, 300.0), program_end(4, 2, 99)}}};
  TwoChannels m(twice, {}, slow, 300);
  m.ctl(1).request_start();
  std::uint64_t waiting_from = 0;
  for (int i = 0; i < 2000 && m.last(1).state != ChannelState::alarm; ++i) {
    m.step();
    if (waiting_from == 0 && m.last(1).state == ChannelState::waiting) {
      waiting_from = m.cycle;
    }
  }
  EXPECT_EQ(m.ctl(1).last_alarm().number, kAlarmCallTimeout);
  EXPECT_EQ(m.ctl(1).last_alarm().line, 4);
  EXPECT_NEAR(static_cast<double>(m.cycle - waiting_from), 300.0, 3.0);
  EXPECT_EQ(m.src2.calls.size(), 1U);
  // Without the limit the same program waits and makes both calls.
  TwoChannels patient(twice, {}, slow);
  patient.ctl(1).request_start();
  for (int i = 0; i < 40000 && !patient.last(1).program_end; ++i) {
    patient.step();
  }
  EXPECT_TRUE(patient.last(1).program_end);
  EXPECT_EQ(patient.src2.calls.size(), 2U);
}

// The called channel's process goes while the caller waits for its G145, and the E-stop for
// its host comes in the same cycle: the caller says which channel went.
TEST(ChannelCall, ACalledChannelGoneWithTheEmergencyStopIsStillTold) {
  TwoChannels m({g144(3, 1, 2, 2000, true), program_end(4, 2)}, {}, {{2000, called_program(true)}});
  m.ctl(1).request_start();
  for (int i = 0; i < 20; ++i) {
    m.step();
  }
  ASSERT_EQ(m.last(1).state, ChannelState::waiting);
  m.ctl(1).partner_lost(2);
  m.ctl(1).emergency_stop();
  m.step();
  EXPECT_EQ(m.ctl(1).last_alarm().number, kAlarmCallFailed);
  EXPECT_NE(std::string(m.ctl(1).last_alarm().text.data()).find("channel 2 is gone"),
            std::string::npos)
      << m.ctl(1).last_alarm().text.data();
  EXPECT_EQ(m.last(1).state, ChannelState::reset);
}

TEST(ChannelCall, ACallToAChannelWhoseProcessIsGoneIsAnAlarm) {
  TwoChannels m({g144(3, 1, 2, 2000, true), program_end(4, 2)}, {}, {{2000, called_program(true)}});
  m.ctl(1).partner_lost(2);
  m.ctl(1).request_start();
  for (int i = 0; i < 20; ++i) {
    m.step();
  }
  EXPECT_EQ(m.last(1).state, ChannelState::alarm);
  EXPECT_EQ(m.ctl(1).last_alarm().number, kAlarmCallFailed);
  EXPECT_TRUE(m.src2.calls.empty());
}

}  // namespace
}  // namespace mcnc::channel
