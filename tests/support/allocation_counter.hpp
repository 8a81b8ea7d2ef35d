#pragma once
// Counts the heap allocations of the threads that ask for it: the test binary's global
// operator new counts a call when its thread is counting, and passes every call on to malloc.
#include <cstdint>

namespace mcnc::test {

// Allocations counted so far, on every counting thread.
std::uint64_t allocations() noexcept;

// While one lives, this thread's allocations are counted.
class CountAllocations {
 public:
  CountAllocations() noexcept;
  ~CountAllocations();
  CountAllocations(const CountAllocations&) = delete;
  CountAllocations& operator=(const CountAllocations&) = delete;
};

}  // namespace mcnc::test
