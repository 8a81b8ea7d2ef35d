// The host's own timer wake-up, the floor under the cycle-start alignment between hosts
// (issue 22). THREADS threads at the axis node's cycle priority sleep to the same absolute
// CLOCK_MONOTONIC due times, CYCLE_US apart, as the first axis node of each simulated host does.
// Their clocks are one clock, so every difference between them is this machine's scheduling:
// the lateness of each wake-up, and per cycle the spread between the earliest and the latest
// thread (the alignment that perfect clocks would give, with the hosts sharing these cores).
// Each thread only reads the clock after it wakes: the cycles' own work is not in the figure.
#include "common/clock/cycle_clock.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace {

double percentile_us(std::vector<std::int64_t> ns, double q) {
  if (ns.empty()) {
    return 0.0;
  }
  std::sort(ns.begin(), ns.end());
  const auto index = static_cast<std::size_t>(q * static_cast<double>(ns.size() - 1));
  return static_cast<double>(ns[index]) / 1000.0;
}

void print_row(const char* what, const std::vector<std::int64_t>& ns) {
  std::printf("  %s: median %.0f us, p99 %.0f us, p99.9 %.0f us, max %.0f us\n", what,
              percentile_us(ns, 0.5), percentile_us(ns, 0.99), percentile_us(ns, 0.999),
              percentile_us(ns, 1.0));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Timer wake-up lateness and spread of threads due at the same times"};
  int threads = 1;
  int cycles = 5000;
  int cycle_us = 2000;
  app.add_option("--threads", threads, "threads due at the same times (one per simulated host)")
      ->check(CLI::Range(1, 64));
  app.add_option("--cycles", cycles, "cycles")->check(CLI::Range(10, 10'000'000));
  app.add_option("--cycle-us", cycle_us, "cycle in microseconds")->check(CLI::Range(100, 100'000));
  std::string idle_cpus = "poll";
  app.add_option("--idle-cpus", idle_cpus,
                 "poll: as a realtime process of the machine (CPU latency 0, decision 138); "
                 "kernel: the idle states the kernel chooses")
      ->check(CLI::IsMember({"poll", "kernel"}));
  CLI11_PARSE(app, argc, argv);

  std::printf("%s\n", mcnc::clock::prepare_realtime_process(
                          idle_cpus == "poll" ? mcnc::clock::IdleCpus::poll
                                              : mcnc::clock::IdleCpus::kernel_default));
  const std::int64_t period_ns = static_cast<std::int64_t>(cycle_us) * 1000;
  // Far enough ahead for every thread to be asleep before the first due time.
  const std::int64_t origin_ns = mcnc::clock::monotonic_ns() + 50'000'000;
  const auto n_threads = static_cast<std::size_t>(threads);
  const auto n_cycles = static_cast<std::size_t>(cycles);
  std::vector<std::vector<std::int64_t>> late(n_threads, std::vector<std::int64_t>(n_cycles));
  bool raised = true;
  std::vector<std::thread> sleepers;
  std::vector<char> thread_raised(n_threads, 0);
  for (std::size_t t = 0; t < n_threads; ++t) {
    sleepers.emplace_back([&, t] {
      thread_raised[t] =
          mcnc::clock::raise_realtime_thread(mcnc::clock::kAxisCyclePriority) ? 1 : 0;
      for (std::size_t c = 0; c < n_cycles; ++c) {
        const std::int64_t due = origin_ns + static_cast<std::int64_t>(c + 1) * period_ns;
        mcnc::clock::sleep_until_ns(due);
        late[t][c] = mcnc::clock::monotonic_ns() - due;
      }
    });
  }
  for (auto& s : sleepers) {
    s.join();
  }
  for (const char r : thread_raised) {
    raised = raised && r != 0;
  }

  std::vector<std::int64_t> all;
  std::vector<std::int64_t> spread(n_cycles);
  for (std::size_t c = 0; c < n_cycles; ++c) {
    std::int64_t lo = late[0][c];
    std::int64_t hi = late[0][c];
    for (std::size_t t = 0; t < n_threads; ++t) {
      all.push_back(late[t][c]);
      lo = std::min(lo, late[t][c]);
      hi = std::max(hi, late[t][c]);
    }
    spread[c] = hi - lo;
  }
  std::printf("%d thread(s) at SCHED_FIFO %d%s, %d cycles of %d us\n", threads,
              mcnc::clock::kAxisCyclePriority, raised ? "" : " (NOT raised: run as root)", cycles,
              cycle_us);
  print_row("wake-up lateness", all);
  if (threads > 1) {
    print_row("spread between the threads per cycle", spread);
  }
  return 0;
}
