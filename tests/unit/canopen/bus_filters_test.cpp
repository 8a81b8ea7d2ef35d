// What each end of a bus lets in: the master of node 1 (with node 2 on the bus) and the drives.
#include "axisnode/canopen/bus_filters.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace mcnc::canopen {
namespace {

can::CanFrame with_id(std::uint32_t id) {
  can::CanFrame f;
  f.id = id;
  return f;
}

TEST(BusFilters, TheMasterOfANodeHearsItsNodeSyncAndTheOthersRpdos) {
  std::array<can::CanFilter, can::kMaxFilters> filters{};
  const std::vector<std::uint8_t> others{2};
  const std::size_t n = master_filters(1, others, filters);
  ASSERT_GT(n, 0U);
  can::CanFilterSet set;
  ASSERT_TRUE(set.assign(std::span(filters.data(), n)));
  for (const std::uint32_t id : {0x080U, 0x081U, 0x181U, 0x281U, 0x581U, 0x701U, 0x202U}) {
    EXPECT_TRUE(set.passes(with_id(id))) << std::hex << id;
  }
  for (const std::uint32_t id : {0x000U, 0x082U, 0x182U, 0x201U, 0x601U, 0x582U, 0x702U}) {
    EXPECT_FALSE(set.passes(with_id(id))) << std::hex << id;
  }
  EXPECT_TRUE(set.passes(with_id(can::kErrFlag | 0x40U)));  // error frames always
}

TEST(BusFilters, TheDrivesHearNmtSyncAndWhatIsAddressedToThem) {
  std::array<can::CanFilter, can::kMaxFilters> filters{};
  const std::vector<std::uint8_t> nodes{1, 2};
  const std::size_t n = device_filters(nodes, filters);
  can::CanFilterSet set;
  ASSERT_TRUE(set.assign(std::span(filters.data(), n)));
  for (const std::uint32_t id : {0x000U, 0x080U, 0x201U, 0x302U, 0x601U, 0x602U}) {
    EXPECT_TRUE(set.passes(with_id(id))) << std::hex << id;
  }
  for (const std::uint32_t id : {0x181U, 0x581U, 0x701U, 0x203U, 0x603U, 0x081U}) {
    EXPECT_FALSE(set.passes(with_id(id))) << std::hex << id;
  }
  // Too many drives for the filters: no filter rather than a wrong one.
  const std::vector<std::uint8_t> many(20, 3);
  EXPECT_EQ(device_filters(many, filters), 0U);
}

}  // namespace
}  // namespace mcnc::canopen
