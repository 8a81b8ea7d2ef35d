// ChannelPeers (channel/wire), the adapter between DDS and the controller for what a channel
// hears from the others, over real DDS participants: CH1's adapter, and a participant of the
// test that writes CH2's status and events as CH2's process would (each test on a DDS domain
// of its own, over the network transport: no RouDi). What it must do (channel_peers.hpp): hold
// the lockstep gate until the peer's status stamped N-1 and the events it announces are in,
// hand an event to the controller in the first cycle after the one it was sent in, and tell
// the controller when the peer's process is gone.
#include "channel/wire/channel_peers.hpp"
#include "channel_rig.hpp"
#include "common/config/machine_config.hpp"
#include "support/eventually.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

namespace mcnc::channel {
namespace {

using namespace std::chrono_literals;
using test::eventually;

constexpr auto kWait = 20s;

// CH2 as its process is seen on the wire: a status every cycle, numbered events.
class PeerOnTheWire {
 public:
  explicit PeerOnTheWire(int domain)
      : participant_(domain, "CH2", dds::CyclicClock::lockstep, dds::Middleware::cyclonedds,
                     dds::LocalTransport::network),
        status_(participant_, "CH2"),
        events_(participant_) {}

  void status(std::uint64_t cycle, ::mcnc::ChannelState state = CH_RUNNING) {
    ::mcnc::ChannelStatus s;
    s.channel(2);
    s.cycle(cycle);
    s.event_seq(seq_);
    s.state(state);
    status_.write(s);
  }
  // A G04.1 arrival at mark `p` with CH1, sent in `cycle`; its number is announced by the
  // statuses written after it.
  void arrival(std::uint64_t cycle, int p) {
    ::mcnc::CoordinationEvent e;
    e.channel(2);
    e.seq(++seq_);
    e.cycle(cycle);
    e.kind(COORD_SYNC_ARRIVE);
    e.p(p);
    e.generation(1);
    e.channels(0b11);
    events_.write(e);
  }
  // The next event's number is announced without the event being written (it is on its way).
  void announce_unsent_event() { ++seq_; }
  [[nodiscard]] bool matched() const {
    return status_.matched_readers() > 0 && events_.matched_readers() > 0;
  }

 private:
  dds::Participant participant_;
  dds::Writer<::mcnc::ChannelStatus> status_;
  dds::Writer<::mcnc::CoordinationEvent> events_;
  std::uint64_t seq_ = 0;
};

// CH1 of the mill-turn machine (two channels): its controller (program `program`) on standing axes
// that follow, and its ChannelPeers on `domain`.
class PeersRig : public ChannelRig {
 public:
  PeersRig(int domain, const std::string& program)
      : ChannelRig(config(), alike_axes(2, 0.002), xz_spindle_setup(0.002)),
        machine_(config::load_machine_file(std::string(MCNC_SOURCE_DIR) +
                                           "/launch/machines/mill_turn.yaml")),
        node_(domain, "CH1", dds::CyclicClock::lockstep, dds::Middleware::cyclonedds,
              dds::LocalTransport::network),
        gate_(machine_.channels.size() - 1),
        read_ahead_(nullptr, nullptr),
        peers_(node_, machine_, machine_.channels[0], gate_, 0, read_ahead_),
        feedback_(standing_feedback(3, 1)) {
    load(program);
  }

  const CycleOutput& step() override {
    ++cycle_;
    peers_.apply(cycle_, true, ctl());
    const CycleOutput& out = channel_cycle(cycle_, feedback_);
    follow_setpoints(out, feedback_, 2);
    for (std::size_t e = 0; e < out.event_count; ++e) {
      if (out.events[e].kind == ChannelEventKind::sync_release && !released_) {
        released_ = cycle_;
      }
    }
    last_state_ = out.state;
    return out;
  }

  static interp::InterpreterConfig config() {
    interp::InterpreterConfig c;
    c.channel = 1;
    c.channel_count = 2;
    return c;
  }

  config::MachineConfig machine_;
  process::ProcessNode node_;
  cycle::LockstepGate gate_;
  ReadAhead read_ahead_;
  ChannelPeers peers_;
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 0;
  std::optional<std::uint64_t> released_;
  ChannelState last_state_ = ChannelState::reset;
};

constexpr std::size_t kCh2 = 0;  // CH2's gate input: the first other channel

TEST(ChannelPeers, TheGateWaitsForThePeersStatusAndForTheEventsItAnnounces) {
  PeersRig ch1(146, "M30\n");
  PeerOnTheWire ch2(146);
  ASSERT_TRUE(eventually([&] { return ch1.peers_.discovered() && ch2.matched(); }, kWait, 5ms));
  EXPECT_FALSE(ch1.gate_.may_run(1));
  ch2.status(0);
  ASSERT_TRUE(eventually([&] { return ch1.gate_.may_run(1); }, kWait, 5ms))
      << "CH2's status 0 is in";
  EXPECT_FALSE(ch1.gate_.may_run(2));

  // Status 1 announces an event that has not come: cycle 2 waits for it, however long.
  ch2.announce_unsent_event();
  ch2.status(1);
  ASSERT_TRUE(eventually(
      [&] { return ch1.gate_.events_received(kCh2) == 0 && ch1.gate_.first_missing(2) == kCh2; },
      kWait, 5ms));
  std::this_thread::sleep_for(300ms);
  EXPECT_FALSE(ch1.gate_.may_run(2)) << "a status without the event it announces";
}

TEST(ChannelPeers, AnArrivalReachesTheControllerInTheCycleAfterTheOneItWasSentIn) {
  PeersRig ch1(218, "G04.1 P1 Q12\nG01 X10 F300\nM30\n");
  PeerOnTheWire ch2(218);
  ASSERT_TRUE(eventually([&] { return ch1.peers_.discovered() && ch2.matched(); }, kWait, 5ms));
  ch1.ctl().request_start();
  ASSERT_TRUE(
      ch1.run_until([](const CycleOutput& o) { return o.state == ChannelState::waiting; }, 2000));
  // CH2 arrives in its cycle `sent`, a few cycles ahead of CH1's.
  const std::uint64_t sent = ch1.cycle_ + 5;
  ch2.arrival(sent, 1);
  ch2.status(sent);
  ASSERT_TRUE(eventually([&] { return ch1.gate_.events_received(kCh2) == 1; }, kWait, 5ms));
  while (ch1.cycle_ < sent) {
    ch1.step();
    ASSERT_EQ(ch1.last_state_, ChannelState::waiting) << "cycle " << ch1.cycle_;
  }
  ch1.step();
  ASSERT_TRUE(ch1.released_.has_value());
  EXPECT_EQ(*ch1.released_, sent + 1);
  EXPECT_TRUE(ch1.run_to_end());
}

TEST(ChannelPeers, APeerWhoseProcessIsGoneIsLostToTheControllerWaitingForIt) {
  PeersRig ch1(219, "G04.1 P1 Q12\nM30\n");
  auto ch2 = std::make_unique<PeerOnTheWire>(219);
  ASSERT_TRUE(eventually([&] { return ch1.peers_.discovered() && ch2->matched(); }, kWait, 5ms));
  ch2->status(0);
  ASSERT_TRUE(eventually([&] { return ch1.gate_.may_run(1) || ch1.gate_.first_missing(1) != kCh2; },
                         kWait, 5ms));
  ch1.ctl().request_start();
  ASSERT_TRUE(
      ch1.run_until([](const CycleOutput& o) { return o.state == ChannelState::waiting; }, 2000));
  ch2.reset();  // CH2's process ends: its writers leave
  ASSERT_TRUE(eventually(
      [&] {
        ch1.step();
        return ch1.last_state_ == ChannelState::alarm;
      },
      kWait, 5ms));
  EXPECT_EQ(ch1.ctl().last_alarm().number, kAlarmSyncPartnerLost);
  EXPECT_TRUE(ch1.gate_.may_run(ch1.cycle_ + 5)) << "a lost peer no longer holds the gate";
  EXPECT_FALSE(ch1.released_.has_value());
}

}  // namespace
}  // namespace mcnc::channel
