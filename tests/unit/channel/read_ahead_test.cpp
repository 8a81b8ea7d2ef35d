// The read-ahead thread between the interpreter and the cycle (channel/loading): what the
// cycle takes is what the interpreter gives, in order; the thread stops at read-ahead stops
// until the cycle pulls past them; shared writes keep their place among the commands; the
// partners' writes reach the interpreter at stops only; a realtime cycle never waits.
#include "channel/loading/read_ahead.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

namespace mcnc::channel {
namespace {

using interp::Command;
using interp::Op;
using interp::PullResult;
using namespace std::chrono_literals;

Command move_to(int line, double x, bool barrier = false) {
  Command c;
  c.op = Op::linear;
  c.line = line;
  c.n = static_cast<std::uint64_t>(line);
  c.to[0] = x;
  c.feed = 100.0;
  c.barrier = barrier;
  return c;
}

Command program_end(int line) {
  Command c;
  c.op = Op::end;
  c.code = 30;
  c.line = line;
  c.n = static_cast<std::uint64_t>(line);
  return c;
}

// A source of `count` moves, line i to x = i, then M30; a stop at the lines in `stops`. Before
// the move of each line in `writes_at` it writes #500 = line through the sink; it reads #600
// from the shared store at every pull. What it did is logged, in the order done.
class ScriptSource final : public interp::CommandSource {
 public:
  ScriptSource(int count, std::vector<int> stops) : count_(count), stops_(std::move(stops)) {}
  void rewind(const interp::AxisVector& current) override {
    std::lock_guard<std::mutex> lock(mutex_);
    line_ = 0;
    log_.push_back("rewind " + std::to_string(current[0]));
  }
  std::optional<PullResult> next() override {
    if (block_ != nullptr) {
      while (block_->load()) {
        std::this_thread::sleep_for(1ms);
      }
    }
    const int line = ++line_;
    pulls_.fetch_add(1);
    if (shared_ != nullptr) {
      seen_600_.push_back(shared_->read(600).value.number());
    }
    if (line > count_ + 1) {
      return std::nullopt;
    }
    if (line == count_ + 1) {
      return PullResult{program_end(line)};
    }
    for (const int w : writes_at_) {
      if (w == line && sink_ != nullptr) {
        sink_->on_shared_write(500, interp::macro::MacroValue::of(line));
      }
    }
    bool stop = false;
    for (const int s : stops_) {
      stop = stop || s == line;
    }
    return PullResult{move_to(line, line, stop)};
  }
  [[nodiscard]] std::size_t block_count() const noexcept override {
    return static_cast<std::size_t>(count_ + 1);
  }
  void adopt_position(const interp::AxisVector& at) override {
    std::lock_guard<std::mutex> lock(mutex_);
    log_.push_back("position " + std::to_string(at[0]) + " after line " + std::to_string(line_));
  }
  std::optional<interp::ProgramAlarm> call(int number, std::span<const std::pair<int, double>> args,
                                           const interp::AxisVector&) override {
    line_ = 0;
    called_args_ = args.size();
    if (number != 1234) {
      return interp::ProgramAlarm{1150, "O" + std::to_string(number) + " not found", "", 0, 0};
    }
    return std::nullopt;
  }
  std::vector<std::string> log() {
    std::lock_guard<std::mutex> lock(mutex_);
    return log_;
  }

  int count_;
  std::vector<int> stops_;
  std::vector<int> writes_at_;
  interp::macro::SharedWriteSink* sink_ = nullptr;
  interp::macro::VariableStore* shared_ = nullptr;
  std::atomic<bool>* block_ = nullptr;  // while true, next() does not answer
  std::atomic<int> pulls_{0};
  std::vector<double> seen_600_;  // #600 at each pull (read after the thread stood still)
  std::size_t called_args_ = 0;

 private:
  int line_ = 0;
  std::mutex mutex_;
  std::vector<std::string> log_;
};

// Writes the cycle takes, with how many commands the cycle had taken when each came.
class TakenWrites final : public interp::macro::SharedWriteSink {
 public:
  void on_shared_write(std::int64_t number, interp::macro::MacroValue value) noexcept override {
    writes.push_back({number, value.number(), *taken});
  }
  struct Write {
    std::int64_t number;
    double value;
    int taken_before;
  };
  std::vector<Write> writes;
  const int* taken = nullptr;
};

// In lockstep, `source` telling its shared writes to `r`, a run started.
void start_writing_run(ReadAhead& r, ScriptSource& source) {
  source.sink_ = &r.interpreter_sink();
  r.set_lockstep(true);
  r.start(source);
  r.rewind({});
}

// Takes commands in lockstep until the end or a stop; the lines taken.
std::vector<int> take_until_stop(ReadAhead& r, int* taken = nullptr) {
  std::vector<int> lines;
  while (r.ready()) {
    const auto pulled = r.next();
    EXPECT_TRUE(pulled.has_value());
    if (!pulled) {
      break;
    }
    const auto* c = std::get_if<Command>(&*pulled);
    EXPECT_NE(c, nullptr);
    if (c == nullptr) {
      break;
    }
    lines.push_back(c->line);
    if (taken != nullptr) {
      ++*taken;
    }
    if (c->barrier || c->op == Op::end) {
      break;
    }
  }
  return lines;
}

TEST(ReadAhead, TakeHandsOverEachCommandWhereItLiesInTheRingAndTheSlotGoesBackAtTheNextPull) {
  ScriptSource source(1000, {300});
  ReadAhead r(nullptr, nullptr);
  r.set_lockstep(true);
  r.start(source);
  r.rewind({});
  std::vector<int> lines;
  std::set<const PullResult*> places;
  while (r.ready()) {
    const PullResult* pulled = r.take();
    ASSERT_NE(pulled, nullptr);
    places.insert(pulled);
    const auto& c = std::get<Command>(*pulled);
    lines.push_back(c.line);
    if (c.op == Op::end) {
      break;
    }
  }
  // Past the stop at line 300 and to the end: each slot went back to the thread once read.
  ASSERT_EQ(lines.size(), 1001U);
  for (int i = 0; i < 1001; ++i) {
    ASSERT_EQ(lines[static_cast<std::size_t>(i)], i + 1);
  }
  // Read where they lay, in the ring's slots: none was copied out to one place.
  EXPECT_GT(places.size(), 1U);
  EXPECT_LE(places.size(), ReadAhead::kWindow);
  EXPECT_FALSE(r.ready());  // nothing after the end
}

TEST(CommandSource, TakeOfASourceWithoutABufferAnswersWhatNextDoes) {
  ScriptSource source(2, {});
  source.rewind({});
  for (int line = 1; line <= 2; ++line) {
    const PullResult* pulled = source.take();
    ASSERT_NE(pulled, nullptr);
    EXPECT_EQ(std::get<Command>(*pulled).line, line);
  }
  EXPECT_EQ(std::get<Command>(*source.take()).op, Op::end);
  EXPECT_EQ(source.take(), nullptr);
}

TEST(ReadAhead, LockstepHandsOutTheSourcesCommandsInOrderAndReadsNoMoreThanItsWindowAhead) {
  ScriptSource source(3000, {});
  ReadAhead r(nullptr, nullptr);
  r.set_lockstep(true);
  r.start(source);
  r.rewind({});
  int taken = 0;
  std::size_t most_ahead = 0;
  std::vector<int> lines;
  while (r.ready()) {
    const auto pulled = r.next();
    ASSERT_TRUE(pulled.has_value());
    const auto& c = std::get<Command>(*pulled);
    lines.push_back(c.line);
    ++taken;
    most_ahead = std::max(most_ahead, static_cast<std::size_t>(source.pulls_.load() - taken));
    if (c.op == Op::end) {
      break;
    }
  }
  ASSERT_EQ(lines.size(), 3001U);
  for (int i = 0; i < 3001; ++i) {
    ASSERT_EQ(lines[static_cast<std::size_t>(i)], i + 1);
  }
  EXPECT_LE(most_ahead, ReadAhead::kWindow + 1);
  EXPECT_GT(most_ahead, 0U) << "it read ahead at all";
  EXPECT_EQ(r.block_count(), 3001U);
  EXPECT_FALSE(r.ready()) << "nothing after the end, and no wait for it";
}

TEST(ReadAhead, StopsAtAReadAheadStopUntilTheCyclePullsPastAndTakesThePositionAdoptedThere) {
  ScriptSource source(10, {4});
  ReadAhead r(nullptr, nullptr);
  r.set_lockstep(true);
  r.start(source);
  r.rewind({});
  EXPECT_EQ(take_until_stop(r), (std::vector<int>{1, 2, 3, 4}));
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(source.pulls_.load(), 4) << "nothing after the stop was evaluated";
  interp::AxisVector at{};
  at[0] = 42.0;
  r.adopt_position(at);  // e.g. G141 brought an axis
  EXPECT_EQ(take_until_stop(r), (std::vector<int>{5, 6, 7, 8, 9, 10, 11}));
  const std::vector<std::string> log = source.log();
  ASSERT_EQ(log.size(), 2U);
  EXPECT_EQ(log[1], "position 42.000000 after line 4");
}

TEST(ReadAhead, TheChannelsSharedWritesReachTheCycleWithTheCommandAfterThem) {
  ScriptSource source(300, {});
  source.writes_at_ = {2, 150, 299};
  TakenWrites out;
  int taken = 0;
  out.taken = &taken;
  ReadAhead r(&out, nullptr);
  start_writing_run(r, source);
  (void)take_until_stop(r, &taken);
  ASSERT_EQ(out.writes.size(), 3U);
  // Written while line k was evaluated, before its command: seen once k-1 commands were taken.
  EXPECT_EQ(out.writes[0].taken_before, 1);
  EXPECT_EQ(out.writes[1].taken_before, 149);
  EXPECT_EQ(out.writes[2].taken_before, 298);
  EXPECT_DOUBLE_EQ(out.writes[1].value, 150.0);
}

TEST(ReadAhead, APartnersWriteReachesTheInterpreterAtTheNextStopNotBefore) {
  interp::macro::VariableStore shared(interp::macro::MacroDialect{});
  ScriptSource source(8, {3, 6});
  source.shared_ = &shared;
  ReadAhead r(nullptr, &shared);
  r.set_lockstep(true);
  r.start(source);
  r.rewind({});
  EXPECT_EQ(take_until_stop(r), (std::vector<int>{1, 2, 3}));
  ASSERT_TRUE(r.peer_write(600, interp::macro::MacroValue::of(7.0)));
  EXPECT_EQ(take_until_stop(r), (std::vector<int>{4, 5, 6}));
  ASSERT_TRUE(r.peer_write(600, interp::macro::MacroValue::of(9.0)));
  EXPECT_EQ(take_until_stop(r), (std::vector<int>{7, 8, 9}));
  r.stop();
  ASSERT_EQ(source.seen_600_.size(), 9U);
  EXPECT_EQ(source.seen_600_, (std::vector<double>{0, 0, 0, 7, 7, 7, 9, 9, 9}));
}

TEST(ReadAhead, RealtimeNeverWaitsForTheThread) {
  std::atomic<bool> blocked{true};
  ScriptSource source(5, {});
  source.block_ = &blocked;
  ReadAhead r(nullptr, nullptr);
  r.start(source);  // realtime: the default
  r.rewind({});
  const auto before = std::chrono::steady_clock::now();
  for (int i = 0; i < 100; ++i) {
    EXPECT_FALSE(r.ready());
  }
  EXPECT_LT(std::chrono::steady_clock::now() - before, 50ms);
  blocked = false;
  const auto until = std::chrono::steady_clock::now() + 10s;
  while (!r.ready() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_TRUE(r.ready());
  EXPECT_EQ(std::get<Command>(*r.next()).line, 1);
}

TEST(ReadAhead, ANewStartDropsWhatWasReadAheadForTheRunBefore) {
  ScriptSource source(1000, {});
  ReadAhead r(nullptr, nullptr);
  r.set_lockstep(true);
  r.start(source);
  interp::AxisVector at{};
  at[0] = 1.0;
  r.rewind(at);
  ASSERT_TRUE(r.ready());
  EXPECT_EQ(std::get<Command>(*r.next()).line, 1);
  EXPECT_EQ(std::get<Command>(*r.next()).line, 2);
  at[0] = 2.0;
  r.rewind(at);  // a reset and a new cycle start
  ASSERT_TRUE(r.ready());
  EXPECT_EQ(std::get<Command>(*r.next()).line, 1);
  const std::vector<std::string> log = source.log();
  ASSERT_EQ(log.size(), 2U);
  EXPECT_EQ(log[1], "rewind 2.000000");
}

TEST(ReadAhead, ACallsAlarmIsTheFirstPullsAnswer) {
  ScriptSource source(3, {});
  ReadAhead r(nullptr, nullptr);
  r.set_lockstep(true);
  r.start(source);
  const std::pair<int, double> args[] = {{1, 2.0}, {24, 5.0}};
  EXPECT_FALSE(r.call(4321, args, {}).has_value());
  ASSERT_TRUE(r.ready());
  const auto pulled = r.next();
  ASSERT_TRUE(pulled.has_value());
  const auto* alarm = std::get_if<interp::ProgramAlarm>(&*pulled);
  ASSERT_NE(alarm, nullptr);
  EXPECT_EQ(alarm->number, 1150);
  EXPECT_EQ(alarm->text, "O4321 not found");
  EXPECT_EQ(r.block_count(), 0U);
  EXPECT_FALSE(r.ready());

  EXPECT_FALSE(r.call(1234, args, {}).has_value());
  EXPECT_EQ(take_until_stop(r), (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(source.called_args_, 2U);
}

TEST(ReadAhead, PartnersWritesNeverPileUpWhileTheChannelStands) {
  interp::macro::VariableStore shared(interp::macro::MacroDialect{});
  ScriptSource source(3, {});
  source.shared_ = &shared;
  ReadAhead r(nullptr, &shared);
  r.set_lockstep(true);
  r.start(source);
  // Idle, no run: ten times what the queue holds, as a partner writing in a loop would.
  // The thread applies them as they come: a full queue empties again.
  for (int i = 1; i <= static_cast<int>(ReadAhead::kPeerWrites) * 10; ++i) {
    const auto until = std::chrono::steady_clock::now() + 10s;
    while (!r.peer_write(600, interp::macro::MacroValue::of(i))) {
      ASSERT_LT(std::chrono::steady_clock::now(), until) << "write " << i << " never taken";
      std::this_thread::sleep_for(1ms);
    }
  }
  r.rewind({});
  EXPECT_EQ(take_until_stop(r), (std::vector<int>{1, 2, 3, 4}));
  r.stop();
  ASSERT_FALSE(source.seen_600_.empty());
  EXPECT_DOUBLE_EQ(source.seen_600_.front(), static_cast<double>(ReadAhead::kPeerWrites) * 10);
}

TEST(ReadAhead, TheSharedWritesOfARunAbandonedByAResetStillReachThePartners) {
  ScriptSource source(600, {});
  source.writes_at_ = {5, 400};
  TakenWrites out;
  int taken = 0;
  out.taken = &taken;
  ReadAhead r(&out, nullptr);
  start_writing_run(r, source);
  ASSERT_TRUE(r.ready());
  EXPECT_EQ(std::get<Command>(*r.next()).line, 1);  // the cycle took one command, then a reset
  const auto until = std::chrono::steady_clock::now() + 10s;
  while (source.pulls_.load() < 20 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(1ms);  // the thread reads the old run ahead, past line 5
  }
  r.abandon();
  r.rewind({});
  ASSERT_TRUE(r.ready());
  EXPECT_EQ(std::get<Command>(*r.next()).line, 1);
  // #500 = 5 was evaluated (the thread read past line 5 before the reset came): in this
  // channel's copy, so the partners get it too. Line 400 lies beyond the window: never.
  ASSERT_GE(out.writes.size(), 1U);
  EXPECT_DOUBLE_EQ(out.writes[0].value, 5.0);
  EXPECT_EQ(out.writes[0].taken_before, 0);
}

}  // namespace
}  // namespace mcnc::channel
