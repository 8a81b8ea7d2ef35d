#include "axisnode/coupling/master_history.hpp"

namespace mcnc::coupling {

namespace {
constexpr std::uint64_t kLookBack = 8;  // realtime: how far back the sample before the newest
}

MasterHistory::MasterHistory(std::span<const std::uint32_t> masters, std::size_t depth)
    : depth_(depth == 0 ? 1 : depth) {
  for (const std::uint32_t axis : masters) {
    Master m;
    m.axis = axis;
    m.cycles.assign(depth_, 0);
    m.cmd.assign(depth_, 0.0);
    m.operating.assign(depth_, false);
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

void MasterHistory::put(std::uint32_t axis, std::uint64_t cycle, double cmd,
                        bool operating) noexcept {
  const int i = index(axis);
  if (i < 0) {
    return;
  }
  Master& m = masters_[static_cast<std::size_t>(i)];
  const std::size_t slot = cycle % depth_;
  m.cycles[slot] = cycle + 1;
  m.cmd[slot] = cmd;
  m.operating[slot] = operating;
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

MasterHistory::Sample MasterHistory::sample(const Master& m, std::uint64_t cycle) const noexcept {
  const std::size_t slot = cycle % depth_;
  if (m.cycles[slot] == cycle + 1) {
    return Sample{Lookup::found, m.cmd[slot], m.operating[slot]};
  }
  // Samples come in cycle order from one writer: one newer than `cycle` by the whole ring
  // has overwritten it.
  const bool passed = m.any && m.newest >= cycle + depth_;
  return Sample{m.gone || passed ? Lookup::unavailable : Lookup::not_yet, 0.0, false};
}

MasterHistory::Sample MasterHistory::at(std::uint32_t axis, std::uint64_t cycle) const noexcept {
  const int i = index(axis);
  if (i < 0) {
    return Sample{Lookup::unavailable, 0.0, false};
  }
  return sample(masters_[static_cast<std::size_t>(i)], cycle);
}

MasterHistory::Sample MasterHistory::estimate(std::uint32_t axis, std::uint64_t cycle,
                                              bool exact) const noexcept {
  const int i = index(axis);
  if (i < 0 || cycle == 0) {
    return Sample{i < 0 ? Lookup::unavailable : Lookup::not_yet, 0.0, false};
  }
  const Master& m = masters_[static_cast<std::size_t>(i)];
  std::uint64_t at_cycle = cycle - 1;
  if (!exact) {
    if (!m.any) {
      return Sample{m.gone ? Lookup::unavailable : Lookup::not_yet, 0.0, false};
    }
    at_cycle = m.newest;
  }
  Sample newest = sample(m, at_cycle);
  if (newest.lookup != Lookup::found) {
    return newest;
  }
  // The speed between the newest sample and the one before it, per cycle.
  for (std::uint64_t back = 1; back <= (exact ? 1 : kLookBack) && back <= at_cycle; ++back) {
    const Sample before = sample(m, at_cycle - back);
    if (before.lookup == Lookup::found && before.operating) {
      const double per_cycle = (newest.cmd - before.cmd) / static_cast<double>(back);
      newest.cmd += per_cycle * (static_cast<double>(cycle) - static_cast<double>(at_cycle));
      break;
    }
  }
  return newest;
}

}  // namespace mcnc::coupling
