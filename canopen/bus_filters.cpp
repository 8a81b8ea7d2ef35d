#include "canopen/bus_filters.hpp"

namespace mcnc::canopen {

namespace {

class FilterList {
 public:
  explicit FilterList(std::span<can::CanFilter> out) noexcept : out_(out) {}
  void add(std::uint32_t id) noexcept {
    if (count_ < out_.size()) {
      out_[count_] = can::CanFilter{id, can::kSffMask};
    }
    ++count_;
  }
  [[nodiscard]] std::size_t result() const noexcept { return count_ <= out_.size() ? count_ : 0; }

 private:
  std::span<can::CanFilter> out_;
  std::size_t count_ = 0;
};

}  // namespace

std::size_t master_filters(std::uint8_t node, bool sync_producer,
                           std::span<const std::uint8_t> other_nodes,
                           std::span<can::CanFilter> out) noexcept {
  FilterList list(out);
  list.add(0x080U + node);  // EMCY
  list.add(0x180U + node);  // TPDO1
  list.add(0x280U + node);  // TPDO2
  list.add(0x580U + node);  // SDO responses
  list.add(0x700U + node);  // heartbeat, boot-up
  if (sync_producer) {
    list.add(0x080);  // SYNC
    for (const std::uint8_t other : other_nodes) {
      list.add(0x200U + other);  // the others' RPDO1
    }
  }
  return list.result();
}

std::size_t device_filters(std::span<const std::uint8_t> nodes,
                           std::span<can::CanFilter> out) noexcept {
  FilterList list(out);
  list.add(0x000);  // NMT
  list.add(0x080);  // SYNC
  for (const std::uint8_t n : nodes) {
    list.add(0x200U + n);  // RPDO1
    list.add(0x300U + n);  // RPDO2
    list.add(0x600U + n);  // SDO requests
  }
  return list.result();
}

}  // namespace mcnc::canopen
