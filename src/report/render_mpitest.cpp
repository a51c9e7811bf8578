// Under `mpiexec -n 2`: a distributed mesh draws exactly like the same mesh on one process.
#include <string>

#include <gtest/gtest.h>

#include "core/testing/test_data.hpp"
#include "mesh/generate.hpp"
#include "mesh/serial_view.hpp"
#include "report/render.hpp"

namespace neomesh {
namespace {

// A value per cell that depends only on its input number, so both pictures agree.
double value_of(PetscInt input_cell) {
  return std::sin(0.37 * input_cell);
}

TEST(RenderMeshParallel, GathersToTheSerialPicture) {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const MeshData data = box(CellType::Quadrilateral, 6);
  const PlexMesh mesh = PlexMesh::from_data(rank == 0 ? data : MeshData{}, "box-quad");
  const MeshView& view = mesh.view();
  std::vector<double> values;
  for (PetscInt c = 0; c < view.num_cells; ++c) values.push_back(value_of(view.global_cell[c]));

  const auto dir = testing::shared_scratch_dir("render_parallel");
  render_mesh(mesh, values, dir / "parallel.png");
  if (rank != 0) return;

  const MeshView serial = serial_view(data);
  std::vector<double> serial_values;
  for (PetscInt c = 0; c < serial.num_cells; ++c) serial_values.push_back(value_of(c));
  render_mesh(serial, serial.coords, serial_values, dir / "serial.png");
  EXPECT_EQ(testing::read_file(dir / "parallel.png"), testing::read_file(dir / "serial.png"));
}

}  // namespace
}  // namespace neomesh
