// A refill of the look-ahead is spread over cycles (issue 23, the cycle's worst case): past
// `pulls_before_settled` commands a cycle the channel pulls on only while the window's end holds
// down what the planner's next cycle may do. The motion stays what a channel that pulls its
// whole 64 a cycle makes, cycle for cycle, bit for bit; only the pulls per cycle change.
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;

// Counts the commands the channel takes.
class CountingSource final : public interp::CommandSource {
 public:
  explicit CountingSource(interp::CommandSource& inner) : inner_(inner) {}
  void rewind(const AxisVector& current) override { inner_.rewind(current); }
  std::optional<interp::PullResult> next() override {
    ++pulls;
    return inner_.next();
  }
  const interp::PullResult* take() override {
    ++pulls;
    return inner_.take();
  }
  bool ready() noexcept override { return inner_.ready(); }
  [[nodiscard]] std::size_t block_count() const noexcept override { return inner_.block_count(); }
  void adopt_position(const AxisVector& at) override { inner_.adopt_position(at); }
  void abandon() noexcept override { inner_.abandon(); }
  [[nodiscard]] bool has_program() const noexcept override { return inner_.has_program(); }
  std::size_t pulls = 0;

 private:
  interp::CommandSource& inner_;
};

// What a cycle commands.
struct Commanded {
  ChannelState state = ChannelState::reset;
  int line = 0;
  std::size_t event_count = 0;
  std::array<double, 2> pos{};
  std::array<double, 2> vel{};
  bool program_end = false;
};

struct RefillRun {
  std::vector<Commanded> outputs;
  std::vector<std::size_t> pulls;  // per cycle
};

// The program run to its end with the channel pulling at least `settled` a cycle.
RefillRun run(const std::string& program, std::size_t settled, bool feed_hold) {
  interp::InterpreterConfig config;
  config.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z', false}};
  interp::InterpreterSource source(config);
  const auto alarm = source.load(program, "R.nc");
  EXPECT_FALSE(alarm.has_value()) << alarm->text;
  CountingSource counted(source);
  motion::MotionPlanner planner(alike_axes(2, kDt), AxisVector{});
  ChannelSetup setup{2, {0.001, 0.001}, kDt};
  setup.pulls_before_settled = settled;
  ChannelController ctl(setup, counted, planner);
  std::vector<AxisFeedbackView> feedback = standing_feedback(2, 1);
  RefillRun r;
  ctl.request_start();
  for (std::uint64_t cycle = 0; cycle < 200000; ++cycle) {
    if (feed_hold && cycle == 700) {
      ctl.request_feed_hold();
    }
    if (feed_hold && cycle == 900) {
      ctl.request_start();
    }
    const std::size_t before = counted.pulls;
    const CycleOutput& out = ctl.cycle(cycle, feedback);
    follow_setpoints(out, feedback, 2);
    r.outputs.push_back({out.state,
                         out.line,
                         out.event_count,
                         {out.setpoints[0].pos, out.setpoints[1].pos},
                         {out.setpoints[0].vel, out.setpoints[1].vel},
                         out.program_end});
    r.pulls.push_back(counted.pulls - before);
    if (out.program_end || out.state == ChannelState::alarm) {
      break;
    }
  }
  return r;
}

void expect_same_motion(const RefillRun& eager, const RefillRun& spread) {
  ASSERT_EQ(eager.outputs.size(), spread.outputs.size());
  for (std::size_t c = 0; c < eager.outputs.size(); ++c) {
    const Commanded& a = eager.outputs[c];
    const Commanded& b = spread.outputs[c];
    ASSERT_EQ(a.state, b.state) << "cycle " << c;
    ASSERT_EQ(a.line, b.line) << "cycle " << c;
    ASSERT_EQ(a.event_count, b.event_count) << "cycle " << c;
    for (std::size_t i = 0; i < 2; ++i) {
      // Bit for bit: the planner saw the same window wherever it mattered.
      ASSERT_EQ(a.pos[i], b.pos[i]) << "cycle " << c << " axis " << i;
      ASSERT_EQ(a.vel[i], b.vel[i]) << "cycle " << c << " axis " << i;
    }
  }
}

// Lines with corners of every angle (G64 blends) and feeds that change: a stretch of long ones,
// where 16 blocks hold more than the way to a stop; a read-ahead stop (G04.1), then short lines
// straight on at the highest feed, whose speed in the refill is held down by blocks far past
// the first 16; long ones again; a dwell and a rapid.
std::string mixed_program(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> step(0.5, 3.0);
  std::uniform_real_distribution<double> short_step(0.01, 0.2);
  std::uniform_int_distribution<int> feed(1, 10);
  std::ostringstream p;
  p << "G00 X0 Z0\n";
  double x = 0.0;
  double z = 0.0;
  for (int k = 0; k < 450; ++k) {
    if (k == 150) {  // a read-ahead stop: the short lines come in a refill
      p << "G04.1\n";
    }
    if (k >= 150 && k < 300) {  // straight on at the highest feed: no corner slows it
      z -= short_step(random);
      p << "G01 Z" << z << " F6000\n";
      continue;
    }
    const double d = step(random);
    x += (k % 2 == 0 ? 0.5 : -0.5) * d;
    z -= d;
    p << "G01 X" << x << " Z" << z << " F" << 600 * feed(random) << "\n";
    if (k == 100) {
      p << "G04 P0.05\n";
    }
    if (k == 350) {
      p << "G00 X" << x + 2.0 << "\n";
    }
  }
  p << "M30\n";
  return p.str();
}

std::size_t first_pulls(const RefillRun& r) {
  const auto it = std::find_if(r.pulls.begin(), r.pulls.end(), [](std::size_t n) { return n > 0; });
  return it == r.pulls.end() ? 0 : *it;
}

TEST(ChannelRefill, PullsSixteenACycleWhereMoreWouldNotChangeTheMotionWhichStaysTheSame) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(seed);
    const std::string program = mixed_program(seed);
    const RefillRun eager = run(program, 64, false);
    const RefillRun spread = run(program, 16, false);
    ASSERT_TRUE(eager.outputs.back().program_end);
    expect_same_motion(eager, spread);
    // At the start the eager channel took 64 commands, the spread one 16.
    EXPECT_EQ(first_pulls(eager), 64U);
    EXPECT_EQ(first_pulls(spread), 16U);
  }
}

TEST(ChannelRefill, AFeedHoldAndItsRestartMoveAlike) {
  const std::string program = mixed_program(7);
  const RefillRun eager = run(program, 64, true);
  const RefillRun spread = run(program, 16, true);
  ASSERT_TRUE(eager.outputs.back().program_end);
  expect_same_motion(eager, spread);
}

// Where the window's end does hold the speed down (blocks so short that 16 of them are less
// than the way to a stop), the channel pulls on, up to its 64.
TEST(ChannelRefill, BlocksShorterThanTheWayToAStopArePulledOnUpToTheWhole64) {
  std::ostringstream p;
  p << "G01 X0 Z0 F6000\n";
  for (int k = 1; k <= 300; ++k) {
    p << "G01 Z" << -0.01 * k << "\n";
  }
  p << "M30\n";
  const RefillRun eager = run(p.str(), 64, false);
  const RefillRun spread = run(p.str(), 16, false);
  ASSERT_TRUE(eager.outputs.back().program_end);
  expect_same_motion(eager, spread);
  EXPECT_EQ(*std::max_element(spread.pulls.begin(), spread.pulls.end()), 64U);
}

}  // namespace
}  // namespace mcnc::channel
