// Under `mpiexec -n 2`: the facets one rank's cells share with the other's are found on both
// sides, in the same order, and values pass across them.
#include "mesh/partition_facets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

#include "generate/generate.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

constexpr int kMaxFacets = PartitionFacets::kMaxFacets;

// Whether all of the facet's vertices lie in one side of the box [-1,1]^d.
bool on_a_box_side(const MeshView& view, const CellBlock& block, PetscInt c, int f) {
  const FacetVertices& facet = facts(block.type).facets[f];
  for (int j = 0; j < view.dim; ++j)
    for (double side : {-1.0, 1.0}) {
      bool all = true;
      for (int k = 0; k < facet.size; ++k)
        all = all && view.coords[block.cell(c)[facet.vertices[k]] * view.dim + j] == side;
      if (all) return true;
    }
  return false;
}

std::vector<PetscInt> sorted_vertices(const CellBlock& block, PetscInt c, int f) {
  const FacetVertices& facet = facts(block.type).facets[f];
  std::vector<PetscInt> key;
  for (int k = 0; k < facet.size; ++k) key.push_back(block.cell(c)[facet.vertices[k]]);
  std::sort(key.begin(), key.end());
  return key;
}

class SharedFacets : public ::testing::TestWithParam<CellType> {};

TEST_P(SharedFacets, AreThePartitionsFacetsOnBothSides) {
  ASSERT_EQ(mpi_size(), 2);
  MeshData empty;
  empty.dim = dimension(GetParam());
  const MeshData data = box(GetParam(), 4);
  PlexMesh mesh = PlexMesh::from_data(mpi_rank() == 0 ? data : empty, "box", PETSC_COMM_WORLD);
  const MeshView& view = mesh.view();
  ASSERT_GT(view.num_cells, 0);

  // Open: every facet not shared by two local cells (counted by its sorted vertices).
  std::map<std::vector<PetscInt>, int> count;
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int f = 0; f < facts(block.type).num_facets; ++f) ++count[sorted_vertices(block, c, f)];
  std::vector<std::uint8_t> open(view.num_cells * kMaxFacets, 0);
  int boundary = 0;
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int f = 0; f < facts(block.type).num_facets; ++f) {
        const bool alone = count[sorted_vertices(block, c, f)] == 1;
        open[(block.first_cell + c) * kMaxFacets + f] = alone;
        boundary += alone && on_a_box_side(view, block, c, f);
      }

  const PartitionFacets shared(view, PETSC_COMM_WORLD, open);
  // Every open facet is on the box's boundary or shared with the other rank, never both.
  const int opened = static_cast<int>(std::count(open.begin(), open.end(), 1));
  EXPECT_EQ(boundary + static_cast<int>(shared.facets().size()), opened);
  EXPECT_GT(shared.facets().size(), 0u);
  int sizes[2] = {0, 0};
  sizes[mpi_rank()] = static_cast<int>(shared.facets().size());
  MPI_Allgather(MPI_IN_PLACE, 1, MPI_INT, sizes, 1, MPI_INT, PETSC_COMM_WORLD);
  EXPECT_EQ(sizes[0], sizes[1]);

  // What crosses is the other side's: each rank sends its cell's input number (mod 251).
  std::vector<std::uint8_t> mine;
  for (const PartitionFacets::Facet& facet : shared.facets()) {
    EXPECT_EQ(facet.rank, 1 - mpi_rank());
    EXPECT_TRUE(open[facet.cell * kMaxFacets + facet.facet]);
    mine.push_back(static_cast<std::uint8_t>(view.global_cell[facet.cell] % 251));
  }
  const std::vector<std::uint8_t> theirs = shared.exchange(mine);
  for (std::size_t k = 0; k < theirs.size(); ++k)
    EXPECT_EQ(theirs[k], shared.facets()[k].remote_cell % 251) << "facet " << k;
}

INSTANTIATE_TEST_SUITE_P(Box, SharedFacets,
                         ::testing::Values(CellType::Triangle, CellType::Quadrilateral,
                                           CellType::Tetrahedron, CellType::Hexahedron),
                         [](const auto& info) { return std::string(name(info.param)); });

}  // namespace
}  // namespace neomesh
