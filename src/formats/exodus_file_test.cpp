#include "formats/exodus_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "mesh/cell_order.hpp"

namespace neomesh {
namespace {

// A facet as canonical vertices, rotated to start at its smallest: two cycles that list the
// same facet in the same sense compare equal.
std::vector<int> rotated(std::vector<int> cycle) {
  std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
  return cycle;
}

// Exodus' side tables name the facets of cell_type.hpp, each once, counter-clockwise seen from
// outside in 3D (the manual draws outward normals by the right-hand rule).
TEST(ExodusSides, AreTheFacetsOfEachCellType) {
  for (CellType t : kAllCellTypes) {
    const ExodusSides& table = exodus_sides(t);
    const CellFacts& f = facts(t);
    ASSERT_EQ(table.count, f.num_facets) << f.name;
    std::vector<std::vector<int>> sides, facets;
    for (int s = 0; s < table.count; ++s) {
      std::vector<int> side;
      for (int j = 0; j < table.sides[s].size; ++j)
        side.push_back(gmsh_from_canonical(t)[table.sides[s].nodes[j]]);
      std::vector<int> facet(f.facets[s].vertices.begin(),
                             f.facets[s].vertices.begin() + f.facets[s].size);
      if (f.dim == 2) {  // an edge: its ends, in either order
        std::sort(side.begin(), side.end());
        std::sort(facet.begin(), facet.end());
      }
      sides.push_back(rotated(side));
      facets.push_back(rotated(facet));
    }
    std::sort(sides.begin(), sides.end());
    std::sort(facets.begin(), facets.end());
    EXPECT_EQ(sides, facets) << f.name;
  }
}

TEST(ExodusTypeNames, ReadInAnyCaseWithAnyNodeCountAndBackAsWritten) {
  bool shell = true;
  EXPECT_EQ(exodus_cell_type("tri3", shell), CellType::Triangle);
  EXPECT_FALSE(shell);
  EXPECT_EQ(exodus_cell_type("TRIANGLE", shell), CellType::Triangle);
  EXPECT_EQ(exodus_cell_type("SHELL4", shell), CellType::Quadrilateral);
  EXPECT_TRUE(shell);
  EXPECT_EQ(exodus_cell_type("TET4", shell), CellType::Tetrahedron);
  EXPECT_EQ(exodus_cell_type("TETRA10", shell), CellType::Tetrahedron);  // refused by nodes
  EXPECT_EQ(exodus_cell_type("BAR2", shell), std::nullopt);
  EXPECT_EQ(exodus_cell_type("NSIDED", shell), std::nullopt);
  for (CellType t : kAllCellTypes) EXPECT_EQ(exodus_cell_type(exodus_type_name(t), shell), t);
  EXPECT_EQ(exodus_point_or_line("BAR2"), 1);
  EXPECT_EQ(exodus_point_or_line("beam"), 1);
  EXPECT_EQ(exodus_point_or_line("SPHERE"), 0);
  EXPECT_EQ(exodus_point_or_line("NSIDED"), std::nullopt);
}

}  // namespace
}  // namespace neomesh
