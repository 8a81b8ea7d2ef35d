#pragma once
// How a stopping axis node leaves its drive (issue 25, "stopping is safe"): whatever ends the
// process (a signal, the run's end), the drive is quick-stopped first and disabled only once it
// stands. Cutting the power of a moving drive lets a vertical axis fall and a spindle coast.
//
// The node keeps cycling, paced to real time, until the drive is ready to be disabled. The
// bus's SYNC producer also keeps cycling until the other nodes of its bus have gone quiet (no
// RPDO for a while): their drives act only on its SYNC, so without it they would never finish
// their own quick stop. Each wait is bounded: a drive that no longer answers is not waited for,
// and nothing is waited for beyond the limit.
//
// Pure and deterministic: counts cycles, allocates nothing, throws nothing.
#include <cstdint>

namespace mcnc::axisnode {

struct DriveStopLimits {
  // The bus's other nodes are quiet after this many cycles without one of their RPDOs.
  int quiet_cycles = 50;
  // A drive that has not answered for this many cycles is gone: it is not waited for.
  int silent_drive_cycles = 20;
  // The longest the whole stop may take.
  int limit_cycles = 5000;
};

class DriveStop {
 public:
  enum class Verdict : std::uint8_t {
    go_on,       // another cycle of quick stop (or of SYNC for the others)
    disable,     // the drive stands (and the others are quiet): disable it now
    drive_gone,  // the drive no longer answers: disable it without waiting
    timed_out,   // the limit passed with the drive or the others still moving
  };

  DriveStop(bool sync_producer, const DriveStopLimits& limits) noexcept
      : sync_producer_(sync_producer), limits_(limits) {}

  // One cycle of the stop: whether the drive answered this cycle, whether it is ready to be
  // disabled, and how many RPDOs of the bus's other nodes have been seen so far.
  Verdict cycle(bool drive_answered, bool ready_to_disable, std::uint64_t other_rpdos) noexcept;

  [[nodiscard]] int cycles() const noexcept { return cycles_; }

 private:
  bool sync_producer_;
  DriveStopLimits limits_;
  int cycles_ = 0;
  int silent_ = 0;
  int quiet_ = 0;
  bool rpdos_known_ = false;
  std::uint64_t last_rpdos_ = 0;
};

const char* to_text(DriveStop::Verdict verdict) noexcept;

}  // namespace mcnc::axisnode
