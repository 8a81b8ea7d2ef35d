// CAN bus figures of a machine (bench/README.md): frames and bus load per bus at the machine's
// cycle, and the round trip RPDO + SYNC -> TPDO on a transport, measured against the drive
// simulator on the same bus (UDP here; SocketCAN inside the socketcan tests' QEMU guest). Not a
// test.
// Also how punctually the realtime SYNC timer sends at its offset inside the cycle.
//   mcnc_bench_can MACHINE.yaml [--uri URI] [--cycles N] [--sync-seconds S]
#include "axisnode/drivesim/drive_bus_simulator.hpp"
#include "axisnode/link/drive_link.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/frames.hpp"
#include "common/can/can_bus.hpp"
#include "common/clock/cycle_clock.hpp"
#include "common/config/machine_config.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

namespace {

using namespace mcnc;
using Clock = std::chrono::steady_clock;

void print_load(const config::MachineConfig& machine) {
  std::printf("machine %s, cycle %d us\n", machine.name.c_str(), machine.cycle_us);
  std::printf("| bus | bit/s | axes | spindles | frames per cycle | bits per cycle | load |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const config::BusConfig& bus : machine.buses) {
    int axes = 0;
    int spindles = 0;
    int bits = config::can_frame_bits(1);  // SYNC
    for (const config::AxisConfig& a : machine.axes) {
      if (a.bus != bus.name) {
        continue;
      }
      (a.type == config::AxisType::spindle ? spindles : axes) += 1;
      bits += config::axis_bits_per_cycle(a);
    }
    std::printf("| %s | %d | %d | %d | %d | %d | %.1f %% |\n", bus.name.c_str(), bus.bitrate, axes,
                spindles, 1 + 2 * axes + 3 * spindles, bits,
                100.0 * bits / (static_cast<double>(bus.bitrate) * machine.cycle_us * 1e-6));
  }
}

// The master sends RPDO1 then SYNC; the simulated drive answers SYNC with TPDO1. The time from
// the RPDO's send to the TPDO's arrival.
void round_trip(const std::string& uri, int cycles) {
  auto master = can::open_can_bus(uri);
  auto device = can::open_can_bus(uri);
  drivesim::DriveBusSimulator sim({drivesim::DriveParams{}}, 0.001);
  std::array<can::CanFrame, 8> out{};
  sim.power_on(out);
  std::atomic<bool> stop{false};
  std::thread drive([&] {
    can::CanFrame in;
    while (!stop) {
      if (device->receive(in, std::chrono::milliseconds(50)) != can::BusResult::ok) {
        continue;
      }
      const std::size_t n = sim.handle(in, out);
      for (std::size_t i = 0; i < n; ++i) {
        device->send(out[i]);
      }
    }
  });
  master->send(canopen::encode_nmt(canopen::NmtCommand::start, 1));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(cycles));
  can::CanFrame in;
  for (int k = 0; k < cycles + 200; ++k) {
    const auto t0 = Clock::now();
    master->send(canopen::encode_rpdo_csp(1, canopen::RxPdoCsp{0x0F, k}));
    master->send(canopen::encode_sync(static_cast<std::uint8_t>(k % 240 + 1)));
    bool got = false;
    while (!got) {
      if (master->receive(in, std::chrono::milliseconds(100)) != can::BusResult::ok) {
        break;
      }
      got = in.id == 0x181;
    }
    if (got && k >= 200) {  // 200 to warm up
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    }
  }
  stop = true;
  drive.join();
  std::sort(us.begin(), us.end());
  if (us.empty()) {
    std::printf("%s: no answer\n", uri.c_str());
    return;
  }
  std::printf("round trip RPDO + SYNC -> TPDO on %s: %zu samples, median %.0f us, p99 %.0f us\n",
              uri.c_str(), us.size(), us[us.size() / 2], us[us.size() * 99 / 100]);
}

// The SYNC timer of the first bus's producer, as the axis node runs it in realtime: how late
// after its due time (start + n cycles + offset) each SYNC went out.
void sync_timing(const config::MachineConfig& machine, const std::string& uri, double seconds) {
  process::Wakeup wake;
  axisnode::DriveLink link(can::open_can_bus(uri), 1, true, {}, wake);
  const std::int64_t period = static_cast<std::int64_t>(machine.cycle_us) * 1000;
  const std::int64_t offset =
      static_cast<std::int64_t>(machine.buses.front().sync_offset_us) * 1000;
  link.start_sync_timer(canopen::SyncSchedule(clock::monotonic_ns() + 10'000'000, period, offset));
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  link.stop_sync_timer();
  std::vector<std::int64_t> late = link.sync_lateness();
  if (late.empty()) {
    std::printf("SYNC timer: nothing sent\n");
    return;
  }
  std::sort(late.begin(), late.end());
  std::printf(
      "SYNC timer on %s, offset %d us of %d us: %zu SYNCs (the last ones kept), late by median "
      "%.1f us, p99 %.1f us, max %.1f us; %llu skipped\n",
      uri.c_str(), machine.buses.front().sync_offset_us, machine.cycle_us, late.size(),
      static_cast<double>(late[late.size() / 2]) / 1e3,
      static_cast<double>(late[late.size() * 99 / 100]) / 1e3,
      static_cast<double>(late.back()) / 1e3,
      static_cast<unsigned long long>(link.syncs_skipped()));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"CAN bus figures: bus load per machine, RPDO -> TPDO round trip per transport"};
  std::string machine_path;
  std::string uri = "udp:239.255.77.1:24077";
  int cycles = 10000;
  app.add_option("machine", machine_path, "machine file")->required();
  app.add_option("--uri", uri, "transport for the round trip (udp:... or socketcan:IF)");
  app.add_option("--cycles", cycles, "round trips to measure");
  double sync_seconds = 5.0;
  app.add_option("--sync-seconds", sync_seconds, "how long to time the SYNC timer (0: not)");
  CLI11_PARSE(app, argc, argv);
  // As the realtime processes do: timer slack 1 ns, SCHED_FIFO where permitted.
  std::printf("realtime: %s\n", clock::prepare_realtime_process());
  const config::MachineConfig machine = config::load_machine_file(machine_path);
  print_load(machine);
  round_trip(uri, cycles);
  if (sync_seconds > 0.0) {
    sync_timing(machine, uri, sync_seconds);
  }
  return 0;
}
