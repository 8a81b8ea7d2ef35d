// G40.1 / G41.1 / G42.1 normal direction control (spec dafeng L3799-3906): the rotary axis of
// param 5550 keeps the tool normal to the path in the plane, at 0 degrees along the plane's
// first axis and counter-clockwise positive (the second axis at +90 degrees).
#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

namespace {

constexpr double kDegrees = 180.0 / path::kPi;

// The direction (radians) in which move `c` from `from` starts in the plane of `axes`; none
// when it does not move in the plane.
std::optional<double> start_direction(const Command& c, const AxisVector& from,
                                      const std::array<int, 2>& axes) {
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  if (c.op == Op::arc) {
    const double ra = from[a] - c.center[0];
    const double rb = from[b] - c.center[1];
    return c.direction == ArcDirection::ccw ? std::atan2(ra, -rb) : std::atan2(-ra, rb);
  }
  const double da = c.to[a] - from[a];
  const double db = c.to[b] - from[b];
  if (std::hypot(da, db) < path::kLengthEpsilon) {
    return std::nullopt;
  }
  return std::atan2(db, da);
}

// `angle` moved by the multiple of 360 that brings it nearest `from`: the shortest turn.
double nearest_turn(double from, double angle) {
  return from + std::remainder(angle - from, 360.0);
}

}  // namespace

bool ProgramRun::run_normal_direction(GFunction f, int column) {
  const std::string code = f == GFunction::normal_off    ? "G40.1"
                           : f == GFunction::normal_left ? "G41.1"
                                                         : "G42.1";
  for (const BlockWord& w : words_) {
    if (w.column != column && !w.address.is('N')) {
      return fail(alarm::kMustBeAlone, code + " stands alone in its block (spec L3799-3906)",
                  w.column);
    }
  }
  if (f != GFunction::normal_off) {
    if (normal_axis_ < 0) {
      return fail(alarm::kNoPlaneAxis,
                  code +
                      " turns the rotary axis of normal direction control (param 5550, "
                      "`normal.axis`), which this channel does not have",
                  column);
    }
    if (frame_active()) {
      return fail(alarm::kFrameRestriction,
                  code + " is not available under G68.1 or G51.1: cancel them first", column);
    }
    if (compensation_ != Command::Compensation::off) {
      return fail(alarm::kNotInThisVersion,
                  code + " with tool-nose compensation (G41/G42) is not available yet: G40 first",
                  column);
    }
  }
  normal_side_ = f == GFunction::normal_off ? 0 : f == GFunction::normal_left ? 1 : -1;
  modal_codes_[19] = f == GFunction::normal_off ? 40.1 : f == GFunction::normal_left ? 41.1 : 42.1;
  return true;
}

bool ProgramRun::apply_normal_direction() {
  if (normal_side_ == 0 || out_.empty()) {
    return true;
  }
  if (compensation_ != Command::Compensation::off || interpolation_mode()) {
    return fail(compensation_ != Command::Compensation::off ? alarm::kNotInThisVersion
                                                            : alarm::kInterpolationModeRestriction,
                "normal direction control (G41.1/G42.1) does not go with tool-nose compensation "
                "or polar or cylindrical interpolation: G40.1 first",
                0);
  }
  const auto rot = static_cast<std::size_t>(normal_axis_);
  std::array<int, 2> axes = plane_axis_indices();
  if (axes[0] < 0 || axes[1] < 0) {
    return require_plane_axes(axes, 0);
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  // The block's commands start where the block found the machine, the axis at its angle.
  AxisVector at = block_start_;
  double angle = block_start_[rot];
  std::vector<Command> turned;
  turned.reserve(out_.size() * 2);
  for (const Command& c : out_) {
    if (!c.moves()) {
      turned.push_back(c);
      continue;
    }
    if (c.corner != Command::Corner::none) {
      return fail(alarm::kNotInThisVersion,
                  "corners (,C ,R) under normal direction control (G41.1/G42.1) are not "
                  "available yet: the axis would have to turn inside the corner",
                  0);
    }
    if (c.to[rot] != block_start_[rot]) {
      return fail(alarm::kWordNotAllowed,
                  std::string(1, config_.axes[rot].name) +
                      " is turned by normal direction control (G41.1/G42.1): G40.1 first",
                  0);
    }
    Command m = c;
    const std::optional<double> dir =
        c.op == Op::linear || c.op == Op::arc ? start_direction(c, at, axes) : std::nullopt;
    if (dir) {
      const double want = nearest_turn(angle, *dir * kDegrees + normal_side_ * 90.0);
      if (std::fabs(want - angle) > 1e-9) {
        // The control's inserted block `G01 C[computed] F[param 5551]` (L3862-3870).
        Command r = c;
        r.op = Op::linear;
        r.to = at;
        r.to[rot] = want;
        r.feed = config_.normal_feed;
        r.feed_mode = FeedMode::per_min;
        r.exact_stop = false;
        r.barrier = false;
        r.corner = Command::Corner::none;
        turned.push_back(r);
        angle = want;
      }
    }
    if (m.op == Op::arc) {
      // The axis turns with the arc: its sweep (and its full turns) in degrees.
      path::PlaneMove move;
      move.kind = path::MoveKind::arc;
      move.to = {c.to[a], c.to[b]};
      move.center = {c.center[0], c.center[1]};
      move.ccw = c.direction == ArcDirection::ccw;
      double sweep = path::arc_sweep({at[a], at[b]}, move);
      sweep += (sweep < 0.0 ? -1.0 : 1.0) * 2.0 * path::kPi * c.turns;
      angle += sweep * kDegrees;
    }
    m.to[rot] = angle;
    turned.push_back(m);
    at = m.to;
  }
  out_.swap(turned);
  machine_[rot] = angle;
  return true;
}

}  // namespace mcnc::interp
