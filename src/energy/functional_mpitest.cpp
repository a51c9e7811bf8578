// Under `mpiexec -n 2`: the functional of a distributed mesh is that of the serial mesh.
// Dof numbers differ between the two layouts, so only numbering-independent quantities are
// compared: F, the gradient's norm, and the norms of H(α) and L.
#include <gtest/gtest.h>

#include <functional>

#include "energy/functional.hpp"
#include "mesh/generate.hpp"
#include "mesh/mesh.hpp"

namespace neomesh {
namespace {

struct Numbers {
  double value, gradient_norm, hessian_norm, laplacian_norm;
};

// F, ‖F′‖ (free dofs), ‖H(0.5)‖_F and ‖L‖_F with boundary vertices fixed and equal
// desired volumes, on `comm`.
Numbers evaluate(const MeshData& data, MPI_Comm comm) {
  MeshData empty;  // what ranks other than 0 pass
  empty.dim = data.dim;
  Mesh mesh = Mesh::from_data(mpi_rank(comm) == 0 ? data : empty, "test", comm);
  const MeshView& view = mesh.view();
  Functional functional(view, mesh.dofs(), EnergyOptions{}, view.on_boundary);
  OwnedVec x = mesh.coordinates();
  const double volume = mesh_volume(view, mesh.dofs(), x) / mesh.global_num_cells();
  functional.set_desired_volumes(std::vector<double>(view.num_cells, volume));

  Numbers n{};
  OwnedVec gradient = mesh.dofs().create_global_vector();
  n.value = functional.value_and_gradient(x, gradient);
  NM_PETSC(VecNorm(gradient, NORM_2, &n.gradient_norm));
  OwnedMat matrix = functional.create_matrix();
  functional.assemble_hessian(x, 0.5, matrix);
  NM_PETSC(MatNorm(matrix, NORM_FROBENIUS, &n.hessian_norm));
  functional.assemble_laplacian(RieszLaplacian::OptimalCells, x, matrix);
  NM_PETSC(MatNorm(matrix, NORM_FROBENIUS, &n.laplacian_norm));
  return n;
}

// [-1,1]³ in tets, bent by x ↦ x + 0.1 Π_j (1 − x_j²) (boundary kept): not a critical point.
MeshData bent_tetrahedra() {
  MeshData mesh = box(CellType::Tetrahedron, 4);
  for (std::size_t v = 0; v < mesh.coords.size(); v += 3) {
    const double* x = &mesh.coords[v];
    const double bump = 0.1 * (1 - x[0] * x[0]) * (1 - x[1] * x[1]) * (1 - x[2] * x[2]);
    for (int d = 0; d < 3; ++d) mesh.coords[v + d] += bump;
  }
  return mesh;
}

struct Case {
  const char* name;
  std::function<MeshData()> make;
};

class DistributedFunctional : public ::testing::TestWithParam<Case> {};

TEST_P(DistributedFunctional, EqualsSerial) {
  ASSERT_EQ(mpi_size(), 2);
  const MeshData data = GetParam().make();
  const Numbers serial = evaluate(data, PETSC_COMM_SELF);
  const Numbers distributed = evaluate(data, PETSC_COMM_WORLD);
  EXPECT_GT(serial.value, 0.0);
  EXPECT_NEAR(distributed.value, serial.value, 1e-12 * serial.value);
  EXPECT_NEAR(distributed.gradient_norm, serial.gradient_norm, 1e-12 * serial.gradient_norm);
  EXPECT_NEAR(distributed.hessian_norm, serial.hessian_norm, 1e-12 * serial.hessian_norm);
  EXPECT_NEAR(distributed.laplacian_norm, serial.laplacian_norm, 1e-12 * serial.laplacian_norm);
}

INSTANTIATE_TEST_SUITE_P(
    ThesisMeshes, DistributedFunctional,
    ::testing::Values(Case{"square_midpoint", [] { return square_midpoint(16); }},
                      Case{"cube_midpoint", [] { return cube_midpoint(4); }},
                      Case{"tetrahedra", bent_tetrahedra},
                      Case{"triangles", [] { return triangle_equilateral(3, 1); }}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace neomesh
