#include "axisnode/node/drive_stop.hpp"

namespace mcnc::axisnode {

DriveStop::Verdict DriveStop::cycle(bool drive_answered, bool ready_to_disable,
                                    std::uint64_t other_rpdos) noexcept {
  ++cycles_;
  silent_ = drive_answered ? 0 : silent_ + 1;
  if (rpdos_known_ && other_rpdos == last_rpdos_) {
    ++quiet_;
  } else {
    quiet_ = 0;
  }
  rpdos_known_ = true;
  last_rpdos_ = other_rpdos;

  const bool others_quiet = !sync_producer_ || quiet_ >= limits_.quiet_cycles;
  const bool drive_gone = silent_ >= limits_.silent_drive_cycles;
  if ((ready_to_disable || drive_gone) && others_quiet) {
    return ready_to_disable ? Verdict::disable : Verdict::drive_gone;
  }
  if (cycles_ >= limits_.limit_cycles) {
    return Verdict::timed_out;
  }
  return Verdict::go_on;
}

const char* to_text(DriveStop::Verdict verdict) noexcept {
  switch (verdict) {
    case DriveStop::Verdict::go_on:
      return "stopping";
    case DriveStop::Verdict::disable:
      return "at rest";
    case DriveStop::Verdict::drive_gone:
      return "the drive no longer answers";
    case DriveStop::Verdict::timed_out:
      return "still moving at the limit";
  }
  return "?";
}

}  // namespace mcnc::axisnode
