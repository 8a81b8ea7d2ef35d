#include "channel/interp/cycles/hole_cycles.hpp"

#include "channel/interp/path/path_text.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcnc::interp::cycles {

namespace {

using path::mm_text;
using path::PathError;
using path::PathResult;
using Kind = HoleStep::Kind;

constexpr double kTolerance = 1e-9;  // mm
// A bound against a peck of a few microns over a deep hole that would make millions of steps.
constexpr int kMaxPecks = 100000;

const char* cycle_name(HoleKind kind) {
  switch (kind) {
    case HoleKind::tap:
      return "tapping cycle";
    case HoleKind::bore:
    case HoleKind::bore_stop:
    case HoleKind::fine_bore:
      return "boring cycle";
    case HoleKind::back_bore:
      return "back boring cycle";
    case HoleKind::drill:
      break;
  }
  return "drilling cycle";
}

PathResult value_error(const HoleCycle& c, const std::string& text) {
  return PathError{alarm::kCycleValue, std::string(cycle_name(c.kind)) + ": " + text, -1};
}

PathResult check_cycle(const HoleCycle& c) {
  if (c.peck < 0.0 || c.retract < 0.0 || c.clearance < 0.0 || c.dwell_s < 0.0 ||
      c.full_retract_depth < 0.0 || c.shift < 0.0) {
    return value_error(c, "amounts must not be negative: peck Q" + mm_text(c.peck) + ", retract " +
                              mm_text(c.retract) + ", clearance " + mm_text(c.clearance) +
                              ", dwell " + mm_text(c.dwell_s) + " s, full-retract depth " +
                              mm_text(c.full_retract_depth) + ", shift " + mm_text(c.shift));
  }
  if (std::fabs(c.bottom - c.r_level) <= kTolerance) {
    return value_error(c, "R-point " + mm_text(c.r_level) + " is at the bottom: no hole");
  }
  const double in = c.bottom > c.r_level ? 1.0 : -1.0;
  if (c.kind == HoleKind::back_bore) {
    // The tool enters from the far side: R, then the bottom, then the initial level.
    const double top = c.has_initial_level ? c.initial_level : c.initial;
    if (in * (top - c.bottom) < -kTolerance) {
      return value_error(c, "the initial level " + mm_text(top) + " must lie beyond the bottom " +
                                mm_text(c.bottom) + " seen from R " + mm_text(c.r_level));
    }
    return std::nullopt;
  }
  if (in * (c.initial - c.r_level) > kTolerance) {
    if (in * (c.initial - c.bottom) >= 0.0) {
      return value_error(c, "R-point " + mm_text(c.r_level) + " lies beyond the bottom " +
                                mm_text(c.bottom) + " seen from the initial level " +
                                mm_text(c.initial) + ": the hole would be drilled backwards");
    }
    return value_error(c, "initial level " + mm_text(c.initial) + " lies inside the hole from R " +
                              mm_text(c.r_level) + " to the bottom " + mm_text(c.bottom));
  }
  if (c.kind == HoleKind::tap && c.lead == 0.0) {
    return value_error(c, "lead F 0 for a tap");
  }
  return std::nullopt;
}

// The steps of one hole, each motion from where the previous one ended.
class HoleSteps {
 public:
  HoleSteps(double at, std::vector<HoleStep>& out) : at_(at), out_(out) {}

  void move(Kind kind, double to) {
    if (std::fabs(to - at_) > kTolerance) {
      out_.push_back(HoleStep{.kind = kind, .to = to});
      at_ = to;
    }
  }
  void dwell(double seconds) {
    if (seconds > 0.0) {
      out_.push_back(HoleStep{.kind = Kind::dwell, .seconds = seconds});
    }
  }
  void signal(Kind kind, int code = 0) { out_.push_back(HoleStep{.kind = kind, .code = code}); }
  void shift(double amount) { out_.push_back(HoleStep{.kind = Kind::shift, .to = amount}); }
  // G76/G87: the spindle stops oriented and the tool leaves the wall; then `then`; then back.
  template <typename F>
  void clear_of_wall(double amount, F&& then) {
    signal(Kind::orient);
    shift(amount);
    then();
    shift(0.0);
    signal(Kind::restore);
  }

  // Out of the hole to `to`: a tap backs out with the spindle reversed, a drill at rapid.
  void back_out(bool tapping, double to) {
    if (!tapping || std::fabs(to - at_) <= kTolerance) {
      move(Kind::rapid, to);
      return;
    }
    signal(Kind::reverse);
    move(Kind::tap, to);
    signal(Kind::restore);
  }

 private:
  double at_;
  std::vector<HoleStep>& out_;
};

PeckMode effective_peck_mode(const HoleCycle& c) {
  if ((c.kind != HoleKind::drill && c.kind != HoleKind::tap) || c.peck <= 0.0 ||
      (c.peck_mode == PeckMode::high_speed && c.retract <= 0.0)) {
    return PeckMode::none;
  }
  return c.peck_mode;
}

}  // namespace

path::PathResult expand_hole(const HoleCycle& cycle, std::vector<HoleStep>& out) {
  if (PathResult e = check_cycle(cycle)) {
    return e;
  }
  const double top = cycle.has_initial_level ? cycle.initial_level : cycle.initial;
  if (cycle.kind == HoleKind::back_bore) {
    HoleSteps s(cycle.initial, out);
    s.clear_of_wall(cycle.shift, [&] { s.move(Kind::rapid, cycle.r_level); });
    s.move(Kind::feed, cycle.bottom);
    s.dwell(cycle.dwell_s);
    s.clear_of_wall(cycle.shift, [&] { s.move(Kind::rapid, top); });
    return std::nullopt;
  }
  const PeckMode mode = effective_peck_mode(cycle);
  const double in = cycle.bottom > cycle.r_level ? 1.0 : -1.0;
  const double depth = std::fabs(cycle.bottom - cycle.r_level);
  const double pecks = mode == PeckMode::none ? 1.0 : std::ceil(depth / cycle.peck - 1e-9);
  if (pecks > kMaxPecks) {
    return value_error(cycle, "more than " + std::to_string(kMaxPecks) + " pecks of Q" +
                                  mm_text(cycle.peck) + " over " + mm_text(depth));
  }
  const bool tapping = cycle.kind == HoleKind::tap;
  const Kind cut = tapping ? Kind::tap : Kind::feed;
  auto level = [&](double d) { return cycle.r_level + in * d; };  // d: depth below R

  std::vector<HoleStep> steps;
  HoleSteps s(cycle.initial, steps);
  if (cycle.clamp_code != 0) {
    s.signal(Kind::aux, cycle.clamp_code);
  }
  s.move(Kind::rapid, cycle.r_level);
  const int count = static_cast<int>(pecks);
  double since_full = 0.0;  // .7: depth drilled since the last full retract
  double reached = 0.0;
  for (int p = 1; p <= count; ++p) {
    const double next = p == count ? depth : p * cycle.peck;
    s.move(cut, level(next));
    since_full += next - reached;
    reached = next;
    if (p == count) {
      break;
    }
    const bool full =
        mode == PeckMode::deep ||
        (mode == PeckMode::high_speed_deep && since_full >= cycle.full_retract_depth - kTolerance);
    if (!full) {
      s.back_out(tapping, level(reached - std::min(cycle.retract, reached)));
      continue;
    }
    since_full = 0.0;
    s.back_out(tapping, cycle.r_level);
    if (!tapping) {
      s.move(Kind::rapid, level(reached - std::min(cycle.clearance, reached)));
    }
  }
  s.dwell(cycle.dwell_s);
  const double exit = cycle.return_to_initial ? top : cycle.r_level;
  if (cycle.kind == HoleKind::bore) {
    s.move(Kind::feed, cycle.r_level);
  } else if (tapping) {
    s.back_out(true, cycle.r_level);
  }
  if (cycle.kind == HoleKind::fine_bore) {
    s.clear_of_wall(cycle.shift, [&] { s.move(Kind::rapid, exit); });
  } else if (cycle.kind == HoleKind::bore_stop) {
    s.signal(Kind::spindle_stop);
    s.move(Kind::rapid, exit);
    s.signal(Kind::restore);
  }
  s.move(Kind::rapid, exit);
  if (cycle.clamp_code != 0) {
    s.signal(Kind::aux, cycle.clamp_code + 1);
  }
  out.insert(out.end(), steps.begin(), steps.end());
  return std::nullopt;
}

}  // namespace mcnc::interp::cycles
