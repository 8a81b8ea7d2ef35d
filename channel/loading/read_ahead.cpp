#include "channel/loading/read_ahead.hpp"

#include "common/process/thread_name.hpp"

#include <pthread.h>
#include <sched.h>
#include <algorithm>

#include <limits>
#include <utility>

namespace mcnc::channel {

namespace {

// The channel's alarm of things that are not the program's fault (docs/alarms.md, 1200).
constexpr int kAlarmReadAhead = 1200;

}  // namespace

ReadAhead::ReadAhead(interp::macro::SharedWriteSink* writes_out,
                     interp::macro::VariableStore* shared)
    : writes_out_(writes_out), shared_(shared) {}

ReadAhead::~ReadAhead() {
  stop();
}

void ReadAhead::start(interp::CommandSource& inner) {
  inner_ = &inner;
  block_count_ = inner.block_count();
  has_program_ = inner.has_program();
  thread_ = std::thread([this] { run_thread(); });
}

void ReadAhead::stop() noexcept {
  if (stopped_) {
    return;
  }
  if (thread_.joinable()) {
    stopping_.store(true, std::memory_order_release);
    bell_.fetch_add(1, std::memory_order_release);
    bell_.notify_all();
    thread_.join();
  }
  apply_peer_writes(std::numeric_limits<std::uint64_t>::max());
  stopped_ = true;
}

bool ReadAhead::peer_write(std::int64_t number, interp::macro::MacroValue value) noexcept {
  if (shared_ == nullptr) {
    return true;
  }
  if (stopped_) {
    (void)shared_->write(number, value);
    return true;
  }
  SharedWrite* w = peer_writes_.claim();
  if (w == nullptr) {
    return false;
  }
  *w = SharedWrite{number, value};
  peer_writes_.publish();
  ++peer_writes_posted_;
  if (!expecting_) {
    visible_writes_.store(peer_writes_posted_, std::memory_order_release);
    ring_bell();
  }
  return true;
}

void ReadAhead::ring_bell() noexcept {
  bell_.fetch_add(1, std::memory_order_release);
  bell_.notify_one();
}

void ReadAhead::thread_stands() noexcept {
  expecting_ = false;
  visible_writes_.store(peer_writes_posted_, std::memory_order_release);
  ring_bell();
}

void ReadAhead::abandon() noexcept {
  // A newer run that nobody starts: the thread stops reading the old one. Its shared writes
  // still reach writes_out in order (ready() passes the old run's on at the next start).
  ++run_;
  latest_run_.store(run_, std::memory_order_release);
  passed_stop_ = false;
  has_position_ = false;
  has_skip_ = false;
  has_timer_ = false;
  has_overload_ = false;
  thread_stands();
}

// --- the cycle's side ---

ReadAhead::Order* ReadAhead::order_slot() noexcept {
  Order* o = orders_.claim();
  if (o == nullptr) {
    // As many orders as the queue holds not taken: the thread is stuck. The next pull
    // answers the alarm.
    order_lost_ = true;
    expecting_ = false;
  }
  return o;
}

void ReadAhead::post() noexcept {
  orders_.publish();
  ring_bell();
}

ReadAhead::Order* ReadAhead::begin_run(Order::Kind kind, const interp::AxisVector& at) noexcept {
  ++run_;
  latest_run_.store(run_, std::memory_order_release);
  passed_stop_ = false;
  has_position_ = false;
  has_skip_ = false;
  has_timer_ = false;
  has_overload_ = false;
  order_lost_ = false;
  Order* o = order_slot();
  if (o == nullptr) {
    return nullptr;
  }
  expecting_ = true;
  o->kind = kind;
  o->run = run_;
  o->at = at;
  o->has_position = false;
  o->has_skip = false;
  o->has_timer = false;
  o->arg_count = 0;
  o->peer_writes = peer_writes_posted_;
  return o;
}

void ReadAhead::rewind(const interp::AxisVector& current) {
  if (begin_run(Order::Kind::rewind, current) != nullptr) {
    post();
  }
}

std::optional<interp::ProgramAlarm> ReadAhead::start_mdi(const interp::AxisVector& current) {
  if (begin_run(Order::Kind::mdi, current) != nullptr) {
    post();
  }
  return std::nullopt;
}

std::optional<interp::ProgramAlarm> ReadAhead::call(int number,
                                                    std::span<const std::pair<int, double>> args,
                                                    const interp::AxisVector& current) {
  Order* o = begin_run(Order::Kind::call, current);
  if (o == nullptr) {
    return std::nullopt;
  }
  o->program = number;
  for (const auto& arg : args) {
    if (o->arg_count < o->args.size()) {
      o->args[o->arg_count++] = arg;
    }
  }
  post();
  return std::nullopt;
}

void ReadAhead::adopt(interp::CheckedProgram program) noexcept {
  block_count_ = program.block_count;
  has_program_ = !program.alarm.has_value();
  Order* o = order_slot();
  if (o == nullptr) {
    has_program_ = false;
    return;
  }
  o->kind = Order::Kind::adopt;
  o->run = run_;
  o->peer_writes = peer_writes_posted_;
  o->checked = std::move(program);
  post();
}

void ReadAhead::prepare_mdi(interp::CheckedProgram blocks) noexcept {
  Order* o = order_slot();
  if (o == nullptr) {
    return;
  }
  o->kind = Order::Kind::prepare_mdi;
  o->run = run_;
  o->peer_writes = peer_writes_posted_;
  o->checked = std::move(blocks);
  post();
}

void ReadAhead::adopt_position(const interp::AxisVector& at) {
  position_ = at;
  has_position_ = true;
}

void ReadAhead::skip_result(bool skipped, const interp::AxisVector& skip_at,
                            const interp::AxisVector& stop_at) {
  has_skip_ = true;
  multi_skip_ = false;
  skipped_ = skipped;
  skip_at_ = skip_at;
  stop_at_ = stop_at;
}

void ReadAhead::load_timer_result(std::uint32_t axes) {
  has_timer_ = true;
  timer_axes_ = axes;
}

void ReadAhead::overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                                const interp::AxisVector& stop_at) {
  has_overload_ = true;
  overloads_ = overloads;
  dropped_block_ = dropped_block;
  stop_at_ = stop_at;
}

void ReadAhead::multi_skip_result(std::span<const double> latched,
                                  const interp::AxisVector& stop_at) {
  has_skip_ = true;
  multi_skip_ = true;
  latched_count_ = std::min(latched.size(), latched_.size());
  std::copy_n(latched.begin(), latched_count_, latched_.begin());
  stop_at_ = stop_at;
}

bool ReadAhead::ready() noexcept {
  release_taken();
  if (stopped_ || inner_ == nullptr) {
    return false;
  }
  if (order_lost_) {
    return true;  // next() answers the alarm
  }
  for (;;) {
    Entry* e = entries_.front();
    if (e != nullptr) {
      if (e->kind == Entry::Kind::shared_write) {
        // Evaluated, so in this channel's own copy: the partners get it too, even from a run
        // that was abandoned.
        if (writes_out_ != nullptr) {
          writes_out_->on_shared_write(e->write.number, e->write.value);
        }
      } else if (e->run != run_) {
        // read ahead for a run that was abandoned
      } else if (e->kind == Entry::Kind::started) {
        block_count_ = e->block_count;
      } else {
        return true;
      }
      pop_entry();
      continue;
    }
    if (passed_stop_) {
      // The cycle pulls past a read-ahead stop: the thread reads on, from the position the
      // channel stands at there and with what the partners wrote so far.
      passed_stop_ = false;
      Order* o = order_slot();
      if (o == nullptr) {
        return true;  // next() answers the alarm
      }
      o->kind = Order::Kind::resume;
      o->run = run_;
      o->at = position_;
      o->has_position = has_position_;
      o->has_skip = has_skip_;
      o->skipped = skipped_;
      o->skip_at = skip_at_;
      o->stop_at = stop_at_;
      o->multi_skip = multi_skip_;
      o->latched = latched_;
      o->latched_count = latched_count_;
      o->has_timer = has_timer_;
      o->timer_axes = timer_axes_;
      o->has_overload = has_overload_;
      o->overloads = overloads_;
      o->dropped_block = dropped_block_;
      o->peer_writes = peer_writes_posted_;
      has_position_ = false;
      has_skip_ = false;
      has_timer_ = false;
      has_overload_ = false;
      expecting_ = true;
      post();
    }
    if (!lockstep_ || !expecting_) {
      return false;
    }
    entries_.wait_for_item();
  }
}

std::optional<interp::PullResult> ReadAhead::next() {
  interp::PullResult* taken = take_slot();
  if (taken == nullptr) {
    return std::nullopt;
  }
  return std::optional<interp::PullResult>(std::move(*taken));
}

interp::PullResult* ReadAhead::take_slot() {
  if (!ready()) {
    answer_ = interp::PullResult{interp::ProgramAlarm{
        kAlarmReadAhead, "the read-ahead was asked for a command it did not have", "", 0, 0}};
    return &*answer_;
  }
  if (order_lost_) {
    order_lost_ = false;
    expecting_ = false;
    answer_ = interp::PullResult{
        interp::ProgramAlarm{kAlarmReadAhead, "the read-ahead thread does not answer", "", 0, 0}};
    return &*answer_;
  }
  Entry* e = entries_.front();
  interp::PullResult* out = nullptr;
  if (e->kind == Entry::Kind::pulled) {
    out = &e->pulled;  // read where it lies: the slot stays the cycle's until release_taken()
    holds_taken_ = true;
  } else {
    pop_entry();
  }
  const auto* c = out != nullptr ? std::get_if<interp::Command>(out) : nullptr;
  if (c == nullptr || c->op == interp::Op::end) {
    thread_stands();  // the run is over: an alarm, the end, or nothing left
  } else if (c->barrier) {
    thread_stands();
    passed_stop_ = true;
  }
  return out;
}

void ReadAhead::release_taken() noexcept {
  if (holds_taken_) {
    holds_taken_ = false;
    pop_entry();
  }
}

void ReadAhead::pop_entry() noexcept {
  // The thread waits on the bell for orders too: a pop that made no room it waits for does not
  // wake it (a system call and a wake-up of its thread per command, in the cycle).
  if (entries_.pop_was_full()) {
    ring_bell();
  }
}

// --- the read-ahead thread ---

void ReadAhead::run_thread() noexcept {
  // The interpreter may take milliseconds for a block (a G71 over a long contour) and seconds
  // for a loop: never at the cycle's real-time priority, which a thread inherits from the
  // process (--clock realtime).
  sched_param normal{};
  (void)pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  process::name_this_thread("read-ahead");
  for (;;) {
    const std::uint32_t bell = bell_.load(std::memory_order_acquire);
    if (stopping_.load(std::memory_order_acquire)) {
      return;
    }
    if (Order* o = orders_.front()) {
      handle(*o);
      orders_.pop();
      continue;
    }
    if (reading_ && !abandoned()) {
      read_until_stop();
      continue;
    }
    // Standing: the partners' writes posted since reach the interpreter now, so that they
    // never pile up while a channel stands.
    apply_peer_writes(visible_writes_.load(std::memory_order_acquire));
    bell_.wait(bell, std::memory_order_acquire);
  }
}

bool ReadAhead::abandoned() const noexcept {
  return stopping_.load(std::memory_order_acquire) ||
         latest_run_.load(std::memory_order_acquire) != thread_run_;
}

ReadAhead::Entry* ReadAhead::room() noexcept {
  for (;;) {
    const std::uint32_t bell = bell_.load(std::memory_order_acquire);
    if (Entry* e = entries_.claim()) {
      return e;
    }
    if (abandoned()) {
      return nullptr;
    }
    bell_.wait(bell, std::memory_order_acquire);
  }
}

void ReadAhead::apply_peer_writes(std::uint64_t upto) noexcept {
  while (peer_writes_applied_ < upto) {
    const SharedWrite* w = peer_writes_.front();
    if (w == nullptr) {
      return;
    }
    if (shared_ != nullptr) {
      (void)shared_->write(w->number, w->value);
    }
    peer_writes_.pop();
    ++peer_writes_applied_;
  }
}

void ReadAhead::handle(Order& order) noexcept {
  apply_peer_writes(order.peer_writes);
  std::optional<interp::ProgramAlarm> alarm;
  switch (order.kind) {
    case Order::Kind::adopt:
      reading_ = false;  // a program is adopted only while no run is under way
      inner_->adopt(std::move(order.checked));
      return;
    case Order::Kind::prepare_mdi:
      reading_ = false;
      inner_->prepare_mdi(std::move(order.checked));
      return;
    case Order::Kind::resume:
      if (order.run == thread_run_) {
        if (order.has_position) {
          inner_->adopt_position(order.at);
        }
        if (order.has_skip && order.multi_skip) {
          inner_->multi_skip_result(
              std::span<const double>(order.latched.data(), order.latched_count), order.stop_at);
        } else if (order.has_skip) {
          inner_->skip_result(order.skipped, order.skip_at, order.stop_at);
        }
        if (order.has_timer) {
          inner_->load_timer_result(order.timer_axes);
        }
        if (order.has_overload) {
          inner_->overload_result(order.overloads, order.dropped_block, order.stop_at);
        }
        reading_ = true;
      }
      return;
    case Order::Kind::stop:
      return;
    case Order::Kind::rewind:
    case Order::Kind::mdi:
    case Order::Kind::call:
      break;
  }
  thread_run_ = order.run;
  reading_ = false;
  // A start builds the run's interpreter and a call reads and parses its program: allocations,
  // here and not in the cycle. Out of memory is the run's alarm.
  try {
    if (order.kind == Order::Kind::rewind) {
      inner_->rewind(order.at);
    } else if (order.kind == Order::Kind::mdi) {
      alarm = inner_->start_mdi(order.at);
    } else {
      alarm = inner_->call(order.program, std::span(order.args.data(), order.arg_count), order.at);
    }
  } catch (...) {
    alarm = interp::ProgramAlarm{kAlarmReadAhead, "the interpreter ran out of memory", "", 0, 0};
  }
  Entry* e = room();
  if (e == nullptr) {
    return;  // a newer start came meanwhile
  }
  e->kind = Entry::Kind::started;
  e->run = thread_run_;
  e->block_count = alarm ? 0 : inner_->block_count();
  entries_.publish();
  if (!alarm) {
    reading_ = true;
    return;
  }
  e = room();
  if (e == nullptr) {
    return;
  }
  e->kind = Entry::Kind::pulled;
  e->run = thread_run_;
  e->pulled = std::move(*alarm);
  entries_.publish();
}

void ReadAhead::read_until_stop() noexcept {
  while (reading_ && !abandoned() && orders_.front() == nullptr) {
    std::optional<interp::PullResult> pulled;
    try {
      pulled = inner_->next();
    } catch (...) {
      pulled = interp::PullResult{
          interp::ProgramAlarm{kAlarmReadAhead, "the interpreter ran out of memory", "", 0, 0}};
    }
    Entry* e = room();
    if (e == nullptr) {
      reading_ = false;
      return;
    }
    e->run = thread_run_;
    if (!pulled) {
      e->kind = Entry::Kind::exhausted;
      reading_ = false;
    } else {
      const auto* c = std::get_if<interp::Command>(&*pulled);
      // It reads no further than a read-ahead stop, the end or an alarm.
      reading_ = c != nullptr && !c->barrier && c->op != interp::Op::end;
      e->kind = Entry::Kind::pulled;
      e->pulled = std::move(*pulled);
    }
    entries_.publish();
  }
}

void ReadAhead::Relay::on_shared_write(std::int64_t number,
                                       interp::macro::MacroValue value) noexcept {
  // Written already in this channel's copy: it must reach the partners, even from a run that
  // was abandoned, so the thread waits for room (the cycle passes such writes on at the next
  // start). Only a stop of the thread loses it.
  Entry* e = nullptr;
  for (;;) {
    const std::uint32_t bell = owner_.bell_.load(std::memory_order_acquire);
    e = owner_.entries_.claim();
    if (e != nullptr || owner_.stopping_.load(std::memory_order_acquire)) {
      break;
    }
    owner_.bell_.wait(bell, std::memory_order_acquire);
  }
  if (e == nullptr) {
    return;
  }
  e->kind = Entry::Kind::shared_write;
  e->run = owner_.thread_run_;
  e->write = SharedWrite{number, value};
  owner_.entries_.publish();
}

}  // namespace mcnc::channel
