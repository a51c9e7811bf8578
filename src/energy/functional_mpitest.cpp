// Under `mpiexec -n 2`: the functional of a distributed mesh is that of the serial mesh: F,
// the gradient's norm, and H(α) and L entry by entry (dofs matched by vertex coordinates,
// since the two layouts number them differently).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>

#include "core/collective_error.hpp"
#include "energy/functional.hpp"
#include "generate/generate.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

// The mesh given on rank 0, distributed over `comm`.
PlexMesh distribute(const MeshData& data, MPI_Comm comm) {
  MeshData empty;  // what ranks other than 0 pass
  empty.dim = data.dim;
  return PlexMesh::from_data(mpi_rank(comm) == 0 ? data : empty, "test", comm);
}

struct Numbers {
  double value, gradient_norm, hessian_norm, laplacian_norm;
};

// F, ‖F′‖ (free dofs), ‖H(0.5)‖_F and ‖L‖_F with boundary vertices fixed and equal
// desired volumes, on `comm`.
Numbers evaluate(const MeshData& data, MPI_Comm comm) {
  PlexMesh mesh = distribute(data, comm);
  const MeshView& view = mesh.view();
  OwnedVec x = mesh.coordinates();
  const double volume = mesh_volume(view, mesh.dofs(), x) / mesh.global_num_cells();
  const Functional functional(
      EnergyOptions{}, Problem(view, mesh.dofs(), view.on_boundary)
                           .with_desired_volumes(std::vector<double>(view.num_cells, volume)));

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

// A mesh on `comm` with the functional of `evaluate` and its matrices H(0.5), L on the
// optimal cells and L on the current mesh.
struct Assembled {
  PlexMesh mesh;
  std::unique_ptr<Functional> functional;
  OwnedMat hessian, optimal_laplacian, current_laplacian;

  Assembled(const MeshData& data, MPI_Comm comm) : mesh(distribute(data, comm)) {
    const MeshView& view = mesh.view();
    OwnedVec x = mesh.coordinates();
    const double volume = mesh_volume(view, mesh.dofs(), x) / mesh.global_num_cells();
    functional = std::make_unique<Functional>(
        EnergyOptions{}, Problem(view, mesh.dofs(), view.on_boundary)
                             .with_desired_volumes(std::vector<double>(view.num_cells, volume)));
    hessian = functional->create_matrix();
    functional->assemble_hessian(x, 0.5, hessian);
    optimal_laplacian = functional->create_laplacian_matrix();
    functional->assemble_laplacian(RieszLaplacian::OptimalCells, x, optimal_laplacian);
    current_laplacian = functional->create_laplacian_matrix();
    functional->assemble_laplacian(RieszLaplacian::CurrentMesh, x, current_laplacian);
  }

  // The coordinates of every vertex (by global vertex number), on every rank.
  std::vector<std::array<double, 3>> all_coordinates() const {
    OwnedVec x = mesh.coordinates(), all;
    OwnedScatter to_all;
    NM_PETSC(VecScatterCreateToAll(x, to_all.out(), all.out()));
    NM_PETSC(VecScatterBegin(to_all, x, all, INSERT_VALUES, SCATTER_FORWARD));
    NM_PETSC(VecScatterEnd(to_all, x, all, INSERT_VALUES, SCATTER_FORWARD));
    VecReadView values(all);
    const int d = mesh.dim();
    std::vector<std::array<double, 3>> coords(values.size() / d, {0.0, 0.0, 0.0});
    for (PetscInt i = 0; i < values.size(); ++i) coords[i / d][i % d] = values[i];
    return coords;
  }
};

// The serial dof of each distributed dof: the same component of the vertex at the same place.
std::vector<PetscInt> serial_dofs(const Assembled& distributed, const Assembled& serial) {
  std::map<std::array<double, 3>, PetscInt> serial_vertex;
  const auto serial_coords = serial.all_coordinates();
  for (std::size_t v = 0; v < serial_coords.size(); ++v) serial_vertex[serial_coords[v]] = v;
  const int d = serial.mesh.dim();
  std::vector<PetscInt> dof;
  for (const auto& x : distributed.all_coordinates())
    for (int a = 0; a < d; ++a) dof.push_back(d * serial_vertex.at(x) + a);
  return dof;
}

// The first entry of this rank's rows of `distributed` that is not in the serial matrix or
// differs from it by more than round-off of its row's largest entry; "" if there is none.
std::string first_difference(Mat distributed, Mat serial, const std::vector<PetscInt>& serial_dof) {
  PetscInt first = 0, end = 0;
  NM_PETSC(MatGetOwnershipRange(distributed, &first, &end));
  std::string difference;
  for (PetscInt row = first; row < end && difference.empty(); ++row) {
    std::map<PetscInt, double> expected;
    PetscInt n = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* vals = nullptr;
    NM_PETSC(MatGetRow(serial, serial_dof[row], &n, &cols, &vals));
    double largest = 0.0;
    for (PetscInt k = 0; k < n; ++k) {
      expected[cols[k]] = vals[k];
      largest = std::max(largest, std::abs(vals[k]));
    }
    NM_PETSC(MatRestoreRow(serial, serial_dof[row], &n, &cols, &vals));
    NM_PETSC(MatGetRow(distributed, row, &n, &cols, &vals));
    if (static_cast<std::size_t>(n) != expected.size())
      difference = fmt::format("row {}: {} entries, serial {}", row, n, expected.size());
    for (PetscInt k = 0; k < n && difference.empty(); ++k) {
      const auto it = expected.find(serial_dof[cols[k]]);
      if (it == expected.end() || std::abs(vals[k] - it->second) > 1e-13 * largest)
        difference = fmt::format("row {}, column {}: {}, serial {}", row, cols[k], vals[k],
                                 it == expected.end() ? "no entry" : fmt::format("{}", it->second));
    }
    NM_PETSC(MatRestoreRow(distributed, row, &n, &cols, &vals));
  }
  return difference;
}

// Fails (reported by rank 0) if any rank found a difference.
void expect_no_difference_on_any_rank(const std::string& what, const std::string& difference) {
  try {
    throw_if_any(PETSC_COMM_WORLD, difference.empty() ? "" : what + ", " + difference);
  } catch (const Error& e) {
    ADD_FAILURE() << e.what();
  }
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

TEST_P(DistributedFunctional, MatricesEqualSerialEntryByEntry) {
  ASSERT_EQ(mpi_size(), 2);
  const MeshData data = GetParam().make();
  const Assembled serial(data, PETSC_COMM_SELF);
  const Assembled distributed(data, PETSC_COMM_WORLD);
  // Both ranks hold cells, and some rows receive entries from the other rank.
  ASSERT_GT(distributed.mesh.view().num_cells, 0);
  ASSERT_LT(distributed.mesh.view().num_cells, data.num_cells());
  const std::vector<PetscInt> serial_dof = serial_dofs(distributed, serial);
  expect_no_difference_on_any_rank(
      "H(0.5)", first_difference(distributed.hessian, serial.hessian, serial_dof));
  expect_no_difference_on_any_rank(
      "L (optimal cells)",
      first_difference(distributed.optimal_laplacian, serial.optimal_laplacian, serial_dof));
  expect_no_difference_on_any_rank(
      "L (current mesh)",
      first_difference(distributed.current_laplacian, serial.current_laplacian, serial_dof));
}

// The scalar Laplacian's MAIJ is laid out like the DofMap on each rank (interlaced
// components of the owned vertices) and applies the vector Laplacian. Made after H and L
// (the pattern's columns are then read back from H).
TEST_P(DistributedFunctional, ScalarLaplacianActsAsTheVectorLaplacian) {
  ASSERT_EQ(mpi_size(), 2);
  const Assembled a(GetParam().make(), PETSC_COMM_WORLD);
  ASSERT_TRUE(a.functional->laplacian_is_scalar());
  OwnedVec x = a.mesh.coordinates();
  OwnedMat scalar = a.functional->create_scalar_laplacian_matrix();
  a.functional->assemble_laplacian(RieszLaplacian::OptimalCells, x, scalar);
  PetscInt rows = 0, columns = 0;
  NM_PETSC(MatGetLocalSize(scalar, &rows, &columns));
  EXPECT_EQ(rows, a.mesh.dofs().num_owned_dofs());
  EXPECT_EQ(columns, a.mesh.dofs().num_owned_dofs());
  OwnedVec v = a.mesh.dofs().create_global_vector(), expected, product;
  NM_PETSC(VecDuplicate(v, expected.out()));
  NM_PETSC(VecDuplicate(v, product.out()));
  {
    PetscInt first = 0;
    NM_PETSC(VecGetOwnershipRange(v, &first, nullptr));
    VecWriteView out(v);
    for (PetscInt i = 0; i < out.size(); ++i) out[i] = std::sin(1.0 + first + i);
  }
  NM_PETSC(MatMult(a.optimal_laplacian, v, expected));
  NM_PETSC(MatMult(scalar, v, product));
  double size = 0.0, difference = 0.0;
  NM_PETSC(VecNorm(expected, NORM_2, &size));
  NM_PETSC(VecAXPY(product, -1.0, expected));
  NM_PETSC(VecNorm(product, NORM_2, &difference));
  EXPECT_LE(difference, 1e-14 * size);
}

// A box of n cells per direction with interior vertices moved by up to 20% of the cell size
// (on the uniform box the gradient is round-off, nothing to compare).
MeshData jittered_box(CellType type, int n) {
  MeshData mesh = box(type, n);
  jitter(mesh, 2.0 / n, 0.2, 5);
  return mesh;
}

INSTANTIATE_TEST_SUITE_P(
    ThesisMeshes, DistributedFunctional,
    ::testing::Values(Case{"square_midpoint", [] { return square_midpoint(16); }},
                      Case{"cube_midpoint", [] { return cube_midpoint(4); }},
                      Case{"tetrahedra", bent_tetrahedra},
                      Case{"triangles", [] { return triangle_equilateral(3, 1); }},
                      Case{"wedges", [] { return jittered_box(CellType::Wedge, 4); }},
                      Case{"pyramids", [] { return jittered_box(CellType::Pyramid, 3); }}),
    [](const auto& info) { return std::string(info.param.name); });

// An inverted cell on rank 0 only: assembly fails on both ranks (instead of rank 1 waiting
// forever for rank 0), naming the cell.
TEST(DistributedFunctionalErrors, InvertedCellFailsOnEveryRank) {
  ASSERT_EQ(mpi_size(), 2);
  const PlexMesh mesh = distribute(box(CellType::Quadrilateral, 8), PETSC_COMM_WORLD);
  const MeshView& view = mesh.view();
  const Functional functional(
      EnergyOptions{}, Problem(view, mesh.dofs(), view.on_boundary)
                           .with_desired_volumes(std::vector<double>(view.num_cells, 1.0 / 16)));
  OwnedVec x = mesh.coordinates();
  if (mpi_rank() == 0) {
    // An owned vertex whose 4 cells are all on rank 0 moves past the opposite corner of one
    // of them (2 h along the diagonal).
    std::vector<int> cells(view.num_vertices, 0);
    for (PetscInt v : view.blocks[0].vertices) ++cells[v];
    const auto v = std::find(cells.begin(), cells.end(), 4) - cells.begin();
    ASSERT_LT(v, view.num_vertices);
    ASSERT_TRUE(view.owned[v]);
    PetscInt first = 0;
    NM_PETSC(VecGetOwnershipRange(x, &first, nullptr));
    VecWriteView coords(x);
    for (int a = 0; a < 2; ++a) coords[mesh.dofs().global_dof()[2 * v + a] - first] += 0.5;
  }
  OwnedMat hessian = functional.create_matrix();
  try {
    functional.assemble_hessian(x, 0.5, hessian);
    ADD_FAILURE() << "no error on rank " << mpi_rank();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is inverted or degenerate"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace neomesh
