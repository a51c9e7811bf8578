// keep_and_fault_in leaves the process holding faulted-in memory that later allocations use.
#include "core/memory.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace neomesh {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

TEST(Memory, FaultedInMemoryStaysAndServesTheNextAllocations) {
  const double before = resident_bytes();
  ASSERT_GT(before, 0.0);
  keep_and_fault_in(64 * kMiB);
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

}  // namespace
}  // namespace neomesh
