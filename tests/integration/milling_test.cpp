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

// launch/machines/mill_turn.yaml: the upper turret mills a square on the face in polar
// interpolation (G12.1), lends the part's C to the lower turret (G140/G141), takes it back and
// mills a slot with a half circle on the diameter in cylindrical interpolation (G07.1).
TEST(MillTurn, PolarAndCylindricalMillingWithTheCAxisLentBetween) {
  TestMachine machine("mill_turn.yaml", 200);
  const Trace t = run_to_m30(machine, {{"CH1", "launch/programs/mill_turn_ch1.nc"},
                                       {"CH2", "launch/programs/mill_turn_ch2.nc"}});
  ASSERT_FALSE(HasFailure());
  const auto at = commanded(t);

  // The driven tool turns.
  ASSERT_FALSE(events(t, "spindle", "CH1").empty());
  EXPECT_DOUBLE_EQ(events(t, "spindle", "CH1").front()["rpm"].get<double>(), 2000.0);

  // G12.1 (lines 7-13): the tip at radius X1 and angle C1 (0 where G12.1 found C) goes around
  // the square of side 16 from (20, 0) and back, Z1 at the depth.
  const std::vector<Point> square{{20, 0},  {8, 0},  {8, 8}, {-8, 8},
                                  {-8, -8}, {8, -8}, {8, 0}, {20, 0}};
  std::vector<double> nearest(square.size(), INFINITY);
  std::size_t samples = 0;
  double worst = 0.0;
  for (auto it = at.lower_bound(block_start(t, "CH1", 7));
       it != at.end() && it->first < block_start(t, "CH1", 15); ++it) {
    const auto& axes = it->second;
    ASSERT_TRUE(axes.contains("X1") && axes.contains("C1") && axes.contains("Z1"));
    const Point tip{axes.at("X1") * std::cos(axes.at("C1") * kDegree),
                    axes.at("X1") * std::sin(axes.at("C1") * kDegree)};
    worst = std::max(worst, to_polyline(tip, square));
    EXPECT_NEAR(axes.at("Z1"), -2.0, 1e-6);
    for (std::size_t i = 0; i < square.size(); ++i) {
      nearest[i] = std::min(nearest[i], distance(tip, square[i]));
    }
    ++samples;
  }
  EXPECT_GT(samples, 200u);
  EXPECT_LE(worst, kOnContour);
  for (std::size_t i = 0; i < square.size(); ++i) {
    EXPECT_LE(nearest[i], 0.005) << "corner " << i;
  }
  // C1: CH1's, released, CH2's, released, CH1's again. The square went once round
  // counter-clockwise, so CH1 lends C at 360; CH2 turns it to 135, where CH1 takes it back.
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
  EXPECT_NEAR(at.at(lent).at("C1"), 360.0, 1e-6);
  EXPECT_NEAR(at.at(to_ch2).at("C1"), 360.0, 1e-6);
  EXPECT_NEAR(at.at(let_go).at("C1"), 135.0, 1e-6);
  EXPECT_NEAR(at.at(back).at("C1"), 135.0, 1e-6);
  EXPECT_GT(to_ch2, lent);
  EXPECT_GT(block_start(t, "CH1", 20), back);  // G00 C0 after the take-over

  // G07.1 C20 (lines 25-27): on the cylinder of radius 20 unrolled (u = C x 20 in mm, Z), the
  // tip goes along Z-5 to C90, on a half circle of radius 10 through u(90) + 10 (G02 in the
  // plane C-Z) to Z-25, and back to C0, at the slot's depth (X1 the radius 18). The plunge
  // before (X1 from 22) and the retract after blend into it: the path is checked in (u, Z, X1).
  const double u90 = 90.0 * kDegree * 20.0;
  const Point centre{u90, -15.0};
  std::size_t on_cylinder = 0;
  double worst_cylinder = 0.0;
  double farthest_u = -INFINITY;
  double to_end = INFINITY;
  for (auto it = at.lower_bound(block_start(t, "CH1", 25));
       it != at.end() && it->first < block_start(t, "CH1", 30); ++it) {
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
