#pragma once
// The look-ahead behind the interpreter's blocks. A move whose end depends on the moves after it
// waits here until they are known: a move with an automatic corner (,C ,R; GSK L D) until the
// next move, and every move under tool-nose radius compensation (G41/G42) until the next one
// gives the direction to offset its end by. The commands that follow a waiting move wait with
// it, so the program's order is kept; a read-ahead barrier releases everything first.
//
// Pure: the interpreter pushes its commands in program order and takes the ready ones.
#include "channel/interp/command.hpp"
#include "channel/interp/path/corner_insertion.hpp"
#include "channel/interp/path/nose_compensation.hpp"

#include <array>
#include <deque>
#include <optional>
#include <vector>

namespace mcnc::interp {

class BlockLookahead {
 public:
  struct Settings {
    // GSK: compensation may start on a G00 move (gsk A.6.22 rule 2); Dafeng: G00 start-up
    // blocks are not compensated (spec L3745), compensation starts on the first G01.
    bool rapid_startup = false;
  };

  BlockLookahead() = default;
  explicit BlockLookahead(Settings settings) : settings_(settings) {}

  // Where the program stands before its first command (machine coordinates).
  void reset(const AxisVector& position);
  // A move that did not need the look-ahead (nothing waited): where the next one starts.
  void passed(const AxisVector& position) {
    corner_position_ = position;
    comp_position_ = position;
  }
  // The channel axes of the plane the corners and the compensation work in, and the plane.
  void set_plane(std::array<int, 2> axes, Plane plane);

  // The next command in program order. Appends to `ready` what can no longer change. Alarms:
  // a corner or compensation that cannot be made (1147, 1150, 1151).
  path::PathResult push(Command c, std::vector<Command>& ready);
  // Nothing more comes before the channel executes what is ready (the program end): releases
  // everything; a corner still waiting for its next move is alarm 1147.
  path::PathResult flush(std::vector<Command>& ready);
  bool holding() const { return corner_held_.has_value() || !entries_.empty(); }
  // Whether it holds a move under normal direction control (G41.1/G42.1): until that leaves,
  // where the control leaves its axis is not known.
  bool holds_normal_direction() const;

 private:
  struct CornerHeld {
    Command move;
    path::Point2 from;
    std::vector<Command> after;  // commands between it and the next move
  };
  struct Entry {  // a move under compensation whose offset copy is not final yet
    int id = 0;
    Command move;
    std::vector<Command> generated;
    std::vector<Command> after;
  };

  path::Point2 plane_point(const AxisVector& v) const;
  static bool is_motion(Op op);
  path::PathResult corner_stage(Command c, std::vector<Command>& ready);
  path::PathResult compensation_stage(Command c, std::vector<Command>& ready);
  // Ends the compensation: with the G40 move `cancel_move` (from `from`), or without a move.
  path::PathResult end_compensation(const Command* cancel_move, std::vector<Command>& ready,
                                    path::Point2 from = {});
  void take(const path::PlanePath& moves);
  void release_before(int id, std::vector<Command>& ready);
  Command command_of(const Command& source, const path::PlaneMove& m) const;

  Settings settings_;
  std::array<int, 2> axes_{1, 0};
  Plane plane_ = Plane::zx;
  AxisVector corner_position_{};  // programmed end of the last move into the corner stage
  AxisVector comp_position_{};    // programmed end of the last move into the compensation
  std::optional<CornerHeld> corner_held_;
  path::NoseCompensation compensation_;
  Command::Compensation mode_ = Command::Compensation::off;
  double radius_ = 0.0;
  int tip_ = 0;
  std::deque<Entry> entries_;
  int next_id_ = 0;
};

}  // namespace mcnc::interp
