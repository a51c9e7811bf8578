// Under `mpiexec -n 2`: a curved mesh's node mesh distributed with each curved cell's sub-cells
// on one process, whose curved cells, certificate and points are the serial mesh's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "generate/generate.hpp"
#include "geometry/curved_quality.hpp"
#include "geometry/node_mesh.hpp"
#include "mesh/from_input_vertices.hpp"
#include "mesh/gather.hpp"
#include "mesh/raise_order.hpp"

namespace neomesh {
namespace {

// A box of `type` raised to second order on rank 0 (empty elsewhere), its vertices jittered and
// its high-order nodes bent, so that the cells are curved and their quality varies.
InputMesh curved_box(CellType type, int n) {
  if (mpi_rank(MPI_COMM_WORLD) != 0) return {};
  MeshData data = box(type, n);
  jitter(data, 2.0 / n, 0.1, 3);
  InputMesh mesh = input_from_data(data);
  raise_to_second_order(mesh);
  std::vector<double>& xyz = mesh.high_order.xyz;
  for (std::size_t i = 0; i < xyz.size(); ++i)
    if (i % 3 < static_cast<std::size_t>(mesh.dim)) xyz[i] += 0.02 / n * std::sin(7.0 * i);
  return mesh;
}

void expect_the_serial_mesh(CellType type, int n) {
  const MPI_Comm comm = MPI_COMM_WORLD;
  const InputMesh input = curved_box(type, n);
  const DistributedNodeMesh nodes = distribute_node_mesh(input, "box", comm);
  const MeshView& view = nodes.nodes.view();
  const int d = view.dim;

  // Every curved cell on one process, with all its sub-cells (2^d of each), and work for each.
  EXPECT_GT(nodes.cells.num_cells, 0);
  EXPECT_EQ(view.num_cells, (PetscInt{1} << d) * nodes.cells.num_cells);
  const std::vector<PetscInt> numbers = gatherv(comm, nodes.cells.global_cell, MPIU_INT);
  if (mpi_rank(comm) == 0) {
    std::vector<PetscInt> sorted = numbers, all(input.num_cells());
    std::sort(sorted.begin(), sorted.end());
    std::iota(all.begin(), all.end(), PetscInt{0});
    EXPECT_EQ(sorted, all);
  }

  // The certificate over the processes is the serial one; mean up to the order of the sum.
  const CurvedQualitySummary distributed = curved_quality(nodes.cells, view.coords, comm);
  double serial[5] = {};
  if (mpi_rank(comm) == 0) {
    const CurvedQualitySummary s = curved_quality(input);
    const double values[5] = {static_cast<double>(s.not_valid), s.scaled_jacobian.min,
                              s.scaled_jacobian.mean, s.scaled_jacobian.max,
                              s.scaled_jacobian_lower_bound};
    std::copy(values, values + 5, serial);
  }
  MPI_Bcast(serial, 5, MPI_DOUBLE, 0, comm);
  EXPECT_EQ(distributed.not_valid, static_cast<std::int64_t>(serial[0]));
  EXPECT_EQ(distributed.scaled_jacobian.min, serial[1]);
  EXPECT_NEAR(distributed.scaled_jacobian.mean, serial[2], 1e-14);
  EXPECT_EQ(distributed.scaled_jacobian.max, serial[3]);
  EXPECT_EQ(distributed.scaled_jacobian_lower_bound, serial[4]);
  EXPECT_LT(distributed.scaled_jacobian.min, distributed.scaled_jacobian.max);

  // The points gathered in input numbering, and back at every local vertex.
  const std::vector<double> points = gather_points(view, view.coords, nodes.points, comm);
  if (mpi_rank(comm) == 0) {
    EXPECT_EQ(points, curved_point_coordinates(input));
  }
  const std::vector<double> back =
      FromInputVertices(view, static_cast<PetscInt>(points.size()) / d, comm)(points, d);
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    if (view.input_vertex[v] < nodes.points) {
      for (int j = 0; j < d; ++j) EXPECT_EQ(back[d * v + j], view.coords[d * v + j]);
    }
}

TEST(NodeMeshMpi, TrianglesKeepTheirSubcellsTogetherAndMeasureAsSerially) {
  expect_the_serial_mesh(CellType::Triangle, 6);
}

TEST(NodeMeshMpi, TetrahedraKeepTheirSubcellsTogetherAndMeasureAsSerially) {
  expect_the_serial_mesh(CellType::Tetrahedron, 3);
}

TEST(NodeMeshMpi, HexahedraKeepTheirSubcellsTogetherAndMeasureAsSerially) {
  expect_the_serial_mesh(CellType::Hexahedron, 3);
}

}  // namespace
}  // namespace neomesh
