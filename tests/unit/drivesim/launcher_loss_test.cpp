#include "axisnode/drivesim/launcher_loss.hpp"

#include <gtest/gtest.h>

using mcnc::drivesim::LauncherLoss;
using namespace std::chrono_literals;

namespace {
const LauncherLoss::Clock::time_point t0{};
}

TEST(LauncherLoss, StaysWhileTheLauncherLives) {
  LauncherLoss loss(1s, 20s);
  for (int i = 0; i < 100; ++i) {
    EXPECT_FALSE(loss.leave(t0 + i * 1s, false, false));
  }
}

// The axis nodes quick-stop their drives after the launcher died: the simulator answers them,
// and leaves once their frames have stopped for a second.
TEST(LauncherLoss, LeavesASecondAfterTheMastersWentQuiet) {
  LauncherLoss loss(1s, 20s);
  EXPECT_FALSE(loss.leave(t0, true, true));
  for (int ms = 1; ms <= 3000; ++ms) {
    EXPECT_FALSE(loss.leave(t0 + ms * 1ms, true, true)) << ms;
  }
  EXPECT_FALSE(loss.leave(t0 + 3999ms, true, false));
  EXPECT_TRUE(loss.leave(t0 + 4000ms, true, false));
}

// Quiet from the moment it saw the launcher gone: a second later.
TEST(LauncherLoss, ABusAlreadyQuietEndsItASecondAfterTheLauncherWent) {
  LauncherLoss loss(1s, 20s);
  EXPECT_FALSE(loss.leave(t0 + 5s, true, false));
  EXPECT_FALSE(loss.leave(t0 + 5900ms, true, false));
  EXPECT_TRUE(loss.leave(t0 + 6s, true, false));
}

// Whoever keeps talking on the bus, an orphaned simulator does not run on for ever.
TEST(LauncherLoss, LeavesAtTheLimitEvenWhileFramesComeOn) {
  LauncherLoss loss(1s, 20s);
  for (int s = 0; s < 20; ++s) {
    EXPECT_FALSE(loss.leave(t0 + s * 1s, true, true)) << s;
  }
  EXPECT_TRUE(loss.leave(t0 + 20s, true, true));
}
