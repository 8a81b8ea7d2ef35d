// The single-producer/single-consumer ring (common/cycle): what a pop tells the consumer about
// a producer that may wait for room.
#include "common/cycle/spsc_ring.hpp"

#include <gtest/gtest.h>

namespace mcnc::cycle {
namespace {

void fill(SpscRing<int, 4>& ring, int first, int count) {
  for (int k = 0; k < count; ++k) {
    int* slot = ring.claim();
    ASSERT_NE(slot, nullptr);
    *slot = first + k;
    ring.publish();
  }
}

TEST(SpscRing, OnlyThePopFromAFullRingSaysItWasFull) {
  SpscRing<int, 4> ring;
  fill(ring, 1, 4);
  EXPECT_EQ(ring.claim(), nullptr);  // full: a producer would wait for room now
  ASSERT_NE(ring.front(), nullptr);
  EXPECT_EQ(*ring.front(), 1);
  EXPECT_TRUE(ring.pop_was_full());
  EXPECT_EQ(*ring.front(), 2);
  EXPECT_FALSE(ring.pop_was_full());  // room was there already: nobody waits for it
  fill(ring, 5, 2);                   // full again
  EXPECT_EQ(*ring.front(), 3);
  EXPECT_TRUE(ring.pop_was_full());
  EXPECT_FALSE(ring.pop_was_full());
  EXPECT_EQ(*ring.front(), 5);
  EXPECT_FALSE(ring.pop_was_full());
  EXPECT_EQ(*ring.front(), 6);
  EXPECT_FALSE(ring.pop_was_full());
  EXPECT_EQ(ring.front(), nullptr);
}

}  // namespace
}  // namespace mcnc::cycle
