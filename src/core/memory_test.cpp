// keep_and_fault_in leaves the process holding faulted-in memory that later allocations use.
#include "core/memory.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

namespace neomesh {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

TEST(Memory, FaultedInMemoryStaysAndServesTheNextAllocations) {
  const double before = resident_bytes();
  ASSERT_GT(before, 0.0);
  const double kept = kept_bytes();
  keep_and_fault_in(64 * kMiB);
  EXPECT_EQ(kept_bytes() - kept, 64 * kMiB);
  const double after = resident_bytes();
  // Freed, and still held: malloc kept it instead of unmapping it.
  EXPECT_GE(after - before, 60 * kMiB);
  {
    // A large array written now takes those pages, not new ones.
    const std::size_t size = 48 * 1024 * 1024;
    std::unique_ptr<char[]> block(new char[size]());
    EXPECT_LT(resident_bytes() - after, 8 * kMiB);
    EXPECT_EQ(block[size - 1], 0);
  }
  EXPECT_LT(resident_bytes() - after, 8 * kMiB);
}

// What the expected peak still needs beyond the resident set is not spare; what it already
// holds is not counted twice.
TEST(Memory, TheExpectedPeakIsNotSpare) {
  setenv("NEOMESH_MEMORY_AVAILABLE_MIB", "1000", 1);
  EXPECT_EQ(spare_bytes(), 1000 * kMiB);
  expect_peak(resident_bytes() + 300 * kMiB);
  EXPECT_NEAR(spare_bytes(), 700 * kMiB, 4 * kMiB);
  expect_peak(resident_bytes() / 2);
  EXPECT_EQ(spare_bytes(), 1000 * kMiB);
  expect_peak(0.0);
  unsetenv("NEOMESH_MEMORY_AVAILABLE_MIB");
}

}  // namespace
}  // namespace neomesh
