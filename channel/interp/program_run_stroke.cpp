// G22 / G23, the stored stroke check 2 (spec dafeng L2393-2435, gsk A.6.17): the limits from the
// block or the parameters, and the check of every move before it leaves the interpreter.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>
#include <cstdio>

namespace mcnc::interp {

namespace {

// Format ①'s words of the - limits: I, J, K for X, Y, Z (L2394-2408).
char minus_word(char axis) {
  switch (axis) {
    case 'X':
      return 'I';
    case 'Y':
      return 'J';
    case 'Z':
      return 'K';
    default:
      return 0;
  }
}

std::string limit_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::string ProgramRun::stroke_limits_text() const {
  std::string out;
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    const double lo = stroke_zone_.minus[i];
    const double hi = stroke_zone_.plus[i];
    if (!std::isfinite(lo) && !std::isfinite(hi)) {
      continue;
    }
    const int axis = static_cast<int>(i);
    out += (out.empty() ? "" : ", ") + std::string(1, config_.axes[i].name) + " " +
           (std::isfinite(lo) ? limit_text(physical_to_data(axis, lo)) : "-inf") + ".." +
           (std::isfinite(hi) ? limit_text(physical_to_data(axis, hi)) : "+inf");
  }
  return out;
}

bool ProgramRun::run_stroke_check(GFunction f, int column) {
  if (f == GFunction::stroke_check_off) {
    stroke_on_ = false;
    modal_.codes[9] = 23;
    return true;
  }
  limits::StrokeZone zone = stroke_zone_;
  zone.inside_forbidden = config_.stroke_inside_forbidden;
  // Format ②: `G22 α P1` sets the + limit of α, `P2` its - limit (L2412-2419).
  int side = 0;
  if (BlockWord* p = word('P')) {
    p->used = true;
    if (p->value != 1.0 && p->value != 2.0) {
      return fail(alarm::kBadWordValue, "G22 P must be 1 (the + limit) or 2 (the - limit)",
                  p->column);
    }
    side = static_cast<int>(p->value);
  }
  bool any = false;
  const bool ok = for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    const char name = config_.axes[static_cast<std::size_t>(axis)].name;
    if (incremental) {
      return fail(alarm::kWordNotAllowed,
                  std::string("G22 takes absolute machine positions: ") + name + " instead of " +
                      w.address.first,
                  w.column);
    }
    const double v = data_to_physical(axis, scaled_axis_word(axis, w));
    (side == 2 ? zone.minus : zone.plus)[static_cast<std::size_t>(axis)] = v;
    any = true;
    return true;
  });
  if (!ok) {
    return false;
  }
  if (side == 0) {
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      const char m = minus_word(config_.axes[i].name);
      if (BlockWord* w = m != 0 ? word(m) : nullptr) {
        w->used = true;
        zone.minus[i] =
            data_to_physical(static_cast<int>(i), scaled_axis_word(static_cast<int>(i), *w));
        any = true;
      }
    }
  } else if (!any) {
    return fail(alarm::kBadWordValue, "G22 P1/P2 needs the axis whose limit it sets", column);
  }
  if (!any) {
    // No words: the parameters' limits (L2435: params 0512/0513; gsk №100/№101).
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      zone.minus[i] = config_.axes[i].stroke_minus;
      zone.plus[i] = config_.axes[i].stroke_plus;
    }
    if (zone.unlimited()) {
      return fail(alarm::kBadWordValue,
                  "G22 without limits takes the parameters' (0512/0513), and this channel has "
                  "none: give the limits in the block",
                  column);
    }
  }
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    if (zone.minus[i] >= zone.plus[i]) {
      const int axis = static_cast<int>(i);
      return fail(alarm::kBadWordValue,
                  std::string("G22: the - limit of ") + config_.axes[i].name + " (" +
                      limit_text(physical_to_data(axis, zone.minus[i])) +
                      ") is not below its + limit (" +
                      limit_text(physical_to_data(axis, zone.plus[i])) + ")",
                  column);
    }
  }
  if (limits::forbidden(zone, machine(), config_.axes.size())) {
    return fail(alarm::kStrokeLimit,
                "G22: the tool stands in the area it forbids; move it out before G22", column);
  }
  stroke_zone_ = zone;
  stroke_on_ = true;
  modal_.codes[9] = 22;
  return true;
}

void ProgramRun::check_stroke(std::size_t from) {
  for (std::size_t k = from; k < ready_.size(); ++k) {
    const Command& c = ready_[k];
    if (!c.moves()) {
      continue;
    }
    if (stroke_on_ && !alarm_ &&
        limits::enters(stroke_zone_, released_at_, c, config_.axes.size())) {
      // Before the move leaves: the block of the move is to blame, whatever block runs now.
      alarm_ = ProgramAlarm{alarm::kStrokeLimit,
                            "the move would enter the area G22 forbids (" + stroke_limits_text() +
                                (stroke_zone_.inside_forbidden ? ", inside" : ", outside") +
                                " forbidden; spec L2393-2435)",
                            c.file != nullptr ? *c.file : std::string(), c.line, 0};
      save_retained();
      return;
    }
    released_at_ = c.to;
  }
}

}  // namespace mcnc::interp
