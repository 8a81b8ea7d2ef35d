// G40.1 / G41.1 / G42.1 normal direction control (spec dafeng L3799-3906): the rotary axis of
// param 5550 keeps the tool normal to the path in the plane, at 0 degrees along the plane's
// first axis and counter-clockwise positive (the second axis at +90 degrees).
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <string>

namespace mcnc::interp {

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
  }
  // G40.1 while the look-ahead still holds moves of the control: where they leave the axis is
  // known once they leave (sync_normal_direction).
  normal_pending_ = f == GFunction::normal_off && lookahead_.holds_normal_direction();
  normal_side_ = f == GFunction::normal_off ? 0 : f == GFunction::normal_left ? 1 : -1;
  modal_.codes[19] = f == GFunction::normal_off ? 40.1 : f == GFunction::normal_left ? 41.1 : 42.1;
  return true;
}

bool ProgramRun::tag_normal_direction() {
  if (normal_axis_ < 0 || (normal_side_ == 0 && !normal_pending_) || out_.empty()) {
    return true;
  }
  const auto rot = static_cast<std::size_t>(normal_axis_);
  const std::string name(1, config_.axes[rot].name);
  if (normal_side_ == 0) {
    // After G40.1, before the control's last moves left the look-ahead: the axis stays where
    // they leave it, which the program cannot know yet.
    for (Command& c : out_) {
      if (!c.moves()) {
        continue;
      }
      if (c.to[rot] != block_start_[rot] || axis_words(normal_axis_).word != nullptr) {
        return fail(alarm::kWordNotAllowed,
                    name +
                        " stands where normal direction control's last moves leave it, known "
                        "once the compensated path after G40.1 is made: program it after G40 "
                        "or after the next move in the plane",
                    0);
      }
      c.normal = Command::Normal::hold;
    }
    return true;
  }
  if (interpolation_mode()) {
    return fail(alarm::kInterpolationModeRestriction,
                "normal direction control (G41.1/G42.1) does not go with polar or cylindrical "
                "interpolation: G40.1 first",
                0);
  }
  std::array<int, 2> axes = plane_axis_indices();
  if (axes[0] < 0 || axes[1] < 0) {
    return require_plane_axes(axes, 0);
  }
  for (Command& c : out_) {
    if (!c.moves()) {
      continue;
    }
    if (c.to[rot] != block_start_[rot] || axis_words(normal_axis_).word != nullptr) {
      return fail(alarm::kWordNotAllowed,
                  name + " is turned by normal direction control (G41.1/G42.1): G40.1 first", 0);
    }
    c.normal = normal_side_ > 0 ? Command::Normal::left : Command::Normal::right;
    c.normal_plane = axes;
  }
  return true;
}

void ProgramRun::turn_normal_direction(std::size_t from) {
  if (normal_axis_ < 0) {
    return;
  }
  normal_.turn(ready_, from);
  if ((normal_side_ != 0 || normal_pending_) && !lookahead_.holds_normal_direction()) {
    // Every move of the control has left: the program knows where the axis stands.
    machine_[static_cast<std::size_t>(normal_axis_)] = normal_.angle();
    normal_pending_ = false;
  }
}

}  // namespace mcnc::interp
