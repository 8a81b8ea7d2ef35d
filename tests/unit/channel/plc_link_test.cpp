// PlcLink (channel/wire), the adapter between DDS and the controller for the PLC node, over
// real DDS participants: a participant of the test writes the PLC's status and its answers
// (AuxAck) as the PLC node would (each test on a DDS domain of its own, network transport).
// What it must do (plc_link.hpp): hold the lockstep gate until the PLC's status stamped N-1 and
// the answers it announces are in, hand this channel's answers (and only this channel's) to
// the controller from the cycle after the one they were sent in, and tell it when the PLC is
// gone.
#include "channel/wire/plc_link.hpp"
#include "channel_rig.hpp"
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

// The PLC node as it is seen on the wire.
class PlcOnTheWire {
 public:
  explicit PlcOnTheWire(int domain)
      : participant_(domain, "plc", dds::CyclicClock::lockstep, dds::Middleware::cyclonedds,
                     dds::LocalTransport::network),
        status_(participant_),
        acks_(participant_) {}

  void status(std::uint64_t cycle) {
    ::mcnc::PlcStatus s;
    s.cycle(cycle);
    s.event_seq(seq_);
    status_.write(s);
  }
  void answer(std::uint64_t cycle, std::uint32_t channel, std::uint64_t aux_id,
              ::mcnc::AuxOutcome outcome, const std::string& reason = {}) {
    ::mcnc::AuxAck a;
    a.seq(++seq_);
    a.cycle(cycle);
    a.channel(channel);
    a.aux_id(aux_id);
    a.outcome(outcome);
    a.reason(reason);
    acks_.write(a);
  }
  [[nodiscard]] bool matched() const {
    return status_.matched_readers() > 0 && acks_.matched_readers() > 0;
  }

 private:
  dds::Participant participant_;
  dds::Writer<::mcnc::PlcStatus> status_;
  dds::Writer<::mcnc::AuxAck> acks_;
  std::uint64_t seq_ = 0;
};

// Channel 1 with a PLC: its controller on standing axes that follow, and its PlcLink.
class PlcRig : public ChannelRig {
 public:
  PlcRig(int domain, const std::string& program)
      : ChannelRig(config(), alike_axes(2, 0.002), setup()),
        node_(domain, "CH1", dds::CyclicClock::lockstep, dds::Middleware::cyclonedds,
              dds::LocalTransport::network),
        gate_(1),
        link_(node_, gate_, 0, 1),
        feedback_(standing_feedback(3, 1)) {
    load(program);
  }

  const CycleOutput& step() override {
    ++cycle_;
    link_.apply(cycle_, true, ctl());
    const CycleOutput& out = channel_cycle(cycle_, feedback_);
    follow_setpoints(out, feedback_, 2);
    if (out.aux_due) {
      aux_id_ = out.aux.id;
    }
    for (std::size_t e = 0; e < out.event_count; ++e) {
      if (out.events[e].kind == ChannelEventKind::block_started && out.events[e].line == 2 &&
          !second_block_) {
        second_block_ = cycle_;
      }
    }
    last_state_ = out.state;
    return out;
  }

  static interp::InterpreterConfig config() {
    interp::InterpreterConfig c;
    c.channel = 1;
    c.plc = true;
    return c;
  }
  static ChannelSetup setup() {
    ChannelSetup s = xz_spindle_setup(0.002);
    s.plc = true;
    return s;
  }

  process::ProcessNode node_;
  cycle::LockstepGate gate_;
  PlcLink link_;
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 0;
  std::uint64_t aux_id_ = 0;
  std::optional<std::uint64_t> second_block_;
  ChannelState last_state_ = ChannelState::reset;
};

// Runs `ch1` until its M08 is sent to the PLC.
void run_to_request(PlcRig& ch1) {
  ch1.ctl().request_start();
  ASSERT_TRUE(ch1.run_until([&](const CycleOutput&) { return ch1.aux_id_ != 0; }, 2000));
}

// Steps `ch1` until it is in alarm (what the PLC's answer, or its absence, brings about).
bool steps_into_an_alarm(PlcRig& ch1) {
  return eventually(
      [&] {
        ch1.step();
        return ch1.last_state_ == ChannelState::alarm;
      },
      kWait, 5ms);
}

TEST(PlcLink, TheGateWaitsForThePlcStatusAndForTheAnswersItAnnounces) {
  PlcRig ch1(220, "M30\n");
  PlcOnTheWire plc(220);
  ASSERT_TRUE(eventually([&] { return ch1.link_.discovered() && plc.matched(); }, kWait, 5ms));
  EXPECT_FALSE(ch1.gate_.may_run(1));
  plc.status(0);
  ASSERT_TRUE(eventually([&] { return ch1.gate_.may_run(1); }, kWait, 5ms));
  plc.answer(0, 2, 7, AUX_DONE);  // an answer to another channel still counts for the gate
  plc.status(1);
  ASSERT_TRUE(eventually([&] { return ch1.gate_.may_run(2); }, kWait, 5ms));
  EXPECT_EQ(ch1.gate_.events_received(0), 1U);
}

TEST(PlcLink, TheFinEndsTheBlockInTheCycleAfterItWasSentAndOnlyThisChannelsCounts) {
  PlcRig ch1(221, "M08\nG01 X5 F300\nM30\n");
  PlcOnTheWire plc(221);
  ASSERT_TRUE(eventually([&] { return ch1.link_.discovered() && plc.matched(); }, kWait, 5ms));
  run_to_request(ch1);
  const std::uint64_t sent = ch1.cycle_ + 5;
  plc.answer(sent - 1, 2, ch1.aux_id_, AUX_DONE);  // CH2's answer with this id: not ours
  plc.answer(sent, 1, ch1.aux_id_, AUX_DONE);
  ASSERT_TRUE(eventually([&] { return ch1.gate_.events_received(0) == 2; }, kWait, 5ms));
  while (ch1.cycle_ <= sent + 2 && !ch1.second_block_) {
    ch1.step();
  }
  ASSERT_TRUE(ch1.second_block_.has_value()) << "the FIN never ended M08";
  // The controller takes the FIN in cycle sent + 1, where M08 ends; the next block starts in
  // the cycle after.
  EXPECT_EQ(*ch1.second_block_, sent + 2);
  EXPECT_TRUE(ch1.run_to_end());
}

TEST(PlcLink, ARefusalIsAnAlarmWithThePlcsReasonAndAPlcThatIsGoneToo) {
  {
    PlcRig ch1(222, "M08\nG01 X5 F300\nM30\n");
    PlcOnTheWire plc(222);
    ASSERT_TRUE(eventually([&] { return ch1.link_.discovered() && plc.matched(); }, kWait, 5ms));
    run_to_request(ch1);
    plc.answer(ch1.cycle_, 1, ch1.aux_id_, AUX_REFUSED, "coolant pressure low");
    ASSERT_TRUE(steps_into_an_alarm(ch1));
    EXPECT_EQ(ch1.ctl().last_alarm().number, kAlarmAuxRefused);
    EXPECT_NE(std::string(ch1.ctl().last_alarm().text.data()).find("coolant pressure low"),
              std::string::npos)
        << ch1.ctl().last_alarm().text.data();
    EXPECT_FALSE(ch1.second_block_.has_value());
  }
  PlcRig ch1(223, "M08\nG01 X5 F300\nM30\n");
  auto plc = std::make_unique<PlcOnTheWire>(223);
  ASSERT_TRUE(eventually([&] { return ch1.link_.discovered() && plc->matched(); }, kWait, 5ms));
  plc->status(0);
  ASSERT_TRUE(eventually([&] { return ch1.gate_.may_run(1); }, kWait, 5ms));
  run_to_request(ch1);
  plc.reset();  // the PLC node's process ends
  ASSERT_TRUE(steps_into_an_alarm(ch1));
  EXPECT_EQ(ch1.ctl().last_alarm().number, kAlarmAuxRefused);
  EXPECT_NE(std::string(ch1.ctl().last_alarm().text.data()).find("PLC node is gone"),
            std::string::npos);
  EXPECT_FALSE(ch1.second_block_.has_value());
}

}  // namespace
}  // namespace mcnc::channel
