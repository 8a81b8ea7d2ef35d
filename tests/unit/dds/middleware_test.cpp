// Fast DDS and Cyclone DDS on one wire: a sample written by a participant of either is read by a
// participant of the other with every field as written, routed topics stay in their partitions
// (Cyclone DDS 0.10's shared memory ignores them: the reader does not), and a Cyclone DDS
// participant without a RouDi is an error, never a hang. Needs the host's RouDi (the ctest
// fixture `roudi` starts one).
#include "idl/dds_participant.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace {

using mcnc::dds::Keys;
using mcnc::dds::Middleware;
using mcnc::dds::Participant;

constexpr int kDomain = 229;

// ctest runs each instance of a parameterised test as a test of its own, in parallel: each
// (middlewares, test) pair gets a domain of its own, 210-217, or one instance would hear
// another's writer (and its transient-local history).
int domain_of(const std::pair<Middleware, Middleware>& ways, int test) {
  const int ways_index = 2 * static_cast<int>(ways.first) + static_cast<int>(ways.second);
  return 210 + 2 * ways_index + test;
}
constexpr auto kWait = std::chrono::seconds(20);

template <class T>
struct Inbox {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<T> samples;

  void put(const T& sample) {
    std::lock_guard<std::mutex> lock(mutex);
    samples.push_back(sample);
    changed.notify_all();
  }
  bool wait_for(std::size_t count) {
    std::unique_lock<std::mutex> lock(mutex);
    return changed.wait_for(lock, kWait, [&] { return samples.size() >= count; });
  }
  std::size_t size() {
    std::lock_guard<std::mutex> lock(mutex);
    return samples.size();
  }
};

template <class W, class R>
bool wait_matched(const W& writer, const R& reader) {
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (std::chrono::steady_clock::now() < deadline) {
    if (writer.matched_readers() > 0 && reader.matched_writers() > 0) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

mcnc::AxisSetpoint setpoint(std::uint64_t cycle) {
  mcnc::AxisSetpoint sp;
  sp.axis(3);
  sp.channel(2);
  sp.cycle(cycle);
  sp.event_seq(77);
  sp.pos(-12.345678901234);
  sp.vel(1.5e3);
  sp.acc(-2.25);
  sp.valid(true);
  sp.mode(mcnc::SP_VELOCITY);
  sp.probe(3);  // G160's torque skip, with its limit and deviation
  sp.torque_limit(50.0);
  sp.skip_deviation(2.25);
  sp.torque_mode(true);  // G10 L14 P10's torque and speed limit
  sp.torque(-35.5);
  sp.torque_speed(300.0);
  return sp;
}

void expect_same(const mcnc::AxisSetpoint& got, const mcnc::AxisSetpoint& sent) {
  EXPECT_EQ(got.axis(), sent.axis());
  EXPECT_EQ(got.channel(), sent.channel());
  EXPECT_EQ(got.cycle(), sent.cycle());
  EXPECT_EQ(got.event_seq(), sent.event_seq());
  EXPECT_EQ(got.pos(), sent.pos());
  EXPECT_EQ(got.vel(), sent.vel());
  EXPECT_EQ(got.acc(), sent.acc());
  EXPECT_EQ(got.valid(), sent.valid());
  EXPECT_EQ(got.mode(), sent.mode());
  EXPECT_EQ(got.probe(), sent.probe());
  EXPECT_EQ(got.torque_limit(), sent.torque_limit());
  EXPECT_EQ(got.skip_deviation(), sent.skip_deviation());
  EXPECT_EQ(got.torque_mode(), sent.torque_mode());
  EXPECT_EQ(got.torque(), sent.torque());
  EXPECT_EQ(got.torque_speed(), sent.torque_speed());
}

class Middlewares : public ::testing::TestWithParam<std::pair<Middleware, Middleware>> {};

TEST_P(Middlewares, ACyclicSampleCrossesWithEveryField) {
  const auto [from, to] = GetParam();
  Participant writing(domain_of(GetParam(), 0), "writing", mcnc::dds::CyclicClock::lockstep, from);
  Participant reading(domain_of(GetParam(), 0), "reading", mcnc::dds::CyclicClock::lockstep, to);
  Inbox<mcnc::AxisSetpoint> inbox;
  mcnc::dds::Reader<mcnc::AxisSetpoint> reader(
      reading, Keys::of({"X1"}),
      [&](const mcnc::AxisSetpoint& sp, const mcnc::dds::WriterId&) { inbox.put(sp); });
  mcnc::dds::Writer<mcnc::AxisSetpoint> writer(writing, "X1");
  ASSERT_TRUE(wait_matched(writer, reader));
  for (std::uint64_t cycle = 1; cycle <= 5; ++cycle) {
    ASSERT_TRUE(writer.write(setpoint(cycle)));
    ASSERT_TRUE(inbox.wait_for(cycle));
  }
  for (std::uint64_t cycle = 1; cycle <= 5; ++cycle) {
    expect_same(inbox.samples[cycle - 1], setpoint(cycle));
  }
}

TEST_P(Middlewares, AnEventWithTextCrossesWithEveryField) {
  const auto [from, to] = GetParam();
  Participant writing(domain_of(GetParam(), 1), "writing", mcnc::dds::CyclicClock::lockstep, from);
  Participant reading(domain_of(GetParam(), 1), "reading", mcnc::dds::CyclicClock::lockstep, to);
  Inbox<mcnc::Alarm> inbox;
  mcnc::dds::Reader<mcnc::Alarm> reader(
      reading, [&](const mcnc::Alarm& a, const mcnc::dds::WriterId&) { inbox.put(a); });
  mcnc::dds::Writer<mcnc::Alarm> writer(writing);
  ASSERT_TRUE(wait_matched(writer, reader));
  mcnc::Alarm alarm;
  alarm.src("CH1");
  alarm.seq(9);
  alarm.number(2006);
  alarm.text(std::string(150, 'x') + " CH1 N120: the feedback of X1 is late");
  alarm.cycle(123456789012ULL);
  ASSERT_TRUE(writer.write(alarm));
  ASSERT_TRUE(inbox.wait_for(1));
  EXPECT_EQ(inbox.samples[0].src(), "CH1");
  EXPECT_EQ(inbox.samples[0].seq(), 9U);
  EXPECT_EQ(inbox.samples[0].number(), 2006U);
  EXPECT_EQ(inbox.samples[0].text(), alarm.text());
  EXPECT_EQ(inbox.samples[0].cycle(), 123456789012ULL);
}

INSTANTIATE_TEST_SUITE_P(BothWays, Middlewares,
                         ::testing::Values(std::pair{Middleware::cyclonedds,
                                                     Middleware::cyclonedds},
                                           std::pair{Middleware::cyclonedds, Middleware::fastdds},
                                           std::pair{Middleware::fastdds, Middleware::cyclonedds}),
                         [](const auto& info) {
                           return std::string(mcnc::dds::middleware_name(info.param.first)) +
                                  "_to_" + mcnc::dds::middleware_name(info.param.second);
                         });

// Two Cyclone DDS participants on `domain`: one writes the setpoints of X1 and Z1, the other
// reads each into an inbox of its own. Both writers and readers are matched once made.
struct TwoRoutedKeys {
  explicit TwoRoutedKeys(int domain)
      : writing(domain, "writing", mcnc::dds::CyclicClock::lockstep, Middleware::cyclonedds),
        reading(domain, "reading", mcnc::dds::CyclicClock::lockstep, Middleware::cyclonedds),
        x1_reader(reading, Keys::of({"X1"}),
                  [this](const mcnc::AxisSetpoint& sp, const mcnc::dds::WriterId&) { x1.put(sp); }),
        z1_reader(reading, Keys::of({"Z1"}),
                  [this](const mcnc::AxisSetpoint& sp, const mcnc::dds::WriterId&) { z1.put(sp); }),
        to_x1(writing, "X1"),
        to_z1(writing, "Z1") {}
  [[nodiscard]] bool matched() const {
    return wait_matched(to_x1, x1_reader) && wait_matched(to_z1, z1_reader);
  }

  Participant writing;
  Participant reading;
  Inbox<mcnc::AxisSetpoint> x1;
  Inbox<mcnc::AxisSetpoint> z1;
  mcnc::dds::Reader<mcnc::AxisSetpoint> x1_reader;
  mcnc::dds::Reader<mcnc::AxisSetpoint> z1_reader;
  mcnc::dds::Writer<mcnc::AxisSetpoint> to_x1;
  mcnc::dds::Writer<mcnc::AxisSetpoint> to_z1;
};

// Over shared memory Cyclone DDS 0.10 matches by topic: with a topic per key, a reader of X1's
// setpoints never receives Z1's (and, were a chunk of another writer ever handed to it, the
// reader keeps only the samples of the writers it matched, as over RTPS).
TEST(CycloneDds, ARoutedReaderNeverHearsAnotherKey) {
  TwoRoutedKeys keys(kDomain + 2);
  auto [x1, z1, to_x1, to_z1] = std::tie(keys.x1, keys.z1, keys.to_x1, keys.to_z1);
  ASSERT_TRUE(keys.matched());
  EXPECT_EQ(to_x1.matched_readers(), 1);
  // One sample a cycle, each awaited, as a lockstep consumer takes them.
  for (std::uint64_t cycle = 1; cycle <= 20; ++cycle) {
    ASSERT_TRUE(to_x1.write(setpoint(cycle)));
    ASSERT_TRUE(x1.wait_for(cycle));
  }
  ASSERT_TRUE(to_z1.write(setpoint(1000)));
  ASSERT_TRUE(z1.wait_for(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(x1.size(), 20U);
  ASSERT_EQ(z1.size(), 1U);
  EXPECT_EQ(z1.samples[0].cycle(), 1000U);
}

// A lockstep process that waits announces its latest cyclic samples again (decision 98): each
// cyclic writer writes its last sample once more, so a reader that lost it learns of it. A
// writer that wrote nothing and the state and event topics send nothing.
TEST(CycloneDds, AnnouncingTheLatestCyclicSamplesWritesEachOnceMoreAndNothingElse) {
  TwoRoutedKeys keys(kDomain + 1);  // Z1's writer writes nothing
  auto [x1, z1, to_x1, writing] = std::tie(keys.x1, keys.z1, keys.to_x1, keys.writing);
  Inbox<mcnc::RunControl> run;
  mcnc::dds::Reader<mcnc::RunControl> run_reader(
      keys.reading, [&](const mcnc::RunControl& rc, const mcnc::dds::WriterId&) { run.put(rc); });
  mcnc::dds::Writer<mcnc::RunControl> run_writer(writing);
  ASSERT_TRUE(keys.matched());
  ASSERT_TRUE(wait_matched(run_writer, run_reader));
  ASSERT_TRUE(to_x1.write(setpoint(41)));
  ASSERT_TRUE(to_x1.write(setpoint(42)));
  mcnc::RunControl rc;
  rc.generation(5);
  ASSERT_TRUE(run_writer.write(rc));
  ASSERT_TRUE(x1.wait_for(2));
  ASSERT_TRUE(run.wait_for(1));

  writing.announce_latest_cyclic();
  ASSERT_TRUE(x1.wait_for(3));
  writing.announce_latest_cyclic();
  ASSERT_TRUE(x1.wait_for(4));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  std::lock_guard<std::mutex> lock(x1.mutex);
  ASSERT_EQ(x1.samples.size(), 4U);
  EXPECT_EQ(x1.samples[2].cycle(), 42U);  // the latest, as written
  EXPECT_EQ(x1.samples[3].cycle(), 42U);
  EXPECT_EQ(x1.samples[3].pos(), -12.345678901234);
  EXPECT_EQ(z1.size(), 0U);
  EXPECT_EQ(run.size(), 1U);
}

TEST(CycloneDds, TheMiddlewareIsNamedByMcncMiddleware) {
  EXPECT_EQ(mcnc::dds::parse_middleware("cyclonedds"), Middleware::cyclonedds);
  EXPECT_EQ(mcnc::dds::parse_middleware("fastdds"), Middleware::fastdds);
  EXPECT_FALSE(mcnc::dds::parse_middleware("opendds").has_value());
  EXPECT_FALSE(mcnc::dds::parse_middleware("").has_value());
}

}  // namespace
