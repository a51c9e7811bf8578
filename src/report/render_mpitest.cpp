// Under `mpiexec -n 2`: a distributed mesh draws exactly like the same mesh on one process.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/testing/test_data.hpp"
#include "report/render.hpp"

namespace neomesh {
namespace {

// A value per cell that depends only on its number, so both pictures agree.
double value_of(std::int64_t cell) {
  return std::sin(0.37 * static_cast<double>(cell));
}

// n × n squares of [0, n]², every other one split into two triangles: both cell types, mixed.
MeshArrays mixed_grid(int n) {
  MeshArrays mesh;
  mesh.dim = mesh.coordinate_dim = 2;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      mesh.coordinates.insert(mesh.coordinates.end(), {1.0 * i, 1.0 * j});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int64_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      if ((i + j) % 2 == 0) {
        mesh.cells.insert(mesh.cells.end(), {a, b, c, d});
        mesh.types.push_back(CellType::Quadrilateral);
      } else {
        mesh.cells.insert(mesh.cells.end(), {a, b, c, a, c, d});
        mesh.types.insert(mesh.types.end(), 2, CellType::Triangle);
      }
    }
  return mesh;
}

TEST(RenderMeshParallel, GathersToTheSerialPicture) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const MeshArrays grid = mixed_grid(6);
  const MeshArrays none;
  const MeshArrays& given = rank == 0 ? grid : none;
  const Mesh mesh =
      Mesh::from_arrays(MPI_COMM_WORLD, 2, given.coordinates, given.cells, given.types, "grid");
  std::vector<double> values;
  for (std::int64_t c : mesh.cell_numbers()) values.push_back(value_of(c));

  const auto dir = testing::shared_scratch_dir("render_parallel");
  render_mesh(mesh, values, dir / "parallel.png");
  if (rank != 0) return;

  std::vector<double> serial_values;
  for (std::size_t c = 0; c < grid.types.size(); ++c) serial_values.push_back(value_of(c));
  render_mesh(grid, serial_values, dir / "serial.png");
  EXPECT_EQ(testing::read_file(dir / "parallel.png"), testing::read_file(dir / "serial.png"));
}

}  // namespace
}  // namespace neomesh
