// G98.1 / G99.1 automatic chip breaking (spec dafeng L2548-2604): the mode, the cutting moves it
// marks, and their split at the breaks as they leave (channel/interp/cycles/chip_breaking.hpp).
#include "channel/interp/cycles/chip_breaking.hpp"
#include "channel/interp/path/path_text.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

bool ProgramRun::run_chip_breaking(GFunction f, int column) {
  const bool per_min = f == GFunction::chip_break_per_min;
  const std::string code = per_min ? "G98.1" : "G99.1";
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  if (p == nullptr || q == nullptr) {
    return fail(alarm::kCycleWordMissing,
                code +
                    " needs P (the break in revolutions) and Q (revolutions of feed between "
                    "breaks)",
                column);
  }
  p->used = true;
  q->used = true;
  // Revolutions, counted as written (a decimal point or none: the same number of turns).
  if (!(q->value > 0.0) || q->value > 99999.0) {
    return fail(alarm::kBadWordValue, code + " Q must be more than 0 revolutions", q->column);
  }
  if (p->value == 0.0 || std::fabs(p->value) > 99999.0) {
    return fail(alarm::kBadWordValue,
                code + " P must not be 0: > 0 pauses the feed, < 0 feeds back (revolutions)",
                p->column);
  }
  // G98.1 is chip breaking in feed per minute, G99.1 per revolution: each selects its feed
  // mode, which a later G98/G99 leaves without chip breaking (decision 59).
  modal_.feed_mode = per_min ? FeedMode::per_min : FeedMode::per_rev;
  const bool b = config_.system == GCodeSystem::b;
  modal_.codes[5] = per_min ? (b ? 94 : 98) : (b ? 95 : 99);
  modal_.codes[13] = per_min ? 98.1 : 99.1;
  chip_ = ChipBreaking{true, q->value, p->value};
  chip_revs_ = 0.0;
  return true;
}

bool ProgramRun::mark_chip_breaking() {
  // In polar or cylindrical interpolation the spindle is a C axis that does not turn.
  if (!chip_.active || interpolation_mode()) {
    return true;
  }
  for (Command& c : out_) {
    if (c.op != Op::linear && c.op != Op::arc) {
      continue;
    }
    double per_rev = c.feed;  // mm of path per spindle revolution
    if (c.feed_mode == FeedMode::per_min && spindles_.css) {
      // G96: the speed at each point of the move follows its radius (decision 108).
      int x = -1;
      for (std::size_t i = 0; i < config_.axes.size(); ++i) {
        x = config_.axes[i].name == 'X' ? static_cast<int>(i) : x;
      }
      if (x < 0 || spindles_.clamp_rpm <= 0.0 || spindles_.surface <= 0.0) {
        return fail(alarm::kCycleWordMissing,
                    "G98.1 under G96 counts the revolutions of a speed that follows the X "
                    "radius: it needs X, a surface speed S and the speed limit G50 S (the speed "
                    "at the centre)",
                    0);
      }
      c.chip_surface = spindles_.surface;
      c.chip_max_rpm = spindles_.clamp_rpm;
      c.chip_radius_axis = x;
      c.chip_centre = offset_sum(x) + tool_offset(x);  // where the X radius is 0
      per_rev = c.feed / spindles_.clamp_rpm;
    } else if (c.feed_mode == FeedMode::per_min) {
      const double rpm = spindles_.reference_rpm();
      if (rpm <= 0.0) {
        return fail(alarm::kCycleWordMissing,
                    "G98.1 counts the spindle's revolutions: the spindle needs a speed S", 0);
      }
      per_rev = c.feed / rpm;
    }
    c.chip_rev_length = per_rev;
    c.chip_every = chip_.every;
    c.chip_break = chip_.brk;
  }
  return true;
}

void ProgramRun::split_chip_breaking(std::size_t from) {
  bool any = false;
  for (std::size_t k = from; k < ready_.size() && !any; ++k) {
    any = ready_[k].chip_rev_length > 0.0;
  }
  if (!any) {
    return;
  }
  std::vector<Command> split;
  split.reserve((ready_.size() - from) * 4);
  AxisVector at = from_inclined(released_at_);  // the moves are still Cartesian here
  for (std::size_t k = from; k < ready_.size(); ++k) {
    const Command& c = ready_[k];
    if (c.chip_rev_length > 0.0) {
      if (!cycles::split_for_chip_breaking(c, at, config_.axes.size(), chip_revs_, split)) {
        // Before the move leaves: nothing of it or after it goes out.
        alarm_ = ProgramAlarm{alarm::kCycleValue,
                              "chip breaking would break this move more than 100000 times (Q " +
                                  path::mm_text(c.chip_every) +
                                  " revolutions of a feed this small): raise the feed or Q",
                              c.file != nullptr ? *c.file : std::string(), c.line, 0};
        ready_.resize(from);
        return;
      }
    } else {
      split.push_back(c);
    }
    at = c.moves() ? c.to : at;
  }
  ready_.resize(from);
  ready_.insert(ready_.end(), split.begin(), split.end());
}

}  // namespace mcnc::interp
