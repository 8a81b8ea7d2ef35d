// The modal state each command carries for the operator's screen: the G codes of the shown
// groups as they stand for that block, and the modal F.
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <string>

namespace mcnc::interp::test {
namespace {

// The shown groups' G codes (ten times the number) of a command, in kShownModalGroups order.
std::array<std::uint16_t, kShownModalGroups.size()> g(const Command& c) {
  return c.modal.g;
}

TEST(ModalState, EachCommandCarriesTheCodesInForceForItsBlock) {
  const RunResult r = run_ok(
      "G00 X20 Z5\n"
      "G99 G01 Z-10 F0.2\n"
      "G96 S120 G41 X30\n"
      "G98 G40 G55 G01 Z-20 F300\n"
      "M30\n");
  const std::vector<Command> moves = [&] {
    std::vector<Command> m;
    for (const Command& c : r.commands) {
      if (c.op == Op::rapid || c.op == Op::linear) {
        m.push_back(c);
      }
    }
    return m;
  }();
  ASSERT_EQ(moves.size(), 4U);
  // Groups 01, 16, 03, 05, 02, 06, 07, 14; system A has no G90/G91 code.
  using G = std::array<std::uint16_t, kShownModalGroups.size()>;
  EXPECT_EQ(g(moves[0]), (G{0, 180, 0, 980, 970, 210, 400, 540}));
  EXPECT_EQ(g(moves[1]), (G{10, 180, 0, 990, 970, 210, 400, 540}));
  EXPECT_DOUBLE_EQ(moves[1].modal.feed, 0.2);
  EXPECT_EQ(g(moves[2]), (G{10, 180, 0, 990, 960, 210, 410, 540}));
  EXPECT_EQ(g(moves[3]), (G{10, 180, 0, 980, 960, 210, 400, 550}));
  EXPECT_DOUBLE_EQ(moves[3].modal.feed, 300.0);
}

}  // namespace
}  // namespace mcnc::interp::test
