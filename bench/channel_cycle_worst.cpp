// The channel cycle's worst case in realtime (issue 23): ChannelController, its planner and its
// command source, woken every CYCLE_US at SCHED_FIFO as the channel process's cycle thread is,
// over a program with M98 calls into a directory of 500 programs, macro loops, G71 over a
// 100-element contour and a feed hold. Each cycle's duration (the controller's cycle() alone:
// no DDS, no trace) is recorded; the percentiles come at the end. `--in-cycle` pulls the
// interpreter inside the cycle, as the channel did before the read-ahead thread.
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/loading/read_ahead.hpp"
#include "channel/motion/motion_planner.hpp"
#include "common/clock/cycle_clock.hpp"

#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace mcnc;

namespace {

constexpr int kFirst = 7000;
constexpr int kCount = 500;

std::filesystem::path write_directory() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mcnc_bench_cycle_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (int k = 0; k < kCount; ++k) {
    std::ofstream(dir / ("O" + std::to_string(kFirst + k) + ".nc"))
        << "O" << kFirst + k << "\nG01 W-1. F4000\nW1.\nM99\n";
  }
  return dir;
}

std::string program(int repeats) {
  std::ostringstream p;
  p << "O0100\n";
  for (int r = 0; r < repeats; ++r) {
    p << "G00 X100. Z2.\n";
    for (int k = r % 7; k < kCount; k += 61) {
      p << "M98 P" << kFirst + k << "\n";
    }
    p << "#10=0\nWHILE[#10LT8]DO1\n#11=SIN[#10*10]*COS[#10*5]\n#10=#10+1\nEND1\n";
    p << "G71 U1. R0.5\nG71 P" << 1000 + r * 2 << " Q" << 1001 + r * 2 << " U0.4 W0.1 F4000\n";
    p << "N" << 1000 + r * 2 << " G00 X20.\n";
    for (int i = 1; i < 99; ++i) {
      p << "G01 X" << 20.0 + 0.6 * i << " Z" << -1.0 * i << "\n";
    }
    p << "N" << 1001 + r * 2 << " G01 X80. Z-100.\n";
  }
  p << "G00 X100. Z2.\nM30\n";
  return p.str();
}

double percentile(std::vector<std::int64_t>& ns, double q) {
  std::sort(ns.begin(), ns.end());
  return static_cast<double>(ns[static_cast<std::size_t>(q * static_cast<double>(ns.size() - 1))]) /
         1000.0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The channel cycle's worst case over a heavy program, in realtime"};
  int cycle_us = 1000;
  int repeats = 3;
  bool in_cycle = false;
  app.add_option("--cycle-us", cycle_us, "cycle")->check(CLI::Range(250, 10000));
  app.add_option("--repeats", repeats, "times the program's pattern is repeated")
      ->check(CLI::Range(1, 100));
  app.add_flag("--in-cycle", in_cycle, "pull the interpreter inside the cycle (as before)");
  CLI11_PARSE(app, argc, argv);
  std::printf("%s\n", clock::prepare_realtime_process());

  const std::filesystem::path dir = write_directory();
  interp::InterpreterConfig config;
  config.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z', false}};
  config.program_dir = dir;
  interp::InterpreterSource interpreter(config);
  if (auto alarm = interpreter.load(program(repeats), "bench.nc")) {
    std::fprintf(stderr, "program: %d %s (line %d)\n", alarm->number, alarm->text.c_str(),
                 alarm->line);
    return 2;
  }
  channel::ReadAhead read_ahead(nullptr, nullptr);
  if (!in_cycle) {
    read_ahead.start(interpreter);
  }
  motion::MotionConfig motion;
  motion.axis_count = 2;
  motion.cycle_s = cycle_us * 1e-6;
  for (std::size_t i = 0; i < 2; ++i) {
    motion.axes[i] = motion::AxisDynamics{100.0, 1000.0, 50000.0};
    motion.rapid_rate[i] = 100.0;
  }
  motion::MotionPlanner planner(motion, interp::AxisVector{});
  channel::ChannelSetup setup{2, {0.001, 0.001}, motion.cycle_s};
  channel::ChannelController controller(
      setup, in_cycle ? static_cast<interp::CommandSource&>(interpreter) : read_ahead, planner);
  std::array<channel::AxisFeedbackView, 2> feedback{};
  for (auto& f : feedback) {
    f.enabled = true;
    f.present = true;
    f.owner = 1;
  }
  (void)clock::raise_realtime_thread(clock::kCyclePriority);

  std::vector<std::int64_t> took;
  took.reserve(4'000'000);
  const std::int64_t period = static_cast<std::int64_t>(cycle_us) * 1000;
  const std::int64_t origin = clock::monotonic_ns() + 10'000'000;
  bool held = false;
  std::uint64_t hold_until = 0;
  for (std::uint64_t cycle = 0;; ++cycle) {
    clock::sleep_until_ns(origin + static_cast<std::int64_t>(cycle) * period);
    if (cycle == 1) {
      controller.request_start();
    }
    const std::int64_t t0 = clock::monotonic_ns();
    const channel::CycleOutput& out = controller.cycle(cycle, feedback);
    took.push_back(clock::monotonic_ns() - t0);
    for (std::size_t a = 0; a < 2; ++a) {
      if (out.setpoints[a].valid) {
        feedback[a].cmd = feedback[a].act = out.setpoints[a].pos;
      }
    }
    // A feed hold of 200 cycles once the first roughing passes are below Z-40.
    if (!held && feedback[1].cmd < -40.0) {
      held = true;
      controller.request_feed_hold();
      hold_until = cycle + 200;
    }
    if (held && cycle == hold_until) {
      controller.request_start();
    }
    if (out.program_end || out.state == channel::ChannelState::alarm) {
      std::printf(
          "%s after %zu cycles of %d us%s\n", out.program_end ? "program end" : "ALARM",
          took.size(), cycle_us,
          in_cycle ? ", interpreter in the cycle" : ", interpreter on the read-ahead thread");
      break;
    }
  }
  std::filesystem::remove_all(dir);
  const auto over = [&](std::int64_t ns) {
    return std::count_if(took.begin(), took.end(), [&](std::int64_t t) { return t > ns; });
  };
  std::printf("cycles over 50 us: %td, over 200 us: %td, over 1 ms: %td\n", over(50'000),
              over(200'000), over(1'000'000));
  std::printf("cycle duration: median %.1f us, p99 %.1f us, p99.99 %.1f us, max %.1f us\n",
              percentile(took, 0.5), percentile(took, 0.99), percentile(took, 0.9999),
              percentile(took, 1.0));
  return 0;
}
