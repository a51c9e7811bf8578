#include "mesh/dof_map.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace neomesh {

TEST(DofMap, SerialIsIdentity) {
  DofMap dofs = DofMap::serial(2, 3);
  EXPECT_EQ(dofs.num_local_dofs(), 6);
  EXPECT_EQ(dofs.num_global_dofs(), 6);
  OwnedVec g = dofs.create_global_vector();
  std::vector<double> local = {1, 2, 3, 4, 5, 6};
  dofs.add_local_to_global(local, g);
  dofs.add_local_to_global(local, g);
  std::vector<double> back(6);
  dofs.global_to_local(g, back);
  for (int i = 0; i < 6; ++i) EXPECT_DOUBLE_EQ(back[i], 2.0 * local[i]);
}

// Without an SF the local dofs must be the global ones: a permuted numbering is refused rather
// than copied in the wrong order.
TEST(DofMap, WithoutAnSfOnlyTheIdentity) {
  EXPECT_TRUE(DofMap::is_identity({0, 1, 2, 3}));
  EXPECT_FALSE(DofMap::is_identity({0, 1, 3, 2}));
  EXPECT_THROW(DofMap(PETSC_COMM_SELF, 2, 2, 4, nullptr, {0, 1, 3, 2}), Error);
  EXPECT_THROW(DofMap(PETSC_COMM_SELF, 2, 2, 2, nullptr, {0, 1, 2, 3}), Error);  // ghosts
  EXPECT_NO_THROW(DofMap(PETSC_COMM_SELF, 2, 2, 4, nullptr, {0, 1, 2, 3}));
}

}  // namespace neomesh
