// The axis node's cycle never allocates: the core (inputs, ownership, coupling, controller) and
// its drive link (read, write), as axisnode/main.cpp runs them each cycle, against the drive
// simulator on an in-memory bus, in lockstep. Allocations are counted on the cycle's thread
// only, while it runs the cycle; the setpoints and events that DDS callbacks would hand over
// arrive between cycles, uncounted, as they would on other threads.
#include "support/allocation_counter.hpp"
#include "simulated_bus.hpp"

#include "axisnode/link/core_exchange.hpp"
#include "axisnode/link/drive_link.hpp"
#include "axisnode/node/axis_node.hpp"
#include "canopen/cia402/drive_pdos.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

using namespace mcnc;
using namespace std::chrono_literals;

namespace {

constexpr double kCycle = 0.001;
constexpr std::int64_t kPeriodNs = 1'000'000;

axisnode::AxisNode::WriterId writer(std::uint8_t n) {
  axisnode::AxisNode::WriterId w{};
  w[0] = n;
  return w;
}

axisnode::SetpointSample at(std::uint64_t cycle, double pos, bool valid = true) {
  return axisnode::SetpointSample{cycle, pos, 0.0, 0.0, valid, false};
}

axisnode::AxisNodeEvent request(std::uint32_t channel, std::uint64_t seq, std::uint64_t cycle,
                                ownership::OwnershipRequestKind kind) {
  axisnode::AxisNodeEvent e;
  e.kind = axisnode::AxisNodeEvent::Kind::axis_request;
  e.channel = channel;
  e.seq = seq;
  e.cycle = cycle;
  e.axis = 1;
  e.request = kind;
  return e;
}

// An axis of channel 1 that channel 2 may take (G141), its drive on node 1.
axisnode::AxisNodeRoles exchanged_axis() {
  axisnode::AxisNodeRoles r;
  r.axis = 1;
  r.home = 1;
  r.candidates = {1, 2};
  r.exchangeable = true;
  r.in_position = 0.01;
  r.cycle_s = kCycle;
  r.controller = axisnode::AxisNodeSetup{10000.0, kCycle, 5};
  return r;
}

// One cycle as axisnode/main.cpp runs it: inputs, the drive's state, the core's step, the
// command out (and in lockstep the drive's answer to it).
struct CycleStatus {
  axisnode::DriveStatus read = axisnode::DriveStatus::ok;
  axisnode::DriveStatus write = axisnode::DriveStatus::ok;
};
CycleStatus run_cycle(std::uint64_t cycle, axisnode::AxisNode& core,
                      axisnode::DriveInterface& link) noexcept {
  CycleStatus status;
  core.take_inputs(cycle, true);
  const auto time = static_cast<std::int64_t>(cycle) * kPeriodNs;
  status.read = link.read(time, kPeriodNs);
  const axisnode::DriveSample& state = link.state();
  const axisnode::AxisNodeOutput& out = core.step(cycle, axisnode::readings_of(state), false);
  link.command() = axisnode::command_of(out);
  status.write = link.write(time, kPeriodNs);
  return status;
}

// The drive of node 1 on a simulated bus, its link configured and active in lockstep, and the
// cycle run with its allocations counted.
struct CountedNode {
  test::SimulatedBus bus;
  process::Wakeup wake;
  axisnode::DriveLink link;
  std::uint64_t allocations = 0;

  CountedNode(double start, std::uint16_t heartbeat_ms,
              std::pair<std::unique_ptr<test::MemoryCanBus>, std::unique_ptr<test::MemoryCanBus>>
                  ends = test::MemoryCanBus::pair())
      : bus(std::move(ends.second), drivesim::DriveParams{1, 10000.0, 0.004, 500.0, 5000.0, start},
            kCycle),
        link(std::move(ends.first), 1, true, {}, wake) {
    canopen::NodeStartupConfig startup;
    startup.node = 1;
    startup.heartbeat_ms = heartbeat_ms;
    if (const auto error = link.configure(startup, 5s)) {
      ADD_FAILURE() << *error;
    }
    axisnode::DriveActivation activation;
    activation.lockstep = true;
    link.activate(activation);
  }

  CycleStatus cycle(std::uint64_t c, axisnode::AxisNode& core) {
    const std::uint64_t before = test::allocations();
    CycleStatus status;
    {
      test::CountAllocations counting;
      status = run_cycle(c, core, link);
    }
    allocations += test::allocations() - before;
    return status;
  }
};

}  // namespace

TEST(AllocationCounter, CountsOnlyTheThreadThatAsks) {
  std::atomic<bool> go{false};
  std::atomic<bool> done{false};
  std::thread other([&] {
    while (!go) {
      std::this_thread::yield();
    }
    ::operator delete(::operator new(16));
    done = true;
  });
  const std::uint64_t before = test::allocations();
  ::operator delete(::operator new(16));  // called directly: a new-expression may be elided
  EXPECT_EQ(test::allocations(), before) << "this thread does not count yet";
  {
    test::CountAllocations counting;
    std::vector<int> grown(64);  // as a container allocates
    go = true;                   // the other thread allocates while this one counts
    while (!done) {
      std::this_thread::yield();
    }
    EXPECT_EQ(test::allocations(), before + 1);
    EXPECT_EQ(grown.size(), 64U);
  }
  other.join();
}

TEST(AxisNodeCycle, NeverAllocatesOverThousandsOfCyclesWithAnOwnershipChange) {
  CountedNode n(5.0, 10);  // heartbeats every 10 ms keep arriving during the run
  ASSERT_EQ(n.link.lifecycle(), axisnode::DriveLifecycle::active);
  axisnode::AxisNode core(exchanged_axis());
  constexpr std::uint64_t kCycles = 4000;
  std::uint64_t seq1 = 0;
  std::uint64_t seq2 = 0;
  for (std::uint64_t c = 0; c < kCycles; ++c) {
    ASSERT_TRUE(core.ready(c)) << c;
    const CycleStatus status = n.cycle(c, core);
    ASSERT_EQ(status.read, axisnode::DriveStatus::ok) << c;
    ASSERT_EQ(status.write, axisnode::DriveStatus::ok) << c;
    // Channel 1 holds the axis at 5, moves it to 5.5 and releases it (G140) at 2000; channel 2
    // takes it (G141) at 2001 and moves it to 4.
    if (c == 2000) {
      core.on_event(request(1, ++seq1, c, ownership::OwnershipRequestKind::release));
    }
    if (c == 2001) {
      core.on_event(request(2, ++seq2, c, ownership::OwnershipRequestKind::acquire));
    }
    const double one = 5.0 + 0.5 * std::min(1.0, static_cast<double>(c) / 1000.0);
    const double two =
        5.5 - 1.5 * std::min(1.0, static_cast<double>(c > 2100 ? c - 2100 : 0) / 1000.0);
    core.on_setpoint(1, 1, at(c, one, c < 2000), seq1, writer(1));
    core.on_setpoint(2, 1, at(c, two, c > 2001), seq2, writer(2));
  }
  EXPECT_EQ(n.allocations, 0U) << "the cycle allocated";
  // What the cycle did: the drive followed channel 1, then channel 2, over the bus.
  EXPECT_EQ(core.standing().owner, 2U);
  EXPECT_NEAR(core.output().cmd, 4.0, 1e-9);
  EXPECT_NEAR(n.link.state().feedback.position_actual / 10000.0, 4.0, 0.01);
  EXPECT_GE(n.link.state().answers, kCycles - 2);
  EXPECT_GT(n.link.state().heartbeats, 100U);
  n.link.deactivate(canopen::DriveCommand{});
  EXPECT_EQ(n.link.lifecycle(), axisnode::DriveLifecycle::inactive);
}

TEST(AxisNodeCycle, NeverAllocatesThroughAnAxisCouplingOnAndOff) {
  CountedNode n(3.0, 100);
  // Axis 2 of channel 1, which may follow axis 1 (G51.4).
  axisnode::AxisNodeRoles roles = exchanged_axis();
  roles.axis = 2;
  roles.candidates = {1};
  roles.exchangeable = false;
  roles.may_follow = true;
  roles.leaders = {1};
  axisnode::AxisNode core(roles);
  constexpr std::uint64_t kCycles = 4000;
  std::uint64_t seq = 0;
  std::uint64_t coupled_at = 0;
  std::uint64_t decoupled_at = 0;
  double while_coupled = 0.0;
  for (std::uint64_t c = 0; c < kCycles; ++c) {
    ASSERT_TRUE(core.ready(c)) << c;
    const CycleStatus status = n.cycle(c, core);
    ASSERT_EQ(status.write, axisnode::DriveStatus::ok) << c;
    while_coupled = c == 2900 ? core.output().cmd : while_coupled;
    for (std::size_t i = 0; i < core.happening_count(); ++i) {
      const auto kind = core.happenings()[i].kind;
      coupled_at = kind == axisnode::AxisNodeHappening::Kind::axis_coupled ? c : coupled_at;
      decoupled_at = kind == axisnode::AxisNodeHappening::Kind::axis_decoupled ? c : decoupled_at;
    }
    // Channel 1 couples the axis to axis 1 at 1000 (G51.4) and releases it at 3000 (G50.4);
    // axis 1 moves from 10 to 11 between 1500 and 2500.
    if (c == 1000 || c == 3000) {
      axisnode::AxisNodeEvent e;
      e.kind = axisnode::AxisNodeEvent::Kind::axis_sync;
      e.channel = 1;
      e.seq = ++seq;
      e.cycle = c;
      e.axis = 2;
      e.sync_on = c == 1000;
      e.sync_master = 1;
      core.on_event(e);
    }
    const double master = 10.0 + std::clamp(static_cast<double>(c) - 1500.0, 0.0, 1000.0) / 1000.0;
    core.on_leader_feedback(1, c, master, true, writer(7));
    const bool own = c < 1000 || c >= 3000;
    core.on_setpoint(1, 2, at(c, c < 1000 ? 3.0 : 4.0, own), seq, writer(1));
  }
  EXPECT_EQ(n.allocations, 0U) << "the cycle allocated";
  EXPECT_GT(coupled_at, 1000U);
  EXPECT_GT(decoupled_at, 3000U);
  EXPECT_NEAR(while_coupled, 4.0, 1e-9) << "moved with its master by 1";
  EXPECT_NEAR(core.output().cmd, 4.0, 1e-9) << "then its own setpoints again";
  EXPECT_NEAR(n.link.state().feedback.position_actual / 10000.0, 4.0, 0.01);
}
