// Milling machines of issue 24 run end to end in lockstep: the tool tip, rebuilt from the axis
// nodes' commanded positions of each cycle, lies on the programmed contour.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

using namespace mcnc::test;

namespace {

using Trace = std::vector<nlohmann::json>;

struct Point {
  double x = 0.0;
  double y = 0.0;
};

double distance(Point a, Point b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

// Distance from p to the segment a-b.
double to_segment(Point p, Point a, Point b) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  const double t =
      len2 == 0.0 ? 0.0 : std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0);
  return distance(p, {a.x + t * dx, a.y + t * dy});
}

// Distance from p to the polyline through `corners`.
double to_polyline(Point p, const std::vector<Point>& corners) {
  double best = INFINITY;
  for (std::size_t i = 1; i < corners.size(); ++i) {
    best = std::min(best, to_segment(p, corners[i - 1], corners[i]));
  }
  return best;
}

// Every axis node's commanded position per cycle (the trace samples every cycle): cycle ->
// axis -> cmd.
std::map<std::uint64_t, std::map<std::string, double>> commanded(const Trace& t) {
  std::map<std::uint64_t, std::map<std::string, double>> out;
  for (const auto& e : t) {
    if (e["ev"] == "pos" && !e["src"].get<std::string>().starts_with("CH")) {
      out[e["cycle"].get<std::uint64_t>()][e["src"].get<std::string>()] = e["cmd"].get<double>();
    }
  }
  return out;
}

std::uint64_t block_start(const Trace& t, const std::string& ch, int line) {
  for (const auto& e : events(t, "block", ch)) {
    if (e["line"] == line) {
      return e["cycle"].get<std::uint64_t>();
    }
  }
  ADD_FAILURE() << "no block on line " << line << " of " << ch;
  return 0;
}

// The owners of `axis` in the order they had it ("" while released), and the cycle of each.
std::vector<std::pair<std::uint64_t, std::string>> owner_changes(const Trace& t,
                                                                 const std::string& axis) {
  std::vector<std::pair<std::uint64_t, std::string>> out;
  for (const auto& e : events(t, "owner", axis)) {
    out.emplace_back(e["cycle"].get<std::uint64_t>(),
                     e["owner"].is_null() ? "" : e["owner"].get<std::string>());
  }
  return out;
}

// Runs the programs (channel -> source tree path) on `machine` with `mcnc run`, every axis
// sampled every cycle; each channel must reach its M30 without an alarm (else the test fails).
Trace run_to_m30(const TestMachine& machine, const std::map<std::string, std::string>& programs) {
  const std::string trace = machine.file("trace.jsonl");
  std::vector<std::string> argv{bin("mcnc"),         "run", machine.path(), "--trace", trace,
                                "--trace-pos-every", "1"};
  for (const auto& [channel, file] : programs) {
    argv.insert(argv.end(), {"--program", channel + "=" + source(file)});
  }
  const RunResult r = run(argv, -1, std::chrono::seconds(300));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const Trace t = read_trace(trace);
  if (t.empty()) {
    ADD_FAILURE() << "no trace";
    return t;
  }
  EXPECT_TRUE(events(t, "alarm").empty()) << r.out << r.err;
  for (const auto& [channel, file] : programs) {
    EXPECT_EQ(t.back()["channels"][channel]["end"], 30) << channel;
  }
  return t;
}

constexpr double kDegree = std::numbers::pi / 180.0;
// The polar steps keep 1 um, the blends between them and at the corners path_tolerance (1 um);
// the trace prints 1e-6.
constexpr double kOnContour = 0.0025;

}  // namespace

// launch/machines/mill_turn.yaml: the upper turret mills a square and a hexagon on the face in
// polar interpolation (G12.1, the hexagon by polar coordinates under G16), lends the part's C to
// the lower turret (G140/G141), takes it back and mills a slot with a half circle on the diameter
// in cylindrical interpolation (G07.1).
TEST(MillTurn, PolarAndCylindricalMillingWithTheCAxisLentBetween) {
  TestMachine machine("mill_turn.yaml", 200);
  const Trace t = run_to_m30(machine, {{"CH1", "launch/programs/mill_turn_ch1.nc"},
                                       {"CH2", "launch/programs/mill_turn_ch2.nc"}});
  ASSERT_FALSE(HasFailure());
  const auto at = commanded(t);

  // The driven tool turns.
  ASSERT_FALSE(events(t, "spindle", "CH1").empty());
  EXPECT_DOUBLE_EQ(events(t, "spindle", "CH1").front()["rpm"].get<double>(), 2000.0);

  // G12.1 (lines 7-23): the tip at radius X1 and angle C1 (0 where G12.1 found C) goes around
  // the square of side 16 from (20, 0) and back (format 1), then under G16 (format 2) around
  // the hexagon of radius 12 given by radius and angle, and back; Z1 at the depth.
  std::vector<Point> path{{20, 0}, {8, 0}, {8, 8}, {-8, 8}, {-8, -8}, {8, -8}, {8, 0}, {20, 0}};
  for (int k = 0; k <= 6; ++k) {
    path.push_back({12.0 * std::cos(60.0 * k * kDegree), 12.0 * std::sin(60.0 * k * kDegree)});
  }
  path.push_back({20, 0});
  std::vector<double> nearest(path.size(), INFINITY);
  std::size_t samples = 0;
  double worst = 0.0;
  for (auto it = at.lower_bound(block_start(t, "CH1", 7));
       it != at.end() && it->first < block_start(t, "CH1", 25); ++it) {
    const auto& axes = it->second;
    ASSERT_TRUE(axes.contains("X1") && axes.contains("C1") && axes.contains("Z1"));
    const Point tip{axes.at("X1") * std::cos(axes.at("C1") * kDegree),
                    axes.at("X1") * std::sin(axes.at("C1") * kDegree)};
    worst = std::max(worst, to_polyline(tip, path));
    EXPECT_NEAR(axes.at("Z1"), -2.0, 1e-6);
    for (std::size_t i = 0; i < path.size(); ++i) {
      nearest[i] = std::min(nearest[i], distance(tip, path[i]));
    }
    ++samples;
  }
  EXPECT_GT(samples, 200u);
  EXPECT_LE(worst, kOnContour);
  for (std::size_t i = 0; i < path.size(); ++i) {
    EXPECT_LE(nearest[i], 0.005) << "corner " << i;
  }
  // C1: CH1's, released, CH2's, released, CH1's again. The square and the hexagon went once
  // round each, counter-clockwise, so CH1 lends C at 720; CH2 turns it to 135, where CH1 takes
  // it back.
  const auto owners = owner_changes(t, "C1");
  std::vector<std::string> sequence;
  for (const auto& [cycle, owner] : owners) {
    sequence.push_back(owner);
  }
  ASSERT_EQ(sequence, (std::vector<std::string>{"CH1", "", "CH2", "", "CH1"}));
  const std::uint64_t lent = owners[1].first;
  const std::uint64_t to_ch2 = owners[2].first;
  const std::uint64_t let_go = owners[3].first;
  const std::uint64_t back = owners[4].first;
  EXPECT_NEAR(at.at(lent).at("C1"), 720.0, 1e-6);
  EXPECT_NEAR(at.at(to_ch2).at("C1"), 720.0, 1e-6);
  EXPECT_NEAR(at.at(let_go).at("C1"), 135.0, 1e-6);
  EXPECT_NEAR(at.at(back).at("C1"), 135.0, 1e-6);
  EXPECT_GT(to_ch2, lent);
  EXPECT_GT(block_start(t, "CH1", 30), back);  // G00 C0 after the take-over

  // G07.1 C20 (lines 35-37): on the cylinder of radius 20 unrolled (u = C x 20 in mm, Z), the
  // tip goes along Z-5 to C90, on a half circle of radius 10 through u(90) + 10 (G02 in the
  // plane C-Z) to Z-25, and back to C0, at the slot's depth (X1 the radius 18). The plunge
  // before (X1 from 22) and the retract after blend into it: the path is checked in (u, Z, X1).
  const double u90 = 90.0 * kDegree * 20.0;
  const Point centre{u90, -15.0};
  std::size_t on_cylinder = 0;
  double worst_cylinder = 0.0;
  double farthest_u = -INFINITY;
  double to_end = INFINITY;
  for (auto it = at.lower_bound(block_start(t, "CH1", 35));
       it != at.end() && it->first < block_start(t, "CH1", 40); ++it) {
    const auto& axes = it->second;
    const Point tip{axes.at("C1") * kDegree * 20.0, axes.at("Z1")};
    const double depth = axes.at("X1") - 18.0;
    double in_slot = std::min(to_segment(tip, {0.0, -5.0}, {u90, -5.0}),
                              to_segment(tip, {u90, -25.0}, {0.0, -25.0}));
    if (tip.x >= u90) {
      in_slot = std::min(in_slot, std::abs(distance(tip, centre) - 10.0));
    }
    double d = std::hypot(in_slot, depth);
    if (depth >= 0.0) {  // on the plunge or the retract, at u = 0
      d = std::min({d, distance(tip, {0.0, -5.0}), distance(tip, {0.0, -25.0})});
    }
    worst_cylinder = std::max(worst_cylinder, d);
    farthest_u = std::max(farthest_u, tip.x);
    to_end = std::min(to_end, std::hypot(distance(tip, {0.0, -25.0}), depth));
    ++on_cylinder;
  }
  EXPECT_GT(on_cylinder, 200u);
  EXPECT_LE(worst_cylinder, kOnContour);
  EXPECT_NEAR(farthest_u, u90 + 10.0, kOnContour);
  EXPECT_LE(to_end, kOnContour);
}

namespace {

// Distance from p to the arc from `a` to `b` about `centre`, clockwise.
double to_clockwise_arc(Point p, Point a, Point b, Point centre) {
  const auto angle = [&](Point q) { return std::atan2(q.y - centre.y, q.x - centre.x); };
  // Clockwise from a: how far p and b lie, in [0, 2 pi).
  const auto sweep = [&](Point q) {
    const double s = angle(a) - angle(q);
    return s < 0.0 ? s + 2.0 * std::numbers::pi : s;
  };
  if (sweep(p) <= sweep(b)) {
    return std::abs(distance(p, centre) - distance(a, centre));
  }
  return std::min(distance(p, a), distance(p, b));
}

}  // namespace

// launch/machines/mill_cell.yaml: the cell's three-axis mill (fanuc-mill) cuts round a contour
// with G41 D1 (radius 5) under G43 H1 (length 100), then drills two holes by G81 in G99 and one
// by G83 in G98 with pecks of 4, while the lathe beside it turns; both meet at the end.
TEST(MillCell, ContourUnderCutterAndLengthCompensationThenDrillingCycles) {
  TestMachine machine("mill_cell.yaml", 201);
  const Trace t = run_to_m30(machine, {{"CH1", "launch/programs/mill_cell_lathe.nc"},
                                       {"CH2", "launch/programs/mill_cell_mill.nc"}});
  ASSERT_FALSE(HasFailure());
  const auto at = commanded(t);

  // The contour (lines 10-14): the cutter's centre keeps 5 mm outside the square with its
  // corner rounded by the G02 of radius 10, at Z-3 + H1's 100.
  const auto to_contour = [](Point p) {
    return std::min({to_polyline(p, {{0, 0}, {0, 40}, {30, 40}}),
                     to_clockwise_arc(p, {30, 40}, {40, 30}, {30, 30}),
                     to_polyline(p, {{40, 30}, {40, 0}, {0, 0}})});
  };
  std::size_t samples = 0;
  std::size_t inside = 0;  // G41 on a clockwise contour: the cutter stays outside
  double worst = 0.0;
  double top = -INFINITY;
  double right = -INFINITY;
  for (auto it = at.lower_bound(block_start(t, "CH2", 10));
       it != at.end() && it->first < block_start(t, "CH2", 15); ++it) {
    const Point centre{it->second.at("X2"), it->second.at("Y2")};
    // The start-up move (to the first side's offset start) and the G40 move out blend into the
    // contour at its ends.
    worst = std::max(worst, std::min({std::abs(to_contour(centre) - 5.0),
                                      to_segment(centre, {-20, -20}, {-5, 0}),
                                      to_segment(centre, {0, -5}, {-20, -20})}));
    inside += centre.x >= 0.0 && centre.x <= 40.0 && centre.y >= 0.0 && centre.y <= 40.0 ? 1 : 0;
    EXPECT_NEAR(it->second.at("Z2"), 97.0, 1e-6);
    top = std::max(top, centre.y);
    right = std::max(right, centre.x);
    ++samples;
  }
  EXPECT_GT(samples, 200u);
  EXPECT_LE(worst, kOnContour);
  EXPECT_EQ(inside, 0u);
  EXPECT_NEAR(top, 45.0, 1e-6);    // the side Y40 and the corner arcs round (0, 40)
  EXPECT_NEAR(right, 45.0, 1e-6);  // the G02's offset arc and the side X40

  // The holes (lines 17-19): below R (Z2, 102 with H1) the tool is only ever on a hole's centre.
  const double r_level = 102.0;
  const double initial = 110.0;
  const std::vector<Point> holes{{10, 10}, {30, 10}, {20, 20}};
  std::vector<double> deepest(holes.size(), INFINITY);
  std::vector<double> peck_bottoms;  // the G83 hole's local lowest points
  double previous_z = initial;
  bool going_down = true;
  double between_holes_highest = -INFINITY;  // G99: the moves from hole to hole
  for (auto it = at.lower_bound(block_start(t, "CH2", 17));
       it != at.end() && it->first < block_start(t, "CH2", 21); ++it) {
    const Point xy{it->second.at("X2"), it->second.at("Y2")};
    const double z = it->second.at("Z2");
    std::size_t hole = holes.size();
    for (std::size_t i = 0; i < holes.size(); ++i) {
      hole = distance(xy, holes[i]) < 1e-6 ? i : hole;
    }
    if (z < r_level - 1e-6) {
      ASSERT_LT(hole, holes.size()) << "below R at " << xy.x << " " << xy.y;
      deepest[hole] = std::min(deepest[hole], z);
    }
    if (hole == holes.size() && xy.x > 10.0 + 1e-6) {  // travelling between the holes
      between_holes_highest = std::max(between_holes_highest, z);
    }
    if (hole == 2) {
      if (going_down && z > previous_z) {
        peck_bottoms.push_back(previous_z);
      }
      going_down = z < previous_z || (going_down && z == previous_z);
    }
    previous_z = z;
  }
  EXPECT_NEAR(deepest[0], 95.0, 1e-6);  // G81 Z-5
  EXPECT_NEAR(deepest[1], 95.0, 1e-6);
  EXPECT_NEAR(deepest[2], 88.0, 1e-6);                // G83 Z-12
  EXPECT_NEAR(between_holes_highest, r_level, 1e-6);  // G99: from hole to hole at R
  ASSERT_EQ(peck_bottoms.size(), 4u);                 // Q4 from R2 down to Z-12
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(peck_bottoms[i], 98.0 - 4.0 * static_cast<double>(i), 1e-6);
  }
  EXPECT_NEAR(peck_bottoms[3], 88.0, 1e-6);
  // G98: after the G83 hole back to the initial level (Z10), where G80 leaves the tool.
  EXPECT_NEAR(std::prev(at.lower_bound(block_start(t, "CH2", 21)))->second.at("Z2"), initial, 1e-6);

  // The lathe turned beside it (X50 is the radius 25), and both ended at the mark.
  bool turned = false;
  for (const auto& [cycle, axes] : at) {
    turned = turned || (axes.contains("X1") && axes.contains("Z1") &&
                        std::abs(axes.at("X1") - 25.0) < 1e-6 && axes.at("Z1") < -19.999);
  }
  EXPECT_TRUE(turned);
}
