#pragma once
// G76, the multiple thread-cutting cycle of spec dafeng §2.5 L1763-1843 and gsk A.6.32: roughing
// passes of constant cut area (depth of pass n = first depth * sqrt(n), each at least the
// minimum depth) down to the thread height minus the finishing allowance, then the finishing
// passes at the full height, each pass infeeding along the flank of the tool angle, threading
// to the end with the chamfer-out, retracting and returning to the start point.
//
// Z (the first axis, a) is always the long axis; the thread runs from the start's a to end.a.
#include "channel/interp/path/plane_path.hpp"

#include <vector>

namespace mcnc::interp::cycles {

enum class ThreadInfeed : std::uint8_t {
  single_flank,   // every pass moves along one flank (J0, param 5035 = 0)
  alternating,    // left and right flank by turns (J3)
  radial,         // straight in along b (J1 read as "centre" when the dialect asks for it)
  leading_flank,  // every pass along the other flank, the one ahead (GSK G78 entry 1 or 2)
};

struct MultipleThread {
  path::Point2 end;               // X/U Z/W: the thread's root at its end (physical, b = radius)
  double taper = 0.0;             // R(i): b at the thread start minus b at its end (radius)
  double height = 0.0;            // P(k): thread height, > 0 (radius)
  double first_depth = 0.0;       // Q(d): depth of the first pass, > 0
  double min_depth = 0.0;         // Q(dmin) of the first block: smallest depth increment
  double finish_allowance = 0.0;  // R(d) of the first block
  int finish_passes = 1;          // m, 1-99 (0 is taken as 1)
  double chamfer = 0.0;           // r * lead / 10: pull-out length along a at the end; 0: none
  double tool_angle = 60.0;       // a, degrees (0-99)
  double lead = 0.0;              // F (or 25.4 / I), mm/rev along a
  double lead_change = 0.0;       // K (dafeng): per revolution
  int starts = 1;                 // L (dafeng): start angles 360 / starts apart
  ThreadInfeed infeed = ThreadInfeed::single_flank;
  // GSK G78 (gsk A.6.33): m = 0 makes every roughing pass first_depth deeper than the last
  // (constant-distance infeed) instead of the sqrt(n) schedule; J/K give the chamfer-out its
  // own rise along b (< 0: as far as `chamfer`, 45 degrees); `code` names the cycle in alarms.
  bool constant_depth = false;
  double chamfer_rise = -1.0;
  // GSK G78 E (decision 84): every pass screws in, its thread starting this far (radius)
  // outside the pass's depth and reaching it at 45 degrees, as far along a.
  double screw_in = 0.0;
  // Dafeng G76 PQ (decision 85): after every `chip_break` of thread along a, a roughing pass
  // lifts out of its chip to the depth of the pass before (the crest for the first) and goes
  // back in, each at 45 degrees on the thread; 0: none. Finishing passes do not break.
  double chip_break = 0.0;
  const char* code = "G76";
};

// `start` is the tool position at the cycle (point A); b must be outside the thread's crest on
// the side away from the root, at both ends of the thread. Each pass: rapid to the pass's infeed
// point, a `thread` move to the chamfer start, a `thread` move through the chamfer (out at 45
// degrees: `chamfer` along a and along b; its lead is the one reached there with lead_change),
// a rapid back to A's b, a rapid to A. Without a chamfer the first thread move ends at end.a.
// With several starts, each pass is repeated per start with start_angle 360 * s / starts.
// A screw-in makes the rapid end `screw_in` outside the infeed point and adds a first thread
// move from there to the pass's depth; a chip break is three thread moves in place of one:
// up, down, and on (only a break that ends before the chamfer start is made). Every thread
// move's lead is the lead along its longer axis (the one reached at its start with
// lead_change), so a move that rises more than it advances keeps the thread's lead along a.
//
// Infeed point of the pass at `depth` (t = tan(tool_angle / 2), along the cutting direction
// from A): single_flank depth * t, so that the tool's trailing flank stays on the finished
// thread's flank, whose bottom lies height * t ahead of A; alternating the same on even passes
// (0, 2, ...) and (2 * height - depth) * t, on the leading flank, on odd ones; radial 0. Its b
// lies `depth` below the crest on the root line (parallel to the taper).
//
// Alarms (nothing is appended): 1143 height, first depth or lead <= 0, first depth > height,
// finish_allowance >= height, a negative minimum depth, allowance or chamfer, finish_passes or
// tool_angle outside 0-99, starts < 1, end.a = start.a, A on or inside the thread, a pass whose
// infeed point (or the end of its screw-in) is not before the chamfer start, a negative screw-in
// or chip break, more than 20000 passes (all starts) or 100000 chip breaks; 1146 a lead that
// reaches 0 with lead_change.
path::PathResult expand_multiple_thread(path::Point2 start, const MultipleThread& cycle,
                                        path::PlanePath& out);

// The depth (radius, from the crest) of each roughing pass, the last one height -
// finish_allowance: dn = first_depth * sqrt(n), each increment (the first one too) at least
// min_depth, capped at the last. Exposed for the golden and property tests.
std::vector<double> thread_pass_depths(const MultipleThread& cycle);

}  // namespace mcnc::interp::cycles
