#pragma once
// G41.1 / G42.1 normal direction control on the path as it leaves the look-ahead (spec dafeng
// L3799-3906): the rotary axis of param 5550 points the tool at the travel direction + 90
// degrees (left, G41.1) or - 90 (right, G42.1) in the plane, 0 degrees along the plane's first
// axis and counter-clockwise positive. It works on the released commands, after the corners
// (,C ,R) and the tool-nose or cutter compensation (G41/G42) made their moves, so the axis
// follows the path the tool takes (L3880: with compensation, the offset path).
//
// What it promises for every move tagged left or right (Command::normal):
//  - it starts pointing at the normal of its start direction: where the axis stands elsewhere, a
//    block of the axis alone (`G01 C[angle] F[param 5551]`, L3862-3870) turns it first by the
//    shorter way (at most 180 degrees), at the point where the move starts. A turn below
//    kFoldedTurn degrees (the rounding of a tangent joint) is made during the move instead;
//  - a line keeps the angle; an arc turns the axis with it by its sweep, so it ends pointing at
//    the normal of its end direction;
//  - a move without travel in the plane, a rapid or a thread leaves the angle.
// A move tagged `hold` takes the angle where the control left it (the interpreter did not know
// it yet); an untagged move sets it (what the program commands the axis). Pure and deterministic.
#include "channel/interp/command.hpp"

#include <cstddef>
#include <vector>

namespace mcnc::interp {

class NormalDirection {
 public:
  // Degrees: a turn at a joint up to this size is made during the move that follows.
  static constexpr double kFoldedTurn = 1e-6;

  struct Settings {
    int axis = -1;         // the rotary axis (channel index); -1: the channel has none
    double feed = 3600.0;  // the inserted turns' feed, degrees per minute (param 5551)
  };

  NormalDirection() = default;
  explicit NormalDirection(Settings settings) : settings_(settings) {}

  // Where the machine stands: the next move starts there, the axis at its angle.
  void reset(const AxisVector& position);
  // Turns the commands list[from..] in place, in order, inserting the turns before the moves.
  void turn(std::vector<Command>& list, std::size_t from);
  // The axis's angle after the last command turned (or the reset).
  double angle() const { return angle_; }

 private:
  // The inserted turn to `to_angle` at the point where `move` starts.
  Command turn_before(const Command& move, double to_angle) const;

  Settings settings_;
  AxisVector at_{};  // where the last move ended
  double angle_ = 0.0;
};

}  // namespace mcnc::interp
