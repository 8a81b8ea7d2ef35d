#include "channel/control/block_queue.hpp"

#include <cmath>

namespace mcnc::channel {

void BlockQueue::push(const interp::Command& c, const interp::AxisVector& start) noexcept {
  if (full()) {
    return;  // the caller pulls only while there is room
  }
  // A spindle command takes effect where the planner reaches it; as a block it does not move and
  // passes at once.
  const bool spindle = c.op == interp::Op::spindle;
  // G80.1 ends once the oscillating axis stands at its end position.
  const bool ends_at_rest = c.op == interp::Op::oscillate_end;
  blocks_[(head_ + count_) % blocks_.size()] = QueuedBlock{
      c.n,
      c.line,
      c.op == interp::Op::dwell || spindle ? start : c.to,
      c.exact_stop || c.op == interp::Op::rapid || c.op == interp::Op::dwell || ends_at_rest,
      spindle || ((c.op == interp::Op::rapid || c.op == interp::Op::linear) && c.to == start),
      c.file,
      c.block_text,
      c.modal};
  QueuedBlock& b = blocks_[(head_ + count_) % blocks_.size()];
  for (std::size_t i = 0; i < c.to.size() && i < 32 && c.moves(); ++i) {
    b.moves |= c.to[i] != start[i] ? 1U << i : 0U;
  }
  b.sets_torque_limit = (c.torque_skip && c.torque_limit > 0.0) || c.load_skip;
  b.feed = c.op == interp::Op::linear;
  ++count_;
}

void BlockQueue::end_newest_at(const interp::AxisVector& at) noexcept {
  if (!empty()) {
    blocks_[(head_ + count_ - 1) % blocks_.size()].to = at;
  }
}

int BlockQueue::first_moving(std::size_t axis, double from) const noexcept {
  for (std::size_t k = 0; k < count_; ++k) {
    const QueuedBlock& q = blocks_[(head_ + k) % blocks_.size()];
    if (std::fabs(q.to[axis] - from) > 1e-9 && q.line != 0) {
      return q.line;
    }
  }
  return 0;
}

BlockQueue::Due BlockQueue::due(const motion::MotionOutput& m, bool planner_idle) const noexcept {
  if (empty()) {
    return Due::none;
  }
  const QueuedBlock& q = front();
  // An idle planner has run everything it took.
  const std::uint64_t done = planner_idle ? ~std::uint64_t{0} : m.completed_block;
  if (!started_) {
    return q.n > m.block && q.n > done && !q.still ? Due::none : Due::start;
  }
  if (q.still) {
    return Due::end;
  }
  if (q.n > done) {
    return Due::none;
  }
  // A block the path stopped at is an exact stop, whatever made it stop (G09/G61, a rapid, a
  // dwell or the program end after it, a corner the look-ahead would not blend).
  const bool stopped_here = q.n == m.completed_block && m.path_velocity <= 0.0;
  return q.exact_stop || stopped_here ? Due::end_if_in_position : Due::end;
}

void BlockQueue::ended() noexcept {
  head_ = (head_ + 1) % blocks_.size();
  --count_;
  started_ = false;
}

}  // namespace mcnc::channel
