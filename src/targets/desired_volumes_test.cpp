#include "targets/desired_volumes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace neomesh {
namespace {

TEST(DomainCoverage, AMeshWithoutInvertedCellsCoversItsDomainOnce) {
  const std::vector<double> volumes = {0.5, 0.25, 0.25};
  EXPECT_DOUBLE_EQ(domain_coverage(volumes, MPI_COMM_WORLD), 1.0);
}

// A folded cell covers its part of the domain again, and its negative volume is taken off the
// domain: cells 1 + 1 + 1 with one of them folded (-1) cover a domain of 1 three times.
TEST(DomainCoverage, AFoldedCellCoversTheDomainAgain) {
  const std::vector<double> volumes = {1.0, 1.0, -1.0};
  EXPECT_DOUBLE_EQ(domain_coverage(volumes, MPI_COMM_WORLD), 3.0);
  EXPECT_GT(domain_coverage(volumes, MPI_COMM_WORLD), kFoldedCoverage);
}

TEST(DomainCoverage, VolumesThatDoNotSumToAPositiveVolumeCoverWithoutBound) {
  EXPECT_TRUE(std::isinf(domain_coverage(std::vector<double>{1.0, -1.0}, MPI_COMM_WORLD)));
  EXPECT_TRUE(std::isinf(domain_coverage(std::vector<double>{}, MPI_COMM_WORLD)));
}

}  // namespace
}  // namespace neomesh
