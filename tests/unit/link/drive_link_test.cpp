// The axis node's drive link against the drive simulator on a bus in memory: its lifecycle, and
// read() and write() carrying what the PDO layout of the start-up says.
#include "simulated_bus.hpp"

#include "axisnode/link/drive_link.hpp"
#include "canopen/cia402/cia402_state.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "common/clock/cycle_clock.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <thread>

using namespace mcnc;
using namespace std::chrono_literals;
using axisnode::DriveLifecycle;
using axisnode::DriveStatus;

namespace {

constexpr double kCycle = 0.002;
constexpr std::int64_t kPeriodNs = 2'000'000;

struct Link {
  test::SimulatedBus bus;
  process::Wakeup wake;
  axisnode::DriveLink link;

  explicit Link(std::pair<std::unique_ptr<test::MemoryCanBus>, std::unique_ptr<test::MemoryCanBus>>
                    ends = test::MemoryCanBus::pair())
      : bus(std::move(ends.second), drivesim::DriveParams{3, 10000.0, 0.004, 500.0, 5000.0, 2.0},
            kCycle),
        link(std::move(ends.first), 3, true, {}, wake) {}
};

}  // namespace

TEST(DriveLink, ALayoutBeyondACanFrameFailsTheConfigurationAndNothingCycles) {
  Link l;
  canopen::NodeStartupConfig startup{3};
  startup.pdos = canopen::axis_pdos(false, true, true);
  startup.pdos.tpdo2.objects[startup.pdos.tpdo2.count++] = canopen::MappedObject{0x6077, 0, 16};
  const auto error = l.link.configure(startup, 2s);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(*error,
            "node 3: TPDO2 cannot be mapped: the mapping is longer than the 8 bytes a classic CAN "
            "frame carries");
  EXPECT_EQ(l.link.lifecycle(), DriveLifecycle::failed);
  EXPECT_EQ(l.link.read(0, kPeriodNs), DriveStatus::error);
  EXPECT_EQ(l.link.write(0, kPeriodNs), DriveStatus::error) << "not active: nothing is sent";
}

TEST(DriveLink, ReadAndWriteCarryTheSpindleLayoutBothWays) {
  Link l;
  canopen::NodeStartupConfig startup{3};
  startup.pdos = canopen::spindle_pdos();  // the mode travels in RPDO1 and TPDO1
  startup.pdos.tpdo2.objects[startup.pdos.tpdo2.count++] = canopen::MappedObject{0x606C, 0, 32};
  ASSERT_EQ(l.link.configure(startup, 5s), std::nullopt);
  EXPECT_EQ(l.link.lifecycle(), DriveLifecycle::inactive);
  EXPECT_EQ(l.link.write(0, kPeriodNs), DriveStatus::error) << "configured, not active yet";
  axisnode::DriveActivation activation;
  activation.lockstep = true;
  l.link.activate(activation);
  ASSERT_EQ(l.link.lifecycle(), DriveLifecycle::active);

  ASSERT_EQ(l.link.read(0, kPeriodNs), DriveStatus::ok);
  EXPECT_FALSE(l.link.state().fresh) << "no SYNC yet, no answer";
  // Enable (shutdown, switch on, enable operation), then CSV at 1000 counts/s.
  const std::uint16_t steps[] = {cia402::encode_controlword(cia402::Command::shutdown),
                                 cia402::encode_controlword(cia402::Command::switch_on),
                                 cia402::encode_controlword(cia402::Command::enable_operation)};
  std::int64_t time = 0;
  for (int cycle = 0; cycle < 40; ++cycle) {
    canopen::DriveCommand& command = l.link.command();
    command.controlword = steps[std::min(cycle, 2)];
    command.mode = 9;
    command.target_velocity = 1000;
    command.target_position = l.link.state().feedback.position_actual;
    ASSERT_EQ(l.link.write(time, kPeriodNs), DriveStatus::ok) << cycle;
    time += kPeriodNs;
    ASSERT_EQ(l.link.read(time, kPeriodNs), DriveStatus::ok) << cycle;
    EXPECT_TRUE(l.link.state().fresh) << "lockstep: write() waited for the answer, " << cycle;
    EXPECT_EQ(l.link.state().answers, static_cast<std::uint64_t>(cycle + 1))
        << "an answer is complete with both TPDOs";
  }
  ASSERT_EQ(l.link.read(time, kPeriodNs), DriveStatus::ok);
  EXPECT_FALSE(l.link.state().fresh) << "nothing new since the last read";
  const canopen::DriveFeedback& fb = l.link.state().feedback;
  EXPECT_EQ(cia402::decode_statusword(fb.statusword), cia402::State::operation_enabled);
  EXPECT_EQ(fb.mode_display, 9) << "the mode went out in RPDO1 and came back in TPDO1";
  EXPECT_NEAR(fb.velocity_actual, 1000, 50) << "RPDO2's target velocity, TPDO2's actual";
  EXPECT_NEAR(fb.position_actual, 20000 + 1000 * 40 * kCycle, 100) << "from 2.0 units on";

  l.link.deactivate(canopen::DriveCommand{});
  EXPECT_EQ(l.link.lifecycle(), DriveLifecycle::inactive);
  EXPECT_EQ(l.link.write(time, kPeriodNs), DriveStatus::error);
}

namespace {

// Configures and activates `l` in lockstep, the spindle layout, and enables its drive in CSV
// turning at 1000 counts/s. `abandon` as the axis node's.
void run_enabled(Link& l, const std::function<bool()>& abandon, std::int64_t& time) {
  canopen::NodeStartupConfig startup{3};
  startup.pdos = canopen::spindle_pdos();
  ASSERT_EQ(l.link.configure(startup, 5s), std::nullopt);
  axisnode::DriveActivation activation;
  activation.lockstep = true;
  activation.abandon = abandon;
  l.link.activate(activation);
  const std::uint16_t steps[] = {cia402::encode_controlword(cia402::Command::shutdown),
                                 cia402::encode_controlword(cia402::Command::switch_on),
                                 cia402::encode_controlword(cia402::Command::enable_operation)};
  for (int cycle = 0; cycle < 10; ++cycle) {
    canopen::DriveCommand& command = l.link.command();
    command.controlword = steps[std::min(cycle, 2)];
    command.mode = 9;
    command.target_velocity = 1000;
    ASSERT_EQ(l.link.write(time, kPeriodNs), DriveStatus::ok) << cycle;
    time += kPeriodNs;
    ASSERT_EQ(l.link.read(time, kPeriodNs), DriveStatus::ok) << cycle;
    ASSERT_TRUE(l.link.state().fresh) << cycle;
  }
}

}  // namespace

// Issue 25: an NMT stop from another node of the bus takes the drive out of operational; it
// answers no SYNC, and its heartbeat says "stopped". The lockstep wait for its answer ends
// (instead of waiting for ever), and the cycles go on without answers for the SYNC watchdog to
// count.
TEST(DriveLink, ADriveTakenOutOfOperationalIsNoLongerAwaitedInLockstep) {
  Link l;
  const auto give_up_at = std::chrono::steady_clock::now() + 20s;
  const auto abandon = [&] { return std::chrono::steady_clock::now() > give_up_at; };
  std::int64_t time = 0;
  run_enabled(l, abandon, time);
  l.bus.inject(canopen::encode_nmt(canopen::NmtCommand::stop, 3), false);
  for (int cycle = 0; cycle < 20; ++cycle) {
    ASSERT_EQ(l.link.write(time, kPeriodNs), DriveStatus::ok) << "waited until given up";
    time += kPeriodNs;
    ASSERT_EQ(l.link.read(time, kPeriodNs), DriveStatus::ok);
  }
  EXPECT_FALSE(l.link.state().fresh) << "a stopped drive answers nothing";
}

// Issue 25: the SYNC producer counts SYNC frames it did not send (for alarm 2011), and they do
// not hold its cycle back.
TEST(DriveLink, TheSyncProducerCountsSyncsOfAnotherProducer) {
  Link l;
  const auto give_up_at = std::chrono::steady_clock::now() + 20s;
  const auto abandon = [&] { return std::chrono::steady_clock::now() > give_up_at; };
  std::int64_t time = 0;
  run_enabled(l, abandon, time);
  EXPECT_EQ(l.link.state().foreign_syncs, 0U);
  for (int i = 0; i < 3; ++i) {
    l.bus.inject(canopen::encode_sync(static_cast<std::uint8_t>(100 + i)), true);
  }
  for (int cycle = 0; cycle < 5; ++cycle) {
    ASSERT_EQ(l.link.write(time, kPeriodNs), DriveStatus::ok);
    time += kPeriodNs;
    ASSERT_EQ(l.link.read(time, kPeriodNs), DriveStatus::ok);
  }
  EXPECT_EQ(l.link.state().foreign_syncs, 3U);
}

// Decision 128: in realtime the SYNC producer's timer follows the machine's start on this
// host's clock as the host's offset estimate is refined, by 1 % of the cycle a SYNC at most, and
// tells the latest SYNC it sent.
TEST(DriveLink, TheTimedSyncsFollowTheMachineStartByBoundedSteps) {
  Link l;
  canopen::NodeStartupConfig startup{3};
  startup.pdos = canopen::spindle_pdos();
  ASSERT_EQ(l.link.configure(startup, 5s), std::nullopt);
  constexpr std::int64_t kOffsetNs = 1'000'000;
  const std::int64_t start = clock::monotonic_ns() + 10'000'000;
  axisnode::DriveActivation activation;
  activation.sync_timer = canopen::SyncSchedule(start, kPeriodNs, kOffsetNs);
  l.link.activate(activation);
  // How far each SYNC sent is from the schedule it started with.
  std::map<std::uint64_t, std::int64_t> moved;
  const auto watch_until = [&](std::size_t syncs) {
    const auto give_up = std::chrono::steady_clock::now() + 20s;
    while (moved.size() < syncs && std::chrono::steady_clock::now() < give_up) {
      axisnode::SentSync s;
      if (l.link.latest_sync(s)) {
        moved[s.index] =
            s.due_ns - (start + static_cast<std::int64_t>(s.index) * kPeriodNs + kOffsetNs);
        EXPECT_GE(s.late_ns, 0) << s.index;
      }
      std::this_thread::sleep_for(200us);
    }
  };
  watch_until(3);
  l.link.follow_machine_start(start + 70'000);  // the estimate moved 70 us
  watch_until(20);
  l.link.deactivate(canopen::DriveCommand{});
  ASSERT_GE(moved.size(), 20U);
  std::int64_t before = 0;
  std::uint64_t before_index = moved.begin()->first;
  for (const auto& [index, shift] : moved) {
    EXPECT_GE(shift, before) << "SYNC " << index << ": the start only moves toward the estimate";
    // A SYNC the watch did not see in between moved it too.
    EXPECT_LE(shift - before,
              20'000 * static_cast<std::int64_t>(std::max<std::uint64_t>(1, index - before_index)))
        << "SYNC " << index << ": 1 % of 2 ms a SYNC at most";
    before = shift;
    before_index = index;
  }
  EXPECT_EQ(before, 70'000) << "the SYNCs reach the new start and stay on it";
}
