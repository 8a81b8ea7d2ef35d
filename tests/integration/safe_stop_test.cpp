// Stopping is safe (issue 25): an axis node told to stop while its axis moves at feed, by a
// SIGTERM of its own or through its launcher's, quick-stops the drive and disables it only once
// the drive stands. The frames on the machine's (simulated) CAN bus say so: a quick stop
// (controlword 0x0002), then the drive's statusword "quick stop active, halted" with its
// position standing, and only then the disable (controlword without "enable voltage", or NMT
// pre-operational). Every kill test also finds /dev/shm as it was before the run.
#include "bus_recorder.hpp"
#include "common/can/can_bus.hpp"
#include "harness.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

// small_lathe: Z1's drive is node 2 of bus can0.
constexpr std::uint8_t kZNode = 2;
constexpr std::uint32_t kNmtId = 0x000;
constexpr std::uint8_t kNmtEnterPreoperational = 0x80;
constexpr std::uint16_t kCwEnableVoltage = 0x0002;
constexpr std::uint16_t kCwQuickStopMask = 0x0006;  // enable voltage on, quick stop (low) active
constexpr std::uint16_t kSwStateMask = 0x006F;
constexpr std::uint16_t kSwQuickStopActive = 0x0007;
constexpr std::uint16_t kSwHalted = 0x0400;  // bit 10 in quick stop active

std::uint16_t word16(const mcnc::can::CanFrame& f) {
  return static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8));
}
std::int32_t position(const mcnc::can::CanFrame& f) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(f.data[2]) |
                                   (static_cast<std::uint32_t>(f.data[3]) << 8) |
                                   (static_cast<std::uint32_t>(f.data[4]) << 16) |
                                   (static_cast<std::uint32_t>(f.data[5]) << 24));
}

// What the bus said of one drive's stop.
struct DriveStopOnTheBus {
  long quick_stop = -1;  // index of the first RPDO1 with the quick-stop command
  long halted = -1;      // the first TPDO1 "quick stop active, halted" after it
  long disable = -1;     // the first disable: RPDO1 without enable voltage, or NMT pre-op
  bool stood = true;     // the position stood from `halted` to `disable`
};

DriveStopOnTheBus drive_stop_of(const std::vector<mcnc::can::CanFrame>& frames, std::uint8_t node) {
  DriveStopOnTheBus s;
  std::int32_t rest_position = 0;
  for (std::size_t i = 0; i < frames.size() && s.disable < 0; ++i) {
    const auto& f = frames[i];
    const auto index = static_cast<long>(i);
    if (f.id == 0x200U + node) {
      const std::uint16_t cw = word16(f);
      if ((cw & kCwEnableVoltage) == 0) {
        s.disable = index;
      } else if ((cw & kCwQuickStopMask) == kCwEnableVoltage && s.quick_stop < 0) {
        s.quick_stop = index;
      }
    } else if (f.id == kNmtId && f.dlc >= 2 && f.data[0] == kNmtEnterPreoperational &&
               (f.data[1] == node || f.data[1] == 0)) {
      s.disable = index;
    } else if (f.id == 0x180U + node && s.quick_stop >= 0) {
      const std::uint16_t sw = word16(f);
      const bool halted = (sw & kSwStateMask) == kSwQuickStopActive && (sw & kSwHalted) != 0;
      if (halted && s.halted < 0) {
        s.halted = index;
        rest_position = position(f);
      } else if (s.halted >= 0 && position(f) != rest_position) {
        s.stood = false;
      }
    }
  }
  return s;
}

std::set<std::string> shm_listing() {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/shm")) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

// small_lathe running long_feed.nc (Z to -200 at F300) in lockstep under `mcnc run`, on a host
// of its own as iceoryx sees it (its /dev/shm is the test's: what the run leaves is the run's),
// its CAN bus recorded from before the start.
class MovingLathe {
 public:
  explicit MovingLathe(int domain)
      : machine_(isolated(domain)),
        shm_before_(shm_listing()),
        trace_(machine_.file("trace.jsonl")),
        bus_("udp:239.255." + std::to_string(domain) + ".1:" + std::to_string(24000 + domain)),
        run_({bin("mcnc"), "run", machine_.path(), "--clock", "lockstep", "--program",
              "CH1=" + source("launch/programs/long_feed.nc"), "--trace", trace_},
             -1, machine_.file("launch")) {}

  [[nodiscard]] bool z_moves() const {
    return eventually([&] { return last_cmd(trace_ + ".parts/Z1.jsonl", "Z1") < -1.0; }, 90s);
  }
  [[nodiscard]] pid_t launcher() const { return run_.pid(); }
  // The pid of this machine's axis node of `axis`, or -1.
  [[nodiscard]] pid_t axis_node(const std::string& axis) const {
    for (const pid_t p : pids_with_arg("--axis " + axis)) {
      for (const pid_t q : pids_with_arg(machine_.path())) {
        if (p == q) {
          return p;
        }
      }
    }
    return -1;
  }
  int wait_end() { return run_.wait(60s); }
  [[nodiscard]] std::vector<mcnc::can::CanFrame> frames() const { return bus_.frames(); }
  [[nodiscard]] std::set<std::string> shm_before() const { return shm_before_; }
  [[nodiscard]] std::string output() const {
    return slurp(machine_.file("launch.out")) + slurp(machine_.file("launch.err"));
  }
  [[nodiscard]] std::vector<nlohmann::json> trace() const { return read_trace(trace_); }
  [[nodiscard]] const TestMachine& machine() const { return machine_; }

 private:
  static TestMachine isolated(int domain) {
    isolate_iceoryx_host();
    return TestMachine("small_lathe.yaml", domain);
  }

  TestMachine machine_;
  std::set<std::string> shm_before_;
  std::string trace_;
  BusRecorder bus_;
  Background run_;
};

void expect_quick_stop_then_rest_then_disable(const std::vector<mcnc::can::CanFrame>& frames,
                                              std::size_t from, const std::string& output) {
  const std::vector<mcnc::can::CanFrame> after(frames.begin() + static_cast<long>(from),
                                               frames.end());
  const DriveStopOnTheBus s = drive_stop_of(after, kZNode);
  std::cout << after.size() << " frames after the signal; Z's quick stop at " << s.quick_stop
            << ", halted at " << s.halted << ", disabled at " << s.disable << "\n";
  ASSERT_GE(s.quick_stop, 0) << "no quick stop of Z's drive on the bus\n" << output;
  ASSERT_GE(s.halted, 0) << "Z's drive never said it halted\n" << output;
  ASSERT_GE(s.disable, 0) << "Z's drive was never disabled\n" << output;
  EXPECT_LT(s.quick_stop, s.halted);
  EXPECT_LT(s.halted, s.disable) << "disabled before it stood";
  EXPECT_TRUE(s.stood) << "the drive moved after it said it halted";
}

}  // namespace

// SIGTERM to Z1 (not its bus's SYNC producer) while Z moves at F300: Z1 quick-stops its drive,
// which X1's SYNC steps to rest, before disabling it; the run ends in an alarm.
TEST(SafeStop, ASigtermToAMovingAxisNodeQuickStopsItsDriveBeforeDisablingIt) {
  MovingLathe lathe(138);
  ASSERT_TRUE(lathe.z_moves()) << lathe.output();
  const pid_t z1 = lathe.axis_node("Z1");
  ASSERT_GT(z1, 0);
  const std::size_t from = lathe.frames().size();
  ASSERT_EQ(::kill(z1, SIGTERM), 0);
  EXPECT_EQ(lathe.wait_end(), 1) << lathe.output();
  expect_quick_stop_then_rest_then_disable(lathe.frames(), from, lathe.output());
  EXPECT_EQ(shm_listing(), lathe.shm_before()) << lathe.output();
}

// SIGTERM to the launcher while Z moves: it E-stops the machine, and every node brings its
// drive to rest before disabling it.
TEST(SafeStop, ASigtermToTheLauncherQuickStopsTheMovingDriveBeforeDisablingIt) {
  MovingLathe lathe(139);
  ASSERT_TRUE(lathe.z_moves()) << lathe.output();
  const std::size_t from = lathe.frames().size();
  ASSERT_EQ(::kill(lathe.launcher(), SIGTERM), 0);
  EXPECT_EQ(lathe.wait_end(), 1) << lathe.output();
  expect_quick_stop_then_rest_then_disable(lathe.frames(), from, lathe.output());
  EXPECT_EQ(shm_listing(), lathe.shm_before()) << lathe.output();
}

// kill -9 of Z1 on Fast DDS, whose processes keep shared memory in /dev/shm: the launcher
// E-stops the machine, and after the run /dev/shm holds what it held before it (Z1's segments,
// data-sharing files and port files included).
TEST(SafeStop, AChildKilledOnFastDdsLeavesNothingInDevShm) {
  ASSERT_EQ(::setenv("MCNC_MIDDLEWARE", "fastdds", 1), 0);
  MovingLathe lathe(144);
  ASSERT_TRUE(lathe.z_moves()) << lathe.output();
  const pid_t z1 = lathe.axis_node("Z1");
  ASSERT_GT(z1, 0);
  std::size_t dds_files = 0;
  for (const auto& name : shm_listing()) {
    dds_files += name.rfind("fast", 0) == 0 ? 1 : 0;
  }
  std::cout << dds_files << " Fast DDS files in /dev/shm during the run\n";
  ASSERT_GT(dds_files, 0U) << "the run is not on Fast DDS";
  ASSERT_EQ(::kill(z1, SIGKILL), 0);
  EXPECT_EQ(lathe.wait_end(), 1) << lathe.output();
  EXPECT_EQ(shm_listing(), lathe.shm_before()) << lathe.output();
  ::unsetenv("MCNC_MIDDLEWARE");
}

// kill -9 of the launcher while Z moves at feed, on Fast DDS (no RouDi; its processes keep
// shared memory in /dev/shm): its processes are not left running unsupervised. Each gets
// SIGTERM from the kernel as the launcher dies, as from the launcher: the axis nodes quick-stop
// their drives and disable them at rest, while the drive simulator, standing for the drives'
// hardware, answers them until their bus is quiet. Nothing of the machine is left running, and
// the next run of the machine on that host removes what the killed run left in /dev/shm.
TEST(SafeStop, AKill9OfTheLauncherQuickStopsTheMovingDriveAndTheNextRunCleansUp) {
  ASSERT_EQ(::setenv("MCNC_MIDDLEWARE", "fastdds", 1), 0);
  MovingLathe lathe(227);
  ASSERT_TRUE(lathe.z_moves()) << lathe.output();
  ASSERT_FALSE(pids_with_arg(lathe.machine().path()).empty());
  const std::size_t from = lathe.frames().size();
  ASSERT_EQ(::kill(lathe.launcher(), SIGKILL), 0);
  EXPECT_EQ(lathe.wait_end(), -SIGKILL);
  EXPECT_TRUE(eventually([&] { return pids_with_arg(lathe.machine().path()).empty(); }, 30s))
      << "left running after the launcher was killed";
  expect_quick_stop_then_rest_then_disable(lathe.frames(), from, lathe.output());
  // Z stood short of the program's end point (Z-200), where the quick stop left it.
  EXPECT_GT(last_cmd(lathe.machine().file("trace.jsonl") + ".parts/Z1.jsonl", "Z1"), -199.0);

  std::size_t left = 0;
  for (const auto& name : shm_listing()) {
    left += lathe.shm_before().count(name) == 0 ? 1 : 0;
  }
  std::cout << left << " files the killed run left in /dev/shm\n";
  const RunResult next = run({bin("mcnc"), "run", lathe.machine().path(), "--clock", "lockstep",
                              "--program", "CH1=" + source("launch/programs/xz_move.nc")},
                             -1, 120s);
  EXPECT_EQ(next.exit_code, 0) << next.out << next.err;
  EXPECT_EQ(shm_listing(), lathe.shm_before()) << next.out << next.err;
  ::unsetenv("MCNC_MIDDLEWARE");
}
