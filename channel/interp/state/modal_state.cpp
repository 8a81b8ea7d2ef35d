#include "channel/interp/state/modal_state.hpp"

namespace mcnc::interp::state {

ModalState ModalState::power_on(GCodeSystem system, Dialect dialect, FeedMode feed_mode) noexcept {
  ModalState m;
  m.feed_mode = feed_mode;
  const bool b = system == GCodeSystem::b;
  m.codes[1] = 0;
  m.codes[2] = 97;
  m.codes[3] = b ? 90 : 0;
  m.codes[4] = 69;
  m.codes[5] = feed_mode == FeedMode::per_min ? (b ? 94 : 98) : (b ? 95 : 99);
  m.codes[6] = 21;
  m.codes[7] = 40;
  m.codes[9] = 23;
  m.codes[10] = 80;
  m.codes[11] = b ? 98 : 0;
  m.codes[12] = 67;
  m.codes[14] = 54;
  m.codes[15] = 64;
  m.codes[16] = 18;
  m.codes[17] = 69.1;
  m.codes[18] = 15;
  m.codes[19] = 40.1;
  m.codes[21] = 13.1;
  m.codes[22] = 50.1;
  if (dialect == Dialect::fanuc_mill) {
    m.plane = Plane::xy;
    m.codes[16] = 17;
    m.codes[8] = 49;
    m.codes[2] = 0;
    m.codes[9] = 0;  // no G22/G23 in its table
    m.codes[19] = 0;
  }
  return m;
}

}  // namespace mcnc::interp::state
