// A snapshot one thread publishes and another takes whole: never a mix of two publications, and
// never older than the last one the reader saw.
#include "common/cycle/double_buffer.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <thread>

namespace mcnc::cycle {
namespace {

// Fields that all follow from n: a torn copy shows.
struct Sample {
  std::uint64_t n = 0;
  std::int32_t twice = 0;
  std::int16_t low = 0;
  std::uint8_t parity = 0;
  std::uint64_t square = 0;
};

Sample sample_of(std::uint64_t n) {
  return Sample{n, static_cast<std::int32_t>(2 * n), static_cast<std::int16_t>(n & 0x7FFF),
                static_cast<std::uint8_t>(n & 1U), n * n};
}

TEST(DoubleBuffer, StartsWithItsInitialValueAndGivesTheLatest) {
  DoubleBuffer<Sample> buffer(sample_of(7));
  EXPECT_EQ(buffer.latest().square, 49U);
  buffer.publish(sample_of(8));
  buffer.publish(sample_of(9));
  EXPECT_EQ(buffer.latest().n, 9U);
  EXPECT_EQ(buffer.latest().twice, 18);
}

TEST(DoubleBuffer, AReaderNeverSeesATornOrAnOlderSnapshotWhileTheWriterRuns) {
  DoubleBuffer<Sample> buffer;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::uint64_t n = 1; n <= 2'000'000; ++n) {
      buffer.publish(sample_of(n));
    }
    done = true;
  });
  std::uint64_t last = 0;
  std::uint64_t reads = 0;
  std::uint64_t torn = 0;
  std::uint64_t backwards = 0;
  while (!done || reads < 1000) {
    const Sample s = buffer.latest();
    const Sample expected = sample_of(s.n);
    torn += s.twice != expected.twice || s.low != expected.low || s.parity != expected.parity ||
            s.square != expected.square;
    backwards += s.n < last;
    last = s.n;
    ++reads;
  }
  writer.join();
  EXPECT_EQ(torn, 0U) << "of " << reads << " reads";
  EXPECT_EQ(backwards, 0U);
  EXPECT_EQ(buffer.latest().n, 2'000'000U);
}

}  // namespace
}  // namespace mcnc::cycle
