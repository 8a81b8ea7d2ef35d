#pragma once
// The single cycles G90 (OD/ID turning), G94 (facing) and G92 (threading) of spec dafeng §2.5
// L2199-2376 and gsk A.6.26-A.6.28 (G77/G79/G78 in G-code system B): four moves from the start
// point A and back to it — in to the cutting start, the cut to the programmed end point, out
// to the start's level, back to A.
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::cycles {

enum class SingleCycleKind : std::uint8_t {
  turning,  // G90: cut along a (Z) at the end point's b
  facing,   // G94: cut along b (X) at the end point's a
  thread,   // G92: thread along a, rapid out
};

struct SingleCycle {
  SingleCycleKind kind = SingleCycleKind::turning;
  path::Point2 end;  // X/U Z/W: where the cut ends (physical, b a radius)
  // R: the taper. turning/thread: b at the cutting start minus b at the end (radius); facing:
  // a at the cutting start minus a at the end.
  double taper = 0.0;
  double feed = 0.0;  // turning, facing
  // thread: lead along a, its change per revolution, the first start's spindle angle, the
  // number of starts (each 360 / starts further), and the chamfer-out: over the last
  // `chamfer_a` of the thread (along a) the tool rises `chamfer_b` (along b, towards the
  // start's side); 0 and 0: the thread runs to the end point and the tool leaves at rapid.
  double lead = 0.0;
  double lead_change = 0.0;
  double start_angle = 0.0;
  int starts = 1;
  double chamfer_a = 0.0;
  double chamfer_b = 0.0;
};

// The moves of the cycle from `start` (the tool position, point A): rapid to the cutting start,
// feed (thread) to the end, feed (thread cycle: rapid) out to the start's level, rapid to A. A
// thread with several starts repeats the four moves per start. Alarms: 1143 a chamfer longer
// than the thread, starts < 1; 1146 a lead <= 0 or one that reaches 0 with lead_change.
path::PathResult expand_single_cycle(path::Point2 start, const SingleCycle& cycle,
                                     path::PlanePath& out);

}  // namespace mcnc::interp::cycles
