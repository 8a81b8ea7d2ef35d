// Simplified programming (spec dafeng §2.4 L1255-1420, gsk A.6.10-A.6.11): the automatic corner
// a block asks for after its move (,C ,R E; GSK L D), which the look-ahead inserts
// (block_lookahead.hpp), and angle programming (,A; GSK Q), which completes a G01's end point.
#include "channel/interp/path/line_angle.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

bool ProgramRun::take_corner_request() {
  corner_kind_ = Command::Corner::none;
  corner_size_ = 0.0;
  const bool gsk = config_.dialect == Dialect::gsk;
  BlockWord* chamfer = gsk ? word('L') : comma_word('C');
  BlockWord* round = gsk ? word('D') : comma_word('R');
  if (!gsk) {
    if (BlockWord* e = word('E')) {
      e->used = true;  // the corner feed, modal (spec L1262, #4108)
      if (e->value < 0.0) {
        return fail(alarm::kNegativeFeed, "corner feed E must not be negative", e->column);
      }
      corner_feed_ = e->value * (modal_.metric ? 1.0 : 25.4);
    }
  }
  if (round != nullptr) {
    round->used = true;
  }
  BlockWord* size = chamfer != nullptr ? chamfer : round;  // ,C wins over ,R (spec L1267)
  if (size == nullptr) {
    return true;
  }
  size->used = true;
  const double v = length_of(*size);
  if (v <= 0.0) {
    return fail(alarm::kCornerDoesNotFit, "a chamfer or corner radius must be greater than 0",
                size->column);
  }
  corner_size_ = v;
  corner_kind_ = chamfer == nullptr                 ? Command::Corner::round
                 : gsk && config_.chamfer_is_length ? Command::Corner::chamfer_length
                                                    : Command::Corner::chamfer_setback;
  return true;
}

void ProgramRun::mark_corner(Command& c) const {
  c.corner = corner_kind_;
  c.corner_size = corner_size_;
  c.corner_feed = corner_feed_;
}

bool ProgramRun::apply_line_angle(AxisVector& target, std::array<bool, kMaxChannelAxes>& given,
                                  bool& deferred, int column) {
  deferred = false;
  const bool gsk = config_.dialect == Dialect::gsk;
  BlockWord* aw = gsk ? word('Q') : comma_word('A');
  if (aw == nullptr && !angle_start_.active) {
    return true;
  }
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  double degrees = 0.0;
  if (aw != nullptr) {
    aw->used = true;
    degrees = gsk ? aw->value / 1000.0 : aw->value;  // GSK Q in 0.001 degree (gsk A.6.11)
  }
  if (angle_start_.active && aw == nullptr && !given[a] && !given[b]) {
    return true;  // a block without motion between the two (counted by execute_block)
  }
  if (angle_start_.active) {
    // The second block of an angle pair: absolute end point and its own angle (spec L1388-1399,
    // gsk A.6.11 rule 6); the first block's end is the lines' intersection.
    const AxisWords wa = axis_words(axes[0]);
    const AxisWords wb = axis_words(axes[1]);
    if (aw == nullptr || wa.word == nullptr || wb.word == nullptr || wa.incremental ||
        wb.incremental) {
      return fail(alarm::kAngleProgramming,
                  "the block after an angle-only G01 (line " + std::to_string(angle_start_.line) +
                      ") must give the absolute end point of both axes and its own angle",
                  aw != nullptr ? aw->column : column);
    }
    path::Point2 corner;
    const path::Point2 start{angle_start_.from[a], angle_start_.from[b]};
    if (const path::PathResult e = path::angle_lines_corner(
            start, angle_start_.degrees, {target[a], target[b]}, degrees, corner)) {
      return fail(e->alarm, e->text, aw->column);
    }
    AxisVector first = machine_;
    first[a] = corner.a;
    first[b] = corner.b;
    Command& c = emit(Op::linear);
    c.to = first;
    c.line = angle_start_.line;
    c.feed = angle_start_.feed;
    c.feed_mode = modal_.feed_mode;
    machine_ = first;
    angle_start_ = AngleStart{};
    return true;
  }
  if (given[a] && given[b]) {
    if (gsk) {
      return true;  // both coordinates: an ordinary line, Q ignored (gsk A.6.11)
    }
    return fail(alarm::kAngleProgramming,
                ",A with both end coordinates: give one of them, or none for an angle pair",
                aw->column);
  }
  if (!given[a] && !given[b]) {
    // The angle only: the end comes with the next block (spec L1388 case 2).
    angle_start_ =
        AngleStart{true, machine_, degrees, line_ != nullptr ? line_->line : 0, modal_.feed, 0};
    deferred = true;
    return true;
  }
  path::Point2 end;
  const path::KnownAxis known = given[a] ? path::KnownAxis::a : path::KnownAxis::b;
  if (const path::PathResult e = path::line_end_from_angle(
          {machine_[a], machine_[b]}, degrees, known, given[a] ? target[a] : target[b], end)) {
    return fail(e->alarm, e->text, aw->column);
  }
  target[a] = end.a;
  target[b] = end.b;
  given[a] = true;
  given[b] = true;
  return true;
}

}  // namespace mcnc::interp
