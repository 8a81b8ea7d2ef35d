// What each end of a bus lets in: the masters of nodes 1 (the SYNC producer) and 2, and the drives.
#include "canopen/bus_filters.hpp"

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

TEST(BusFilters, TheSyncProducersMasterHearsItsNodeSyncAndTheOthersRpdos) {
  std::array<can::CanFilter, can::kMaxFilters> filters{};
  const std::vector<std::uint8_t> others{2};
  const std::size_t n = master_filters(1, true, others, filters);
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

// Any other node awaits only its drive's answer to the SYNC: neither the SYNC nor the others'
// RPDOs would do more than wake it.
TEST(BusFilters, AnotherNodesMasterHearsItsNodeAlone) {
  std::array<can::CanFilter, can::kMaxFilters> filters{};
  const std::vector<std::uint8_t> others{1};
  const std::size_t n = master_filters(2, false, others, filters);
  ASSERT_GT(n, 0U);
  can::CanFilterSet set;
  ASSERT_TRUE(set.assign(std::span(filters.data(), n)));
  for (const std::uint32_t id : {0x082U, 0x182U, 0x282U, 0x582U, 0x702U}) {
    EXPECT_TRUE(set.passes(with_id(id))) << std::hex << id;
  }
  for (const std::uint32_t id : {0x080U, 0x201U, 0x202U, 0x181U, 0x701U}) {
    EXPECT_FALSE(set.passes(with_id(id))) << std::hex << id;
  }
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
