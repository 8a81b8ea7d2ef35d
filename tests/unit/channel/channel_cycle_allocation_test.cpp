// The channel's cycle never allocates (issue 23): ChannelController over the read-ahead thread
// and the planner, stepped as the channel process steps them, with the allocations of the
// stepping thread counted (tests/support/allocation_counter.hpp). The program calls
// subprograms by M98 from a directory of 500 programs, loops in macro statements, roughs a
// 100-element contour (the most G71 takes; the 200 would be alarm 1142), and is held by a
// feed hold halfway; then another channel calls a program of the directory in this one (G144). The
// read-ahead thread allocates what it likes: only the cycle's thread counts. The DDS and trace
// adapters around the controller in the process (channel/wire) are not part of this test.
#include "channel_rig.hpp"
#include "support/allocation_counter.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr int kFirstProgram = 5000;
constexpr int kPrograms = 500;

// 500 programs O5000-O5499, each a short move out and back.
std::filesystem::path program_directory() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mcnc_cycle_alloc_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (int k = 0; k < kPrograms; ++k) {
    const int number = kFirstProgram + k;
    std::ofstream out(dir / ("O" + std::to_string(number) + ".nc"));
    out << "O" << number << "\nG01 W-0.5 F3000\nG01 W0.5\nM99\n";
  }
  return dir;
}

// The main program: M98 calls spread over the directory, a macro loop around some of them, a
// G71 over a contour of 200 elements, M30.
std::string main_program() {
  std::ostringstream p;
  p << "O0001\nG00 X100 Z2\n";
  for (int k = 0; k < kPrograms; k += 50) {
    p << "M98 P" << kFirstProgram + k << "\n";
  }
  p << "#1=0\nWHILE[#1LT5]DO1\n#2=#1*2+1\n#3=SQRT[#2*#2+1]\nM98 P" << kFirstProgram + 499
    << "\n#1=#1+1\nEND1\n";
  p << "G00 X100 Z2\nG71 U1 R0.5\nG71 P100 Q300 U0.4 W0.1 F600\n";
  p << "N100 G00 X20\n";
  for (int i = 1; i < 99; ++i) {
    p << "G01 X" << 20.0 + 0.6 * i << " Z" << -1.0 * i << "\n";
  }
  p << "N300 G01 X80 Z-100\n";
  p << "G00 X100 Z2\nM30\n";
  return p.str();
}

interp::InterpreterConfig xz_channel(const std::filesystem::path& dir) {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 1;
  c.channel_count = 2;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.program_dir = dir;
  return c;
}

class CountedRig : public ChannelRig {
 public:
  explicit CountedRig(const std::filesystem::path& dir)
      : ChannelRig(xz_channel(dir), alike_axes(2, kDt), xz_spindle_setup(kDt), true) {}

  // One cycle, its allocations counted: what the channel process's cycle thread does with the
  // controller (a call from another channel arrives in the cycle too).
  const CycleOutput& step() override {
    const std::uint64_t before = test::allocations();
    const CycleOutput* out = nullptr;
    {
      test::CountAllocations counting;
      if (call_ && cycle_ == call_at_) {
        ctl().on_call(*call_);
      }
      out = &channel_cycle(cycle_++, feedback_);
    }
    allocations_ += test::allocations() - before;
    follow_setpoints(*out, feedback_, 2);
    return *out;
  }

  void call_at(std::uint64_t cycle, const CallRequest& call) {
    call_ = call;
    call_at_ = cycle;
  }
  [[nodiscard]] std::uint64_t cycles() const { return cycle_; }
  [[nodiscard]] double z() const { return feedback_[1].cmd; }

  std::uint64_t allocations_ = 0;

 private:
  std::vector<AxisFeedbackView> feedback_ = standing_feedback(3, 1);
  std::uint64_t cycle_ = 0;
  std::optional<CallRequest> call_;
  std::uint64_t call_at_ = 0;
};

TEST(ChannelCycle, NeverAllocatesOverM98G71MacroLoopsAFeedHoldAndAG144Call) {
  const std::filesystem::path dir = program_directory();
  // On the heap: the fixed-capacity parts of a channel (interpreter, planner, controller) no
  // longer fit a thread's stack together with the test's frames.
  const auto owned = std::make_unique<CountedRig>(dir);
  CountedRig& rig = *owned;
  rig.load(main_program());
  rig.ctl().request_start();
  // Halfway through the G71 (the roughing passes go below Z-40): a feed hold of 300 cycles.
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.z() < -40.0; }, 400000));
  rig.ctl().request_feed_hold();
  for (int i = 0; i < 300; ++i) {
    EXPECT_NE(rig.step().state, ChannelState::running);
  }
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until(
      [](const CycleOutput& o) { return o.program_end || o.state == ChannelState::alarm; },
      1000000));
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const std::uint64_t program_cycles = rig.cycles();

  // Channel 2 calls O5123 here (G144 with #1 = 4, waiting for its G145 or end).
  for (int i = 0; i < 10; ++i) {
    rig.step();
  }
  CallRequest call;
  call.call_id = 7;
  call.caller = 2;
  call.target = 1;
  call.program = kFirstProgram + 123;
  call.wait = true;
  call.args[0] = 4.0;
  call.args_given = 1;
  rig.call_at(rig.cycles() + 1, call);
  bool called = false;
  ASSERT_TRUE(rig.run_until(
      [&](const CycleOutput& o) {
        called = called || o.state == ChannelState::running;
        return called && (o.state == ChannelState::idle || o.state == ChannelState::alarm);
      },
      100000));
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_GT(program_cycles, 2000U) << "the program ran";
  EXPECT_EQ(rig.allocations_, 0U) << "allocations on the cycle's thread";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mcnc::channel
