#pragma once
// Tool-nose radius compensation, G40/G41/G42 (spec dafeng §2.8 L3670-3798, gsk A.6.22): the
// programmed path of the imaginary tool tip is turned into the path that keeps the nose circle
// tangent to the programmed contour, on its left (G41) or right (G42) seen along the direction
// of travel, and shifted back by the tip direction so that the output is again a path of the
// imaginary tip (tip 0 and 9: of the nose centre).
//
// Corners: an inside corner ends both offset elements at their intersection; an outside corner
// (the path turns away from the compensation side) keeps both elements whole and joins them with
// an arc of the nose radius about the corner (the FANUC type C corner). Start-up (the first
// move after G41/G42) goes from the programmed start point to the offset start of the next
// element; cancel (G40 with a move) from the offset end of the last element to the programmed
// end point. An arc's end point that is off its circle by less than the arc tolerance is
// accepted as on it.
//
// Streaming: the interpreter pushes programmed moves one at a time; a move becomes final when
// the next one is known, so the class holds one move back. Pure, no allocation beyond `out`.
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::path {

enum class CompensationSide : std::uint8_t { left, right };  // G41, G42

// Where the imaginary tip lies relative to the nose centre, scaled by the radius: the FANUC
// lathe numbering (neither spec draws it), seen in G18 with Z (a) to the right and X (b) up:
//     2 6 1        1 (+a,+b)  2 (-a,+b)  3 (-a,-b): OD turning  4 (+a,-b)
//     7 0 5        5 (+a, 0)  6 ( 0,+b)  7 (-a, 0)  8 ( 0,-b)
//     3 8 4        0 and 9: the centre (0, 0).
Point2 tip_offset(int tip, double radius);

class NoseCompensation {
 public:
  // Starts compensating at `position` (the programmed point where the start-up move begins).
  // A radius of 0 passes moves through unchanged (but still applies the corner logic trivially).
  void start(Point2 position, CompensationSide side, double radius, int tip);
  bool active() const { return active_; }
  bool holding() const { return holding_; }

  // The next programmed move (rapid, feed or arc; a start-up move must not be an arc: 1151).
  // Appends the moves that became final to `out`. Alarms: 1150 the offset path cannot be made
  // (an arc whose radius is smaller than the nose radius on its inside, a move shorter than
  // needed so that the path would go backwards), 1151 an arc as the start-up move.
  PathResult push(const PlaneMove& programmed, PlanePath& out);

  // No further move will come before a stop (a read-ahead barrier, a block that must not be
  // looked past): finishes the held move with its end offset normal to it. Compensation stays
  // on; the next push starts from that offset point.
  void flush(PlanePath& out);

  // G40 with a move: finishes the held move (offset normal to its end) and appends the cancel
  // move to the programmed end point. Without a move (`programmed` == nullptr) the held move is
  // flushed and the next programmed move starts from the offset point. Compensation ends.
  PathResult cancel(const PlaneMove* programmed, PlanePath& out);

 private:
  // Appends `programmed` with its end (and centre) moved to the nose-centre point `nose_to`
  // (`nose_center`) plus the tip offset.
  void emit(const PlaneMove& programmed, Point2 nose_to, Point2 nose_center, PlanePath& out) const;
  // Appends the held move's offset copy ending at `nose_to`, `end_trim` mm before its offset end
  // (left out when trimmed to nothing).
  void emit_held(Point2 nose_to, double end_trim, PlanePath& out) const;
  // Appends an arc of the nose radius about the programmed `corner` to `nose_to`.
  void emit_corner_arc(Point2 corner, Point2 nose_to, double feed, PlanePath& out);
  void hold(const PlaneMove& programmed);
  // Finishes the held move at its corner with `programmed` (inside: intersection, outside:
  // corner arc); `next_start_trim` = how far along its offset `programmed` then starts.
  PathResult join_corner(const PlaneMove& programmed, PlanePath& out, double& next_start_trim);
  // Joins the flushed point to the offset start of `programmed`.
  void join_after_flush(const PlaneMove& programmed, PlanePath& out);

  bool active_ = false;
  bool holding_ = false;
  bool started_ = false;  // the start-up move has been made (or flushed)
  CompensationSide side_ = CompensationSide::left;
  double radius_ = 0.0;
  int tip_ = 0;
  Point2 programmed_at_;  // programmed end of the last pushed move
  Point2 offset_at_;      // nose-centre position reached by the output so far
  PlaneMove held_;        // the programmed move not yet final
  Point2 held_from_;      // its programmed start
  double held_start_trim_ = 0.0;  // mm of the held move's offset cut off at its start
  int last_source_ = -1;          // source of the last finished move (for a corner arc)
};

}  // namespace mcnc::interp::path
