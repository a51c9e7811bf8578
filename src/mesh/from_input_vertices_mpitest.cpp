// Under `mpiexec -n 2` (or more): tables on rank 0 by input vertex reach every process' local
// vertices, one star forest serving tables of any type and width.
#include "mesh/from_input_vertices.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

// An n × n grid of quadrilaterals on rank 0 (empty elsewhere), distributed.
PlexMesh distributed_grid(int n) {
  MeshData data;
  if (mpi_rank(MPI_COMM_WORLD) == 0) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) data.coords.insert(data.coords.end(), {1.0 * i, 1.0 * j});
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::int64_t a = j * (n + 1) + i;
        data.cells.insert(data.cells.end(), {a, a + 1, a + n + 1, a + n + 2});  // tensor order
      }
  }
  return PlexMesh::from_data(data, "grid");
}

TEST(FromInputVerticesMpi, EveryLocalVertexGetsItsInputVertexsValues) {
  const PlexMesh mesh = distributed_grid(6);
  const MeshView& view = mesh.view();
  ASSERT_LT(view.num_vertices, mesh.global_num_vertices());  // the vertices are split
  const PetscInt n = mpi_rank(mesh.comm()) == 0 ? mesh.global_num_vertices() : 0;
  std::vector<int> ints;
  std::vector<std::uint8_t> bytes;
  std::vector<double> triples;
  for (PetscInt i = 0; i < n; ++i) {
    ints.push_back(static_cast<int>(7 * i - 30));
    bytes.push_back(static_cast<std::uint8_t>(i % 5));
    triples.insert(triples.end(), {0.5 * i, -1.0 * i, 1.0 / (i + 1)});
  }
  const FromInputVertices fetch(view, n, mesh.comm());
  const std::vector<int> local_ints = fetch(ints);
  const std::vector<std::uint8_t> local_bytes = fetch(bytes);
  const std::vector<double> local_triples = fetch(triples, 3);
  ASSERT_EQ(local_ints.size(), static_cast<std::size_t>(view.num_vertices));
  ASSERT_EQ(local_triples.size(), static_cast<std::size_t>(3 * view.num_vertices));
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const PetscInt i = view.input_vertex[v];
    EXPECT_EQ(local_ints[v], 7 * i - 30);
    EXPECT_EQ(local_bytes[v], i % 5);
    EXPECT_EQ(local_triples[3 * v], 0.5 * i);
    EXPECT_EQ(local_triples[3 * v + 1], -1.0 * i);
    EXPECT_EQ(local_triples[3 * v + 2], 1.0 / (i + 1));
  }
}

}  // namespace
}  // namespace neomesh
