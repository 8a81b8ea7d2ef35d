// NormalDirection (channel/interp/normal_direction.hpp): the rotary axis of G41.1/G42.1 turned
// on the path as the look-ahead releases it, with and without tool-nose compensation: lines,
// arcs, inside and outside corners, a change of side, the carried angle after G40.1, and seeded
// random paths on which the axis points at the travel direction +-90 degrees at every move's
// start and end.
#include "channel/interp/block_lookahead.hpp"
#include "channel/interp/normal_direction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace mcnc::interp {
namespace {

// Channel axes X (radius here), Z and the rotary axis A; G18: a = Z, b = X.
constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;
constexpr std::size_t kA = 2;
constexpr std::array<int, 2> kPlane{1, 0};
constexpr double kFeed = 7200.0;
constexpr double kDegrees = 180.0 / 3.14159265358979323846;

NormalDirection unit() {
  return NormalDirection(NormalDirection::Settings{static_cast<int>(kA), kFeed});
}

Command move(Op op, double z, double x, Command::Normal side) {
  Command c;
  c.op = op;
  c.to[kZ] = z;
  c.to[kX] = x;
  c.feed = 300.0;
  c.normal = side;
  c.normal_plane = kPlane;
  return c;
}

Command line(double z, double x, Command::Normal side = Command::Normal::left) {
  return move(Op::linear, z, x, side);
}

Command arc(double z, double x, double cz, double cx, bool ccw,
            Command::Normal side = Command::Normal::left) {
  Command c = move(Op::arc, z, x, side);
  c.plane = Plane::zx;
  c.center_axes = kPlane;
  c.center = {cz, cx};
  c.direction = ccw ? ArcDirection::ccw : ArcDirection::cw;
  return c;
}

// The same angle up to full turns.
::testing::AssertionResult same_angle(double got, double want) {
  const double d = std::remainder(got - want, 360.0);
  if (std::fabs(d) <= 1e-9) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << got << " is not " << want << " (mod 360)";
}

bool is_turn(const Command& c, const AxisVector& before) {
  return c.op == Op::linear && c.feed == kFeed && c.to[kZ] == before[kZ] && c.to[kX] == before[kX];
}

TEST(NormalDirectionPath, ALineIsPrecededByATurnAndKeepsItsAngle) {
  NormalDirection n = unit();
  n.reset({});
  std::vector<Command> list{line(10, 0), line(10, 5)};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 4u);
  // +Z is 0 degrees: on the left 90, the turn at the start point, A alone at param 5551.
  EXPECT_TRUE(is_turn(list[0], {}));
  EXPECT_TRUE(same_angle(list[0].to[kA], 90));
  EXPECT_TRUE(same_angle(list[1].to[kA], 90));
  // +X is 90 degrees: on the left 180, turned at Z10 X0 by +90 (the shorter way).
  EXPECT_NEAR(list[2].to[kZ], 10, 1e-12);
  EXPECT_NEAR(list[2].to[kA], 180, 1e-9);
  EXPECT_NEAR(list[3].to[kA], 180, 1e-9);
  EXPECT_NEAR(n.angle(), 180, 1e-9);
}

TEST(NormalDirectionPath, TheRightSideAndTheShorterWay) {
  NormalDirection n = unit();
  AxisVector start{};
  start[kA] = 350.0;  // -90 + 360 is 270: from 350 the shorter way is down by 80
  n.reset(start);
  std::vector<Command> list{line(10, 0, Command::Normal::right),
                            line(10, -5, Command::Normal::right)};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 4u);
  EXPECT_NEAR(list[0].to[kA], 270, 1e-9);
  // Along -X (-90 degrees): on the right 180, from 270 down by 90.
  EXPECT_NEAR(list[2].to[kA], 180, 1e-9);
}

TEST(NormalDirectionPath, ArcsTurnTheAxisWithTheirSweep) {
  NormalDirection n = unit();
  n.reset({});
  // A G03 half circle from Z0 X0 about Z0 X10 starts along +Z (normal 90) and ends along -Z
  // (270). The G02 from there about Z0 X30 starts along -Z too: no turn; its quarter circle
  // clockwise takes the axis to 180 (ending along +X).
  std::vector<Command> list{arc(0, 20, 0, 10, true), arc(-10, 30, 0, 30, false)};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_NEAR(list[0].to[kA], 90, 1e-9);
  EXPECT_NEAR(list[1].to[kA], 270, 1e-9);
  EXPECT_EQ(list[2].op, Op::arc);
  EXPECT_NEAR(list[2].to[kA], 180, 1e-9);
}

TEST(NormalDirectionPath, FullTurnsOfAnArcTurnTheAxisAsOften) {
  NormalDirection n = unit();
  n.reset({});
  Command circle = arc(0, 0, 0, 10, true);  // a full circle, and one more turn
  circle.turns = 1;
  std::vector<Command> list{circle};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_NEAR(list[1].to[kA], 90 + 720, 1e-9);
}

TEST(NormalDirectionPath, ATangentJointInsertsNoTurn) {
  NormalDirection n = unit();
  n.reset({});
  // Along +Z, then a G03 quarter circle tangent to it, then along +X tangent to the arc.
  std::vector<Command> list{line(10, 0), arc(20, 10, 10, 10, true), line(20, 20)};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 4u);  // one turn: the first, from 0 to 90
  EXPECT_NEAR(list[1].to[kA], 90, 1e-9);
  EXPECT_NEAR(list[2].to[kA], 180, 1e-9);
  EXPECT_NEAR(list[3].to[kA], 180, 1e-9);
}

TEST(NormalDirectionPath, ATinyTurnIsMadeDuringTheMove) {
  NormalDirection n = unit();
  AxisVector start{};
  start[kA] = 90.0 - 1e-7;  // below kFoldedTurn from the normal of +Z
  n.reset(start);
  std::vector<Command> list{line(10, 0)};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_NEAR(list[0].to[kA], 90, 1e-12);
}

TEST(NormalDirectionPath, HoldCarriesTheAngleAndAnUntaggedMoveSetsIt) {
  NormalDirection n = unit();
  n.reset({});
  Command held = line(0, 10, Command::Normal::hold);
  held.to[kA] = 0.0;  // what the interpreter believed
  Command programmed = line(0, 10, Command::Normal::off);
  programmed.to[kA] = 45.0;
  std::vector<Command> list{line(10, 0), held, programmed};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 4u);
  EXPECT_NEAR(list[2].to[kA], 90, 1e-12);  // no turn: the axis stays where G41.1 left it
  EXPECT_NEAR(list[3].to[kA], 45, 1e-12);
  EXPECT_NEAR(n.angle(), 45, 1e-12);
}

TEST(NormalDirectionPath, RapidsThreadsAndMovesOutOfThePlaneLeaveTheAngle) {
  NormalDirection n = unit();
  n.reset({});
  Command rapid = move(Op::rapid, 5, 5, Command::Normal::left);
  Command thread = move(Op::thread, 20, 5, Command::Normal::left);
  Command still = line(20, 5);
  std::vector<Command> list{line(0, 1), rapid, thread, still};
  n.turn(list, 0);
  ASSERT_EQ(list.size(), 5u);
  for (std::size_t k = 1; k < list.size(); ++k) {
    EXPECT_NEAR(list[k].to[kA], 180, 1e-12) << k;
  }
}

// ---- On the compensated path (BlockLookahead, G41/G42 with a nose radius)

struct Released {
  std::vector<Command> commands;
  bool alarm = false;
};

Released through_lookahead(std::vector<Command> program, AxisVector start = {}) {
  BlockLookahead lookahead;
  lookahead.reset(start);
  lookahead.set_plane(kPlane, Plane::zx);
  NormalDirection n = unit();
  n.reset(start);
  Released r;
  for (Command& c : program) {
    const std::size_t from = r.commands.size();
    if (lookahead.push(std::move(c), r.commands)) {
      r.alarm = true;
      return r;
    }
    n.turn(r.commands, from);
  }
  const std::size_t from = r.commands.size();
  if (lookahead.flush(r.commands)) {
    r.alarm = true;
  }
  n.turn(r.commands, from);
  return r;
}

Command compensated(Command c, Command::Compensation side, double radius) {
  c.compensation = side;
  c.nose_radius = radius;
  return c;
}

// The travel direction (degrees) where a move from `from` starts or ends.
double direction(const Command& c, const AxisVector& from, bool at_end) {
  if (c.op == Op::arc) {
    const AxisVector& p = at_end ? c.to : from;
    const double ra = p[kZ] - c.center[0];
    const double rb = p[kX] - c.center[1];
    return c.direction == ArcDirection::ccw ? std::atan2(ra, -rb) * kDegrees
                                            : std::atan2(-ra, rb) * kDegrees;
  }
  return std::atan2(c.to[kX] - from[kX], c.to[kZ] - from[kZ]) * kDegrees;
}

// Every tagged line or arc that travels in the plane starts and ends with the axis at its
// direction +-90 degrees; returns how many were checked.
int expect_normal_everywhere(const std::vector<Command>& list, const AxisVector& start) {
  AxisVector at = start;
  int checked = 0;
  for (const Command& c : list) {
    if (!c.moves()) {
      continue;
    }
    const bool turned = c.normal == Command::Normal::left || c.normal == Command::Normal::right;
    const double travel = c.op == Op::arc ? 1.0 : std::hypot(c.to[kZ] - at[kZ], c.to[kX] - at[kX]);
    if (turned && (c.op == Op::linear || c.op == Op::arc) && travel > 1e-9) {
      const double side = c.normal == Command::Normal::left ? 90.0 : -90.0;
      EXPECT_TRUE(same_angle(at[kA], direction(c, at, false) + side)) << "start, line " << c.line;
      EXPECT_TRUE(same_angle(c.to[kA], direction(c, at, true) + side)) << "end, line " << c.line;
      ++checked;
    }
    at = c.to;
  }
  return checked;
}

TEST(NormalDirectionPath, AnOutsideCornerTurnsTheAxisAlongTheCornerArc) {
  // G42 along -Z, then along -X: a left turn, the outside for the tool on the right. The
  // start-up line goes from Z30 X10 to the offset start of the second move (Z20 X11).
  const auto right = Command::Compensation::right;
  AxisVector start{};
  start[kZ] = 30;
  start[kX] = 10;
  std::vector<Command> program{compensated(line(20, 10), right, 1),
                               compensated(line(10, 10), right, 1),
                               compensated(line(10, 0), right, 1)};
  const Released r = through_lookahead(program, start);
  ASSERT_FALSE(r.alarm);
  int turns = 0;
  AxisVector at = start;
  std::vector<Command> arcs;
  for (const Command& c : r.commands) {
    turns += is_turn(c, at) ? 1 : 0;
    if (c.op == Op::arc) {
      arcs.push_back(c);
    }
    at = c.to;
  }
  // Before the start-up line and before the second move; none at the corner, where the corner
  // arc (a G03 about the programmed corner) carries the axis from 270 (the left normal of -Z)
  // by +90 to the left normal of -X.
  EXPECT_EQ(turns, 2);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_NEAR(arcs[0].center[0], 10, 1e-9);
  EXPECT_NEAR(arcs[0].center[1], 10, 1e-9);
  EXPECT_TRUE(same_angle(arcs[0].to[kA], 0));
  EXPECT_EQ(expect_normal_everywhere(r.commands, start), 4);
}

TEST(NormalDirectionPath, AnInsideCornerTurnsAtTheIntersection) {
  // G41 along +Z, +X, then -Z: two left turns, the inside for the tool on the left. The
  // second move's offset is the line Z9 and the third's X9: they meet at Z9 X9.
  const auto left = Command::Compensation::left;
  std::vector<Command> program{compensated(line(10, 0), left, 1),
                               compensated(line(10, 10), left, 1),
                               compensated(line(0, 10), left, 1)};
  const Released r = through_lookahead(program);
  ASSERT_FALSE(r.alarm);
  AxisVector at{};
  std::vector<AxisVector> turned_at;
  for (const Command& c : r.commands) {
    if (is_turn(c, at)) {
      turned_at.push_back(c.to);
    }
    EXPECT_NE(c.op, Op::arc);  // no corner arcs on the inside
    at = c.to;
  }
  // Before the start-up line (to 90), at the second move's offset start Z9 X0 (to 180), and at
  // the inside corner Z9 X9 (to 270).
  ASSERT_EQ(turned_at.size(), 3u);
  EXPECT_NEAR(turned_at[0][kA], 90, 1e-9);
  EXPECT_NEAR(turned_at[1][kZ], 9, 1e-9);
  EXPECT_NEAR(turned_at[1][kX], 0, 1e-9);
  EXPECT_NEAR(turned_at[1][kA], 180, 1e-9);
  EXPECT_NEAR(turned_at[2][kZ], 9, 1e-9);
  EXPECT_NEAR(turned_at[2][kX], 9, 1e-9);
  EXPECT_NEAR(turned_at[2][kA], 270, 1e-9);
  EXPECT_EQ(expect_normal_everywhere(r.commands, {}), 3);
}

TEST(NormalDirectionPath, ArcsOnTheOffsetPath) {
  // G42 on a G02 and a G03 that meet tangentially, then a line: the axis follows the offset
  // arcs (their radii differ from the programmed ones, their sweeps do not).
  const auto right = Command::Compensation::right;
  std::vector<Command> program{
      compensated(line(10, 0), right, 0.8), compensated(arc(20, -10, 10, -10, false), right, 0.8),
      compensated(arc(30, -20, 30, -10, true), right, 0.8), compensated(line(30, -30), right, 0.8)};
  const Released r = through_lookahead(program);
  ASSERT_FALSE(r.alarm);
  EXPECT_GE(expect_normal_everywhere(r.commands, {}), 4);
}

TEST(NormalDirectionPath, AChangeFromG41ToG42) {
  std::vector<Command> program{
      compensated(line(10, 0), Command::Compensation::left, 1),
      compensated(line(10, 10), Command::Compensation::left, 1),
      compensated(line(20, 10, Command::Normal::right), Command::Compensation::right, 1),
      compensated(line(20, 0, Command::Normal::right), Command::Compensation::right, 1)};
  const Released r = through_lookahead(program);
  ASSERT_FALSE(r.alarm);
  EXPECT_GE(expect_normal_everywhere(r.commands, {}), 4);
}

// Seeded random paths of lines and arcs, some joined tangentially, under G41 or G42 (changing
// side now and then) or none, turned left or right: at every released move's start and end the
// axis points at the travel direction +-90 degrees within 1e-9.
TEST(NormalDirectionPath, SeededRandomPathsKeepTheAxisNormal) {
  int paths = 0;
  int moves = 0;
  for (std::uint32_t seed = 1; seed <= 300; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit01(0.0, 1.0);
    const double radius = (seed % 3 == 0) ? 0.0 : 0.2 + 0.8 * unit01(rng);
    Command::Compensation comp = seed % 3 == 0   ? Command::Compensation::off
                                 : seed % 2 == 0 ? Command::Compensation::left
                                                 : Command::Compensation::right;
    Command::Normal side = unit01(rng) < 0.5 ? Command::Normal::left : Command::Normal::right;
    std::vector<Command> program;
    double z = 0.0;
    double x = 0.0;
    double heading = 2.0 * 3.14159265358979323846 * unit01(rng);
    for (int k = 0; k < 12; ++k) {
      if (comp != Command::Compensation::off && k > 2 && unit01(rng) < 0.08) {
        comp = comp == Command::Compensation::left ? Command::Compensation::right
                                                   : Command::Compensation::left;
      }
      if (unit01(rng) < 0.1) {
        side = side == Command::Normal::left ? Command::Normal::right : Command::Normal::left;
      }
      const bool tangent = unit01(rng) < 0.4;
      if (!tangent) {
        heading += (unit01(rng) - 0.5) * 3.0;  // a corner of up to about 86 degrees either way
      }
      Command c;
      if (k == 0 || unit01(rng) < 0.5) {
        const double len = 3.0 + 12.0 * unit01(rng);
        z += len * std::cos(heading);
        x += len * std::sin(heading);
        c = line(z, x, side);
      } else {
        const bool ccw = unit01(rng) < 0.5;
        const double r = 3.0 + 10.0 * unit01(rng);
        // The centre to the left of the heading for G03, to the right for G02.
        const double n = heading + (ccw ? 1.0 : -1.0) * 3.14159265358979323846 / 2.0;
        const double cz = z + r * std::cos(n);
        const double cx = x + r * std::sin(n);
        const double sweep = (0.3 + 2.0 * unit01(rng)) * (ccw ? 1.0 : -1.0);
        const double from = std::atan2(x - cx, z - cz);
        z = cz + r * std::cos(from + sweep);
        x = cx + r * std::sin(from + sweep);
        heading += sweep;
        c = arc(z, x, cz, cx, ccw, side);
      }
      c.line = k + 1;
      program.push_back(compensated(c, comp, comp == Command::Compensation::off ? 0.0 : radius));
    }
    const Released r = through_lookahead(program);
    if (r.alarm) {
      continue;  // a corner the nose cannot make (alarm 1150): not this test's matter
    }
    ++paths;
    moves += expect_normal_everywhere(r.commands, {});
  }
  EXPECT_GE(paths, 200);
  EXPECT_GE(moves, 2000);
}

}  // namespace
}  // namespace mcnc::interp
