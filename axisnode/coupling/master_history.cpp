#include "axisnode/coupling/master_history.hpp"

namespace mcnc::coupling {

MasterHistory::MasterHistory(std::span<const std::uint32_t> masters, std::size_t depth)
    : depth_(depth == 0 ? 1 : depth) {
  for (const std::uint32_t axis : masters) {
    Master m;
    m.axis = axis;
    m.cycles.assign(depth_, 0);
    m.cmd.assign(depth_, 0.0);
    masters_.push_back(std::move(m));
  }
}

int MasterHistory::index(std::uint32_t axis) const noexcept {
  for (std::size_t i = 0; i < masters_.size(); ++i) {
    if (masters_[i].axis == axis) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

void MasterHistory::put(std::uint32_t axis, std::uint64_t cycle, double cmd) noexcept {
  const int i = index(axis);
  if (i < 0) {
    return;
  }
  Master& m = masters_[static_cast<std::size_t>(i)];
  const std::size_t slot = cycle % depth_;
  m.cycles[slot] = cycle + 1;
  m.cmd[slot] = cmd;
  if (!m.any || cycle >= m.newest) {
    m.newest = cycle;
  }
  m.any = true;
}

void MasterHistory::gone(std::uint32_t axis) noexcept {
  const int i = index(axis);
  if (i >= 0) {
    masters_[static_cast<std::size_t>(i)].gone = true;
  }
}

MasterHistory::Sample MasterHistory::at(std::uint32_t axis, std::uint64_t cycle) const noexcept {
  const int i = index(axis);
  if (i < 0) {
    return Sample{Lookup::unavailable, 0.0};
  }
  const Master& m = masters_[static_cast<std::size_t>(i)];
  const std::size_t slot = cycle % depth_;
  if (m.cycles[slot] == cycle + 1) {
    return Sample{Lookup::found, m.cmd[slot]};
  }
  // Samples come in cycle order from one writer: one newer than `cycle` by the whole ring
  // has overwritten it.
  const bool passed = m.any && m.newest >= cycle + depth_;
  return Sample{m.gone || passed ? Lookup::unavailable : Lookup::not_yet, 0.0};
}

std::optional<double> MasterHistory::latest(std::uint32_t axis) const noexcept {
  const int i = index(axis);
  if (i < 0 || !masters_[static_cast<std::size_t>(i)].any) {
    return std::nullopt;
  }
  const Master& m = masters_[static_cast<std::size_t>(i)];
  return m.cmd[m.newest % depth_];
}

}  // namespace mcnc::coupling
