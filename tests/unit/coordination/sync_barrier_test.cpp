// G04.1 wait marks: each channel's SyncBarrier sees every arrival and decides its own wait.
// Channels are simulated here as scripts of marks and work, exchanging arrivals at once.
#include "channel/coordination/sync_barrier.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace mcnc::coordination {
namespace {

ChannelSet set_of(std::initializer_list<int> channels) {
  ChannelSet s;
  for (const int c : channels) {
    s.set(static_cast<std::size_t>(c));
  }
  return s;
}

// Channel `c`'s arrival at P in round `generation`, as another channel receives it.
SyncArrival arrival_of(std::uint32_t c, std::int32_t p, std::uint64_t generation,
                       const ChannelSet& participants, bool all = false) {
  SyncArrival a;
  a.channel = c;
  a.p = p;
  a.generation = generation;
  a.all_active = all;
  a.participants = participants;
  return a;
}

// N channels, each with its own barrier; every arrival goes to all of them.
class Machine {
 public:
  explicit Machine(int n) {
    for (int c = 1; c <= n; ++c) {
      barriers_.push_back(std::make_unique<SyncBarrier>(static_cast<std::uint32_t>(c)));
      active_.set(static_cast<std::size_t>(c));
    }
  }
  SyncBarrier& ch(int c) { return *barriers_[static_cast<std::size_t>(c - 1)]; }
  void arrive(int c, int p, ChannelSet s, bool all = false) {
    const SyncArrival a = ch(c).arrive(p, s, all);
    for (auto& b : barriers_) {
      b->on_arrival(a);
    }
  }
  SyncState state(int c) { return ch(c).evaluate(active_); }
  ChannelSet& active() { return active_; }

 private:
  std::vector<std::unique_ptr<SyncBarrier>> barriers_;
  ChannelSet active_;
};

TEST(SyncBarrier, WaitsForEveryParticipantThenReleasesAll) {
  Machine m(3);
  m.arrive(1, 1, set_of({1, 2, 3}));
  EXPECT_EQ(m.state(1), SyncState::waiting);
  EXPECT_EQ(m.ch(1).missing(), set_of({2, 3}));
  m.arrive(3, 1, set_of({1, 2, 3}));
  EXPECT_EQ(m.state(1), SyncState::waiting);
  EXPECT_EQ(m.state(3), SyncState::waiting);
  EXPECT_EQ(m.ch(3).missing(), set_of({2}));
  m.arrive(2, 1, set_of({1, 2, 3}));
  EXPECT_EQ(m.state(1), SyncState::released);
  EXPECT_EQ(m.state(2), SyncState::released);
  EXPECT_EQ(m.state(3), SyncState::released);
  EXPECT_EQ(m.state(1), SyncState::none);  // the wait is over
}

TEST(SyncBarrier, AFastChannelBackAtTheSameMarkWaitsForTheNextRound) {
  Machine m(2);
  m.arrive(1, 5, set_of({1, 2}));
  m.arrive(2, 5, set_of({1, 2}));
  ASSERT_EQ(m.state(1), SyncState::released);
  // CH1 loops back to P5 before CH2 even evaluated its release: round 2 must wait for CH2's
  // second arrival, not be satisfied by its first.
  m.arrive(1, 5, set_of({1, 2}));
  EXPECT_EQ(m.ch(1).current().generation, 2U);
  EXPECT_EQ(m.state(1), SyncState::waiting);
  EXPECT_EQ(m.state(2), SyncState::released);  // CH2's round 1 is still released
  m.arrive(2, 5, set_of({1, 2}));
  EXPECT_EQ(m.state(1), SyncState::released);
  EXPECT_EQ(m.state(2), SyncState::released);
}

TEST(SyncBarrier, AnArrivalOfAnOldRoundDeliveredLateChangesNothing) {
  Machine m(2);
  const SyncArrival old = arrival_of(2, 1, 1, set_of({1, 2}));
  m.arrive(2, 1, set_of({1, 2}));
  m.arrive(1, 1, set_of({1, 2}));
  ASSERT_EQ(m.state(1), SyncState::released);
  m.arrive(2, 1, set_of({1, 2}));  // round 2
  m.arrive(1, 1, set_of({1, 2}));
  m.ch(1).on_arrival(old);  // round 1 again, late
  EXPECT_EQ(m.state(1), SyncState::released);
}

TEST(SyncBarrier, DifferentParticipantsAtTheSameMarkAreAMismatchInBothChannels) {
  Machine m(3);
  m.arrive(1, 2, set_of({1, 2}));
  m.arrive(2, 2, set_of({1, 2, 3}));
  EXPECT_EQ(m.state(1), SyncState::mismatch);
  EXPECT_EQ(m.ch(1).conflict_channel(), 2U);
  EXPECT_EQ(m.state(2), SyncState::mismatch);
  EXPECT_EQ(m.ch(2).conflict_channel(), 1U);
}

TEST(SyncBarrier, MutualWaitsAtDifferentMarksAreADeadlockInBothChannels) {
  Machine m(2);
  m.arrive(1, 1, set_of({1, 2}));
  EXPECT_EQ(m.state(1), SyncState::waiting);  // CH2 may still come
  m.arrive(2, 2, set_of({1, 2}));
  EXPECT_EQ(m.state(1), SyncState::deadlock);
  EXPECT_EQ(m.ch(1).conflict_channel(), 2U);
  EXPECT_EQ(m.state(2), SyncState::deadlock);
}

// The first channel to see a conflict raises its alarm and leaves automatic operation; the
// other, deciding a cycle later, must still find it.
TEST(SyncBarrier, AConflictIsFoundAlsoAfterThePartnerStoppedWithItsAlarm) {
  Machine m(3);
  m.arrive(2, 2, set_of({1, 2, 3}));
  m.arrive(1, 2, set_of({1, 2}));
  EXPECT_EQ(m.state(1), SyncState::mismatch);
  m.active().reset(1);  // CH1 in alarm
  EXPECT_EQ(m.ch(2).evaluate(m.active(), set_of({1})), SyncState::mismatch);
  EXPECT_EQ(m.ch(2).conflict_channel(), 1U);

  Machine d(2);
  d.arrive(2, 2, set_of({1, 2}));
  d.arrive(1, 1, set_of({1, 2}));
  EXPECT_EQ(d.state(1), SyncState::deadlock);
  d.active().reset(1);
  EXPECT_EQ(d.ch(2).evaluate(d.active(), set_of({1})), SyncState::deadlock);
  // A partner reset out of its program (neither active nor halted) is no longer waiting: the
  // channel waits for it to come again.
  Machine r(2);
  r.arrive(2, 2, set_of({1, 2}));
  r.arrive(1, 1, set_of({1, 2}));
  r.active().reset(1);
  EXPECT_EQ(r.ch(2).evaluate(r.active(), ChannelSet{}), SyncState::waiting);
}

// The controller hands over the other channels only: a partner's "all" mark must still count
// this channel in.
TEST(SyncBarrier, APartnersAllMarkCountsThisChannelWhenOnlyTheOthersAreGiven) {
  SyncBarrier ch1(1);
  SyncArrival all = arrival_of(2, 1, 1, ChannelSet{}, true);
  ch1.on_arrival(all);
  ch1.arrive(1, set_of({1, 2}), false);
  EXPECT_EQ(ch1.evaluate(set_of({2})), SyncState::mismatch);
  SyncBarrier ch3(1);
  all.p = 2;
  ch3.on_arrival(all);
  ch3.arrive(1, set_of({1, 2}), false);
  EXPECT_EQ(ch3.evaluate(set_of({2})), SyncState::deadlock);
}

TEST(SyncBarrier, AWaitingCycleThroughThreeChannelsIsADeadlock) {
  Machine m(3);
  m.arrive(1, 1, set_of({1, 2}));  // CH1 waits for CH2 at P1
  m.arrive(2, 2, set_of({2, 3}));  // CH2 waits for CH3 at P2
  EXPECT_EQ(m.state(1), SyncState::waiting);
  m.arrive(3, 3, set_of({3, 1}));  // CH3 waits for CH1 at P3: nobody can move
  EXPECT_EQ(m.state(1), SyncState::deadlock);
  EXPECT_EQ(m.state(2), SyncState::deadlock);
  EXPECT_EQ(m.state(3), SyncState::deadlock);
}

TEST(SyncBarrier, WaitingForAChannelThatWaitsElsewhereIsNotADeadlockWhileThatOneCanGoOn) {
  // The spec's case: CH1 at P4 (all) while CH3 waits at P3 Q23 for CH2, which still runs.
  Machine m(3);
  m.arrive(1, 4, ChannelSet{}, true);
  m.arrive(3, 3, set_of({2, 3}));
  EXPECT_EQ(m.state(1), SyncState::waiting);
  EXPECT_EQ(m.state(3), SyncState::waiting);
  m.arrive(2, 3, set_of({2, 3}));
  EXPECT_EQ(m.state(3), SyncState::released);
  EXPECT_EQ(m.state(2), SyncState::released);
  m.arrive(2, 4, ChannelSet{}, true);
  m.arrive(3, 4, ChannelSet{}, true);
  EXPECT_EQ(m.state(1), SyncState::released);
}

TEST(SyncBarrier, AllChannelsMeansThoseInAutomaticOperation) {
  Machine m(3);
  m.active().reset(3);  // CH3 is idle: not awaited
  m.arrive(1, 9, ChannelSet{}, true);
  EXPECT_EQ(m.state(1), SyncState::waiting);
  EXPECT_EQ(m.ch(1).missing(), set_of({2}));
  m.arrive(2, 9, ChannelSet{}, true);
  EXPECT_EQ(m.state(1), SyncState::released);
  // P without Q in one channel and Q12 in the other at the same mark: a mismatch.
  m.arrive(1, 7, ChannelSet{}, true);
  m.arrive(2, 7, set_of({1, 2}));
  EXPECT_EQ(m.state(1), SyncState::mismatch);
}

TEST(SyncBarrier, TheThreeChannelExampleOfTheSpecRunsInTheExpectedOrder) {
  // CT-G041-01 at the barrier level: the marks of O1001/O1002/O1003 with the work between.
  Machine m(3);
  const auto q123 = set_of({1, 2, 3});
  m.arrive(1, 1, q123);
  m.arrive(2, 1, q123);
  EXPECT_EQ(m.state(1), SyncState::waiting);  // expected 1: nobody passes P1 before all
  m.arrive(3, 1, q123);
  for (int c = 1; c <= 3; ++c) {
    ASSERT_EQ(m.state(c), SyncState::released) << c;
  }
  m.arrive(1, 2, set_of({1, 2}));
  EXPECT_EQ(m.state(1), SyncState::waiting);  // expected 3: CH1's M05 waits for CH2 at P2
  m.arrive(3, 3, set_of({2, 3}));             // expected 2: CH3 is not in P2
  EXPECT_EQ(m.state(3), SyncState::waiting);
  m.arrive(2, 2, set_of({1, 2}));
  EXPECT_EQ(m.state(1), SyncState::released);
  EXPECT_EQ(m.state(2), SyncState::released);
  EXPECT_EQ(m.state(3), SyncState::waiting);
  m.arrive(1, 4, ChannelSet{}, true);  // expected 5: CH1 may sit at P4 meanwhile
  EXPECT_EQ(m.state(1), SyncState::waiting);
  m.arrive(2, 3, set_of({2, 3}));
  EXPECT_EQ(m.state(3), SyncState::released);  // expected 4
  EXPECT_EQ(m.state(2), SyncState::released);
  m.arrive(2, 4, ChannelSet{}, true);
  EXPECT_EQ(m.state(1), SyncState::waiting);  // expected 6: M30 only after all three
  m.arrive(3, 4, ChannelSet{}, true);
  for (int c = 1; c <= 3; ++c) {
    EXPECT_EQ(m.state(c), SyncState::released) << c;
  }
}

// Random programs that are deadlock-free by construction (every channel goes through the same
// sequence of marks, each naming a random subset that contains it) always finish; with two
// channels that name each other disagreeing on the set at one mark, the run always ends in an
// alarm instead of hanging.
struct Step {
  int p = 0;
  ChannelSet participants;
};

// Each channel's own program: the marks whose set contains it, in the common order.
std::vector<std::vector<Step>> programs(int n, const std::vector<Step>& marks) {
  std::vector<std::vector<Step>> out(static_cast<std::size_t>(n));
  for (const Step& s : marks) {
    for (int c = 1; c <= n; ++c) {
      if (s.participants.test(static_cast<std::size_t>(c))) {
        out[static_cast<std::size_t>(c - 1)].push_back(s);
      }
    }
  }
  return out;
}

// Runs the channels in a random interleaving; the state each channel ended in.
std::vector<SyncState> run(int n, const std::vector<std::vector<Step>>& progs, std::mt19937& rng) {
  Machine m(n);
  std::vector<std::size_t> at(static_cast<std::size_t>(n), 0);
  std::vector<SyncState> end(static_cast<std::size_t>(n), SyncState::none);
  std::vector<bool> waiting(static_cast<std::size_t>(n), false);
  for (int guard = 0; guard < 100000; ++guard) {
    std::vector<int> movable;
    for (int c = 1; c <= n; ++c) {
      const auto i = static_cast<std::size_t>(c - 1);
      if (end[i] == SyncState::none && (waiting[i] || at[i] < progs[i].size())) {
        movable.push_back(c);
      }
    }
    if (movable.empty()) {
      break;
    }
    bool progressed = false;
    std::shuffle(movable.begin(), movable.end(), rng);
    for (const int c : movable) {
      const auto i = static_cast<std::size_t>(c - 1);
      if (!waiting[i]) {
        const Step& s = progs[i][at[i]++];
        m.arrive(c, s.p, s.participants);
        waiting[i] = true;
        progressed = true;
        break;
      }
      const SyncState st = m.state(c);
      if (st == SyncState::released) {
        waiting[i] = false;
        progressed = true;
        if (at[i] == progs[i].size()) {
          end[i] = SyncState::released;
        }
        break;
      }
      if (st == SyncState::mismatch || st == SyncState::deadlock) {
        end[i] = st;
        waiting[i] = false;
        progressed = true;
        break;
      }
    }
    if (!progressed) {
      break;  // everyone waits and nothing changes: a hang the barrier did not report
    }
  }
  for (int c = 1; c <= n; ++c) {
    const auto i = static_cast<std::size_t>(c - 1);
    if (end[i] == SyncState::none && (waiting[i] || at[i] < progs[i].size())) {
      end[i] = SyncState::waiting;  // hung
    }
  }
  return end;
}

TEST(SyncBarrier, RandomDeadlockFreeProgramsFinishAndInjectedMismatchesAreFound) {
  std::mt19937 rng(20261201);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + static_cast<int>(rng() % 7);
    std::vector<Step> marks;
    const int count = 1 + static_cast<int>(rng() % 12);
    for (int k = 0; k < count; ++k) {
      Step s;
      s.p = 1 + static_cast<int>(rng() % 4);  // marks reused: rounds must keep them apart
      for (int c = 1; c <= n; ++c) {
        if (rng() % 2 == 0) {
          s.participants.set(static_cast<std::size_t>(c));
        }
      }
      if (s.participants.count() < 2) {
        s.participants.set(1).set(2);
      }
      marks.push_back(s);
    }
    auto progs = programs(n, marks);
    for (const SyncState st : run(n, progs, rng)) {
      ASSERT_TRUE(st == SyncState::released || st == SyncState::none)
          << "trial " << trial << " ended in " << static_cast<int>(st);
    }
    // Inject a disagreement: at one mark, one participant v names another set that still
    // contains a partner u (a third channel x added or left out), so u and v name each other
    // at the same P with different sets.
    if (n < 3) {
      continue;
    }
    const Step& chosen = marks[rng() % marks.size()];
    std::vector<int> members;
    for (int c = 1; c <= n; ++c) {
      if (chosen.participants.test(static_cast<std::size_t>(c))) {
        members.push_back(c);
      }
    }
    const int v = members[0];
    const int u = members[1];
    int x = 1;
    while (x == u || x == v) {
      ++x;
    }
    auto& prog = progs[static_cast<std::size_t>(v - 1)];
    for (Step& s : prog) {
      if (s.p == chosen.p && s.participants == chosen.participants) {
        s.participants.flip(static_cast<std::size_t>(x));
        break;
      }
    }
    bool mismatch = false;
    bool hung = false;
    for (const SyncState st : run(n, progs, rng)) {
      mismatch = mismatch || st == SyncState::mismatch;
      hung = hung || st == SyncState::waiting;
    }
    EXPECT_TRUE(mismatch) << "trial " << trial;
    EXPECT_FALSE(hung && !mismatch) << "trial " << trial;
  }
}

}  // namespace
}  // namespace mcnc::coordination

namespace mcnc::coordination {
namespace {

TEST(SyncBarrier, AFullMarkTableNamesTheChannelWhoseMarksDidNotFit) {
  SyncBarrier ch1(1);
  for (std::size_t p = 1; p <= SyncBarrier::kMarksPerChannel + 1; ++p) {
    ch1.on_arrival(arrival_of(3, static_cast<std::int32_t>(p), 1, set_of({1, 3})));
  }
  ch1.arrive(1, set_of({1, 2}), false);
  EXPECT_EQ(ch1.evaluate(set_of({2, 3})), SyncState::full);
  EXPECT_EQ(ch1.conflict_channel(), 3U);
}

}  // namespace
}  // namespace mcnc::coordination
