// Under `mpiexec -n 2`: the interface of a level set that crosses the partition is closed, each
// facet listed once over both ranks, every local vertex on it known to the rank, ghosts
// included; where the order of the clean-up does not matter, it is the one a single process
// finds (the tetrahedra's clean-up moves other cells across when its order changes).
#include "boundary/interface.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "generate/generate.hpp"
#include "generate/serial_view.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

using Facet = std::vector<PetscInt>;  // input vertex numbers, in the facet's cyclic order

std::vector<Facet> facets_by_input_number(const MeshView& view, const Interface& in) {
  std::vector<Facet> out;
  for (PetscInt f = 0; f < in.num_facets(); ++f) {
    Facet facet;
    for (PetscInt k = in.offsets[f]; k < in.offsets[f + 1]; ++k)
      facet.push_back(view.input_vertex[in.facet_vertices[k]]);
    out.push_back(facet);
  }
  return out;
}

// The facets as sets of vertices, in order: for comparing two lists of facets.
std::vector<Facet> sorted(std::vector<Facet> facets) {
  for (Facet& f : facets) std::sort(f.begin(), f.end());
  std::sort(facets.begin(), facets.end());
  return facets;
}

// Every rank's facets, as one list on every rank.
std::vector<Facet> all_ranks(const std::vector<Facet>& mine) {
  std::vector<PetscInt> flat;
  for (const Facet& f : mine) {
    flat.push_back(static_cast<PetscInt>(f.size()));
    flat.insert(flat.end(), f.begin(), f.end());
  }
  int counts[2] = {0, 0};
  counts[mpi_rank()] = static_cast<int>(flat.size());
  MPI_Allgather(MPI_IN_PLACE, 1, MPI_INT, counts, 1, MPI_INT, PETSC_COMM_WORLD);
  std::vector<PetscInt> all(counts[0] + counts[1]);
  const int offsets[2] = {0, counts[0]};
  MPI_Allgatherv(flat.data(), static_cast<int>(flat.size()), MPIU_INT, all.data(), counts, offsets,
                 MPIU_INT, PETSC_COMM_WORLD);
  std::vector<Facet> out;
  for (std::size_t i = 0; i < all.size(); i += all[i] + 1)
    out.emplace_back(all.begin() + i + 1, all.begin() + i + 1 + all[i]);
  return out;
}

struct Case {
  CellType type;
  int n;
  const char* phi;
  bool same_as_serial;
};

// How many facets hold each ridge (an edge in 3D, a vertex in 2D): 2 for a closed interface.
std::map<std::vector<PetscInt>, int> ridge_counts(const std::vector<Facet>& facets, int dim) {
  std::map<std::vector<PetscInt>, int> count;
  for (const Facet& f : facets)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const PetscInt a = f[i], b = f[(i + 1) % f.size()];
      ++count[dim == 2 ? std::vector<PetscInt>{a} : std::vector{std::min(a, b), std::max(a, b)}];
    }
  return count;
}

class DistributedInterface : public ::testing::TestWithParam<Case> {};

TEST_P(DistributedInterface, IsClosedAndKnownOnBothSides) {
  ASSERT_EQ(mpi_size(), 2);
  const Case& param = GetParam();
  const MeshData data = box(param.type, param.n);
  const LevelSetFunction phi(param.phi, dimension(param.type));

  const MeshView whole = serial_view(data);
  const Interface serial =
      find_interface(whole, DofMap::serial(whole.dim, whole.num_vertices), whole.coords, phi);
  const std::vector<Facet> expected = sorted(facets_by_input_number(whole, serial));

  MeshData empty;
  empty.dim = data.dim;
  PlexMesh mesh = PlexMesh::from_data(mpi_rank() == 0 ? data : empty, "box", PETSC_COMM_WORLD);
  const MeshView& view = mesh.view();
  const Interface split = find_interface(view, mesh.dofs(), view.coords, phi);
  const std::vector<Facet> mine = facets_by_input_number(view, split);
  int ghosts = 0;  // interface vertices a rank shares with the other: it crosses the partition
  for (PetscInt u : split.vertices) ghosts += !view.owned[u];
  MPI_Allreduce(MPI_IN_PLACE, &ghosts, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_GT(ghosts, 0) << "the interface should cross the partition";

  const std::vector<Facet> found = all_ranks(mine);
  for (const auto& [ridge, count] : ridge_counts(found, data.dim))
    EXPECT_EQ(count, 2) << "ridge at input vertex " << ridge[0];
  const std::vector<Facet> found_sorted = sorted(found);
  EXPECT_EQ(std::adjacent_find(found_sorted.begin(), found_sorted.end()), found_sorted.end())
      << "a facet listed twice";
  if (param.same_as_serial) {
    EXPECT_EQ(found_sorted, expected);
    EXPECT_EQ(split.cells_flipped, serial.cells_flipped);
  }

  std::set<PetscInt> on_interface;
  for (const Facet& f : found) on_interface.insert(f.begin(), f.end());
  for (PetscInt u = 0; u < view.num_vertices; ++u) {
    const bool listed = std::binary_search(split.vertices.begin(), split.vertices.end(), u);
    EXPECT_EQ(listed, on_interface.count(view.input_vertex[u]) == 1)
        << "rank " << mpi_rank() << ", vertex " << view.input_vertex[u] << " ("
        << (view.owned[u] ? "owned" : "ghost") << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Box, DistributedInterface,
    ::testing::Values(Case{CellType::Quadrilateral, 16, "sqrt(x^2+y^2)-0.35", true},
                      Case{CellType::Triangle, 16, "sqrt(x^2+(y-0.1)^2)-0.5", true},
                      Case{CellType::Hexahedron, 8, "sqrt(x^2+y^2+z^2)-0.6", true},
                      Case{CellType::Tetrahedron, 6, "sqrt(x^2+y^2+z^2)-0.6", false}),
    [](const auto& info) { return std::string(name(info.param.type)); });

}  // namespace
}  // namespace neomesh
