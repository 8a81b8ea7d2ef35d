#pragma once
// What the load tests of G10 L14 share: an X-Z channel's slots and its axes' feedback with the
// loads their drives report.
#include "channel/coordination/channel_axes.hpp"

#include <vector>

namespace mcnc::coordination::test {

inline std::vector<AxisSlot> xz() {
  std::vector<AxisSlot> s(2);
  s[0].address = 'X';
  s[1].address = 'Z';
  return s;
}

// The feedback of X and Z, each reporting its load (% of the rated torque).
inline std::vector<AxisFeedbackView> loads(double x, double z) {
  std::vector<AxisFeedbackView> f(2);
  f[0].load_known = true;
  f[0].load = x;
  f[1].load_known = true;
  f[1].load = z;
  return f;
}

}  // namespace mcnc::coordination::test
