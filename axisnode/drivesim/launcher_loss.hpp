#pragma once
// When a drive simulator leaves after its launcher died (a `kill -9` of it). A simulated drive
// stands for hardware, which stays powered when its control's supervisor goes: the axis nodes,
// which get SIGTERM then, quick-stop their drives and disable them at rest, and need the drives
// to answer for that. So the simulator stays while the bus's masters still talk to its drives,
// and leaves once they have been quiet for `quiet`, or `limit` after it saw the launcher gone.
// Pure: the caller says what time it is and what came.
#include <chrono>

namespace mcnc::drivesim {

class LauncherLoss {
 public:
  using Clock = std::chrono::steady_clock;

  LauncherLoss(Clock::duration quiet, Clock::duration limit) noexcept
      : quiet_(quiet), limit_(limit) {}

  // One turn of the simulator's loop at `now`: whether the launcher is gone, and whether a
  // frame for its drives came. True: leave now.
  bool leave(Clock::time_point now, bool launcher_gone, bool frame_came) noexcept {
    if (!launcher_gone) {
      return false;
    }
    if (!gone_seen_) {
      gone_seen_ = true;
      gone_since_ = now;
      last_frame_ = now;
    }
    if (frame_came) {
      last_frame_ = now;
    }
    return now - last_frame_ >= quiet_ || now - gone_since_ >= limit_;
  }

 private:
  Clock::duration quiet_;
  Clock::duration limit_;
  // A flag beside plain time points, not an optional: GCC 12 at -O2 takes the optional's value
  // for uninitialised once inlined into the simulator's loop (-Wmaybe-uninitialized).
  bool gone_seen_ = false;
  Clock::time_point gone_since_{};
  Clock::time_point last_frame_{};
};

}  // namespace mcnc::drivesim
