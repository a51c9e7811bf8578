// Under `mpiexec -n 2`: the public Mesh distributed over two processes gives back on the first
// what from_arrays was given, and measures what one process measures.
#include <neomesh/mesh.hpp>

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include <neomesh/generate.hpp>
#include <neomesh/optimizer.hpp>

namespace neomesh {
namespace {

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// An n × n grid of [0,1]² in quads and triangles (every third square split), its vertices
// numbered backwards.
MeshArrays grid(int n) {
  MeshArrays mesh;
  mesh.dim = mesh.coordinate_dim = 2;
  const std::int64_t nv = (n + 1) * (n + 1);
  mesh.coordinates.resize(2 * nv);
  auto number = [&](int i, int j) { return nv - 1 - (j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      mesh.coordinates[2 * number(i, j)] = 1.0 * i / n;
      mesh.coordinates[2 * number(i, j) + 1] = 1.0 * j / n + 0.01 * i * i / n;
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int64_t a = number(i, j), b = number(i + 1, j), c = number(i + 1, j + 1),
                         d = number(i, j + 1);
      if ((i + 2 * j) % 3 == 0) {
        mesh.cells.insert(mesh.cells.end(), {a, b, c, a, c, d});
        mesh.types.insert(mesh.types.end(), 2, CellType::Triangle);
      } else {
        mesh.cells.insert(mesh.cells.end(), {a, b, c, d});
        mesh.types.push_back(CellType::Quadrilateral);
      }
    }
  return mesh;
}

TEST(MeshGatherParallel, GivesBackTheArraysOfFromArrays) {
  const MeshArrays input = grid(8), none;
  const MeshArrays& given = rank() == 0 ? input : none;
  const Mesh mesh =
      Mesh::from_arrays(MPI_COMM_WORLD, 2, given.coordinates, given.cells, given.types);
  EXPECT_GT(mesh.cell_numbers().size(), 0u);  // both processes have cells
  std::vector<double> numbers;
  for (std::int64_t c : mesh.cell_numbers()) numbers.push_back(static_cast<double>(c));
  const MeshArrays out = mesh.gather({{"number", numbers}});
  EXPECT_EQ(out.dim, 2);
  EXPECT_EQ(out.coordinate_dim, 2);
  ASSERT_EQ(out.cell_fields.size(), 1u);
  if (rank() != 0) {
    EXPECT_TRUE(out.coordinates.empty() && out.cells.empty() && out.types.empty());
    return;
  }
  EXPECT_EQ(out.coordinates, input.coordinates);
  EXPECT_EQ(out.cells, input.cells);
  EXPECT_EQ(out.types, input.types);
  for (std::size_t c = 0; c < input.types.size(); ++c)
    EXPECT_EQ(out.cell_fields[0].values[c], static_cast<double>(c));
}

// A surface mesh split over two processes: gather gives back its 3 coordinates per vertex, and
// coordinates set off the surface (lifted by 1) move it on both processes, so that smoothing
// leaves the vertices where they were put rather than on the surface the mesh was made with.
TEST(SurfaceParallel, GathersAndMovesItsSurface) {
  const MeshArrays square = Mesh::generate({.name = "box-quad", .size = 6}).gather();
  MeshArrays bent;  // z = x² over the generated square, on the first process
  if (rank() == 0) {
    for (std::size_t v = 0; v < square.coordinates.size() / 2; ++v) {
      const double x = square.coordinates[2 * v], y = square.coordinates[2 * v + 1];
      bent.coordinates.insert(bent.coordinates.end(), {x, y, x * x});
    }
    bent.cells = square.cells;
    bent.types = square.types;
  }
  Mesh mesh = Mesh::from_arrays(MPI_COMM_WORLD, 3, bent.coordinates, bent.cells, bent.types);
  EXPECT_EQ(mesh.coordinate_dim(), 3);
  EXPECT_GT(mesh.cell_numbers().size(), 0u);  // both processes have cells
  const MeshArrays out = mesh.gather();
  EXPECT_EQ(out.coordinate_dim, 3);
  if (rank() == 0) {
    EXPECT_EQ(out.coordinates, bent.coordinates);
  }
  std::vector<double> x = mesh.coordinates();
  for (std::size_t i = 2; i < x.size(); i += 3) x[i] += 1.0;
  mesh.set_coordinates(x);
  Optimizer(mesh).smooth();
  double lowest = 2.0;
  const std::vector<double> after = mesh.coordinates();
  for (std::size_t i = 2; i < after.size(); i += 3) lowest = std::min(lowest, after[i]);
  MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  EXPECT_GE(lowest, 1.0 - 1e-12);
}

TEST(GenerateMeshParallel, DistributesTheSerialMesh) {
  const GenerateOptions options{.name = "box-tet", .size = 3, .jitter = 0.2, .rotate_degrees = 10};
  const Mesh mesh = Mesh::generate(options, MPI_COMM_WORLD);
  const Mesh serial = Mesh::generate(options, MPI_COMM_SELF);
  EXPECT_GT(mesh.cell_numbers().size(), 0u);
  EXPECT_EQ(mesh.num_cells(), serial.num_cells());
  EXPECT_NEAR(mesh.volume(), serial.volume(), 1e-12);
  EXPECT_NEAR(mesh.max_boundary_distance(Mesh::generate(options, MPI_COMM_WORLD)), 0.0, 1e-14);
  const MeshArrays whole = mesh.gather(), alone = serial.gather();
  if (rank() == 0) {
    EXPECT_EQ(whole.cells, alone.cells);
    EXPECT_EQ(whole.coordinates, alone.coordinates);
  }
}

}  // namespace
}  // namespace neomesh
