// The channel cycle's worst case in realtime (issue 23): ChannelController, its planner and its
// command source, woken every CYCLE_US at SCHED_FIFO as the channel process's cycle thread is,
// over a program with M98 calls into a directory of 500 programs, macro loops, G71 over a
// 100-element contour and a feed hold. Each cycle's duration (the controller's cycle() alone:
// no DDS, no trace) is recorded; the percentiles come at the end. `--in-cycle` pulls the
// interpreter inside the cycle, as the channel did before the read-ahead thread. `--slowest N`
// tells what the slowest cycles did; `--free-run --dump FILE` runs the cycles back to back and
// writes each, so that several runs tell a cycle's own work from the host's stalls.
// `--pulls-before-settled 64` pulls a refill whole in one cycle, as the channel did before.
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

// The bench's own view of what a cycle took from the source: a pass-through that counts pulls.
class CountingSource final : public interp::CommandSource {
 public:
  explicit CountingSource(interp::CommandSource& source) : source_(source) {}
  void rewind(const interp::AxisVector& current) override { source_.rewind(current); }
  std::optional<interp::PullResult> next() override {
    ++pulls;
    return source_.next();
  }
  const interp::PullResult* take() override {
    ++pulls;
    return source_.take();
  }
  bool ready() noexcept override { return source_.ready(); }
  std::size_t block_count() const noexcept override { return source_.block_count(); }
  void adopt_position(const interp::AxisVector& at) override { source_.adopt_position(at); }
  void skip_result(bool skipped, const interp::AxisVector& skip_at,
                   const interp::AxisVector& stop_at) override {
    source_.skip_result(skipped, skip_at, stop_at);
  }
  void abandon() noexcept override { source_.abandon(); }
  bool has_program() const noexcept override { return source_.has_program(); }

  std::size_t pulls = 0;

 private:
  interp::CommandSource& source_;
};

// One cycle as the report of the slowest shows it.
struct CycleRecord {
  std::int64_t ns = 0;
  std::uint64_t cycle = 0;
  std::size_t pulls = 0;
  int line = 0;
  std::size_t events = 0;
};

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
  std::size_t slowest = 0;
  bool free_run = false;
  std::string dump;
  std::size_t pulls_before_settled = channel::ChannelSetup{}.pulls_before_settled;
  app.add_option("--cycle-us", cycle_us, "cycle")->check(CLI::Range(250, 10000));
  app.add_option("--repeats", repeats, "times the program's pattern is repeated")
      ->check(CLI::Range(1, 100));
  app.add_flag("--in-cycle", in_cycle, "pull the interpreter inside the cycle (as before)");
  app.add_option("--slowest", slowest, "print the N slowest cycles: pulls, line, events");
  app.add_flag("--free-run", free_run,
               "cycles back to back, no sleep: with --in-cycle the same cycles every run, so the "
               "least of several runs is a cycle's work without the host's stalls");
  app.add_option("--dump", dump, "write every cycle (cycle, ns, pulls, line) to this file");
  app.add_option("--pulls-before-settled", pulls_before_settled,
                 "commands a cycle pulls before it asks whether more would change the motion "
                 "(64: the whole refill in one cycle, as before)")
      ->check(CLI::Range(1, 64));
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
  setup.pulls_before_settled = pulls_before_settled;
  CountingSource counted(in_cycle ? static_cast<interp::CommandSource&>(interpreter)
                                  : static_cast<interp::CommandSource&>(read_ahead));
  channel::ChannelController controller(setup, counted, planner);
  std::array<channel::AxisFeedbackView, 2> feedback{};
  for (auto& f : feedback) {
    f.enabled = true;
    f.present = true;
    f.owner = 1;
  }
  (void)clock::raise_realtime_thread(clock::kCyclePriority);

  std::vector<std::int64_t> took;
  took.reserve(4'000'000);
  std::vector<CycleRecord> records;
  const bool record = slowest > 0 || !dump.empty();
  records.reserve(record ? 4'000'000 : 0);
  const std::int64_t period = static_cast<std::int64_t>(cycle_us) * 1000;
  const std::int64_t origin = clock::monotonic_ns() + 10'000'000;
  bool held = false;
  std::uint64_t hold_until = 0;
  for (std::uint64_t cycle = 0;; ++cycle) {
    if (!free_run) {
      clock::sleep_until_ns(origin + static_cast<std::int64_t>(cycle) * period);
    }
    if (cycle == 1) {
      controller.request_start();
    }
    const std::size_t pulls_before = counted.pulls;
    const std::int64_t t0 = clock::monotonic_ns();
    const channel::CycleOutput& out = controller.cycle(cycle, feedback);
    took.push_back(clock::monotonic_ns() - t0);
    if (record) {
      records.push_back(
          CycleRecord{took.back(), cycle, counted.pulls - pulls_before, out.line, out.event_count});
    }
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
  if (!dump.empty()) {
    std::FILE* f = std::fopen(dump.c_str(), "w");
    for (const CycleRecord& r : records) {
      std::fprintf(f, "%llu %lld %zu %d\n", static_cast<unsigned long long>(r.cycle),
                   static_cast<long long>(r.ns), r.pulls, r.line);
    }
    std::fclose(f);
  }
  if (slowest > 0) {
    std::sort(records.begin(), records.end(),
              [](const CycleRecord& a, const CycleRecord& b) { return a.ns > b.ns; });
    std::size_t pulled_cycles = 0;
    for (const CycleRecord& r : records) {
      pulled_cycles += r.pulls > 0 ? 1 : 0;
    }
    std::printf("cycles that pulled commands: %zu of %zu\n", pulled_cycles, records.size());
    for (std::size_t k = 0; k < std::min(slowest, records.size()); ++k) {
      const CycleRecord& r = records[k];
      std::printf("  %.1f us: cycle %llu, %zu pulls, line %d, %zu events\n",
                  static_cast<double>(r.ns) / 1000.0, static_cast<unsigned long long>(r.cycle),
                  r.pulls, r.line, r.events);
    }
  }
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
