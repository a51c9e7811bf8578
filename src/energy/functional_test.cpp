#include "energy/functional.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/testing/thread_count.hpp"
#include "energy/functional_test_util.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {
namespace {

using testing::entry;
using testing::kFdTolerance;
using testing::norm;
using testing::set_entry;

// A serial mesh with boundary vertices fixed and the Functional on it. Not movable: the
// Functional keeps references to the view and the DofMap.
struct MeshCase {
  MeshData data;
  MeshView view;
  DofMap dofs;
  Functional functional;
  OwnedVec x;

  explicit MeshCase(MeshData mesh, const EnergyOptions& options = {})
      : data(std::move(mesh)),
        view(serial_view(data)),
        dofs(DofMap::serial(data.dim, static_cast<PetscInt>(data.num_vertices()))),
        functional(options, Problem(view, dofs, view.on_boundary)),
        x(dofs.create_global_vector()) {
    VecWriteView out(x);
    for (std::size_t i = 0; i < data.coords.size(); ++i)
      out[static_cast<PetscInt>(i)] = data.coords[i];
  }
  MeshCase(const MeshCase&) = delete;

  // The functional of the problem with these targets instead.
  void set_desired_volumes(std::span<const double> volumes) {
    functional =
        Functional(functional.options(), functional.problem().with_desired_volumes(volumes));
  }
  void set_target_shapes(std::span<const double> shapes, std::span<const double> weights) {
    const Problem& problem = functional.problem();
    functional = Functional(functional.options(),
                            problem.with_targets(problem.desired_volumes(), shapes, weights));
  }

  // Equal desired volumes whose sum is the mesh's volume, each scaled by a factor in
  // [1 − spread, 1 + spread].
  void set_volumes(double spread = 0.0, unsigned seed = 0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-spread, spread);
    const double mean = mesh_volume(view, dofs, x) / view.num_cells;
    std::vector<double> volumes(view.num_cells);
    for (double& v : volumes) v = mean * (1.0 + u(rng));
    set_desired_volumes(volumes);
  }

  // 1 at free dofs, 0 at those of the (fixed) boundary vertices.
  std::vector<double> free_dofs() const {
    std::vector<double> mask(dofs.num_local_dofs());
    for (std::size_t l = 0; l < mask.size(); ++l) mask[l] = view.on_boundary[l / view.dim] ? 0 : 1;
    return mask;
  }
};

// A box [-1,1]^d with n cells per direction, interior vertices moved by up to 20% of h.
MeshData perturbed_box(CellType type, int n, unsigned seed) {
  MeshData mesh = box(type, n);
  jitter(mesh, 2.0 / n, 0.2, seed);
  return mesh;
}

class FunctionalTest : public ::testing::TestWithParam<CellType> {};

INSTANTIATE_TEST_SUITE_P(AllCellTypes, FunctionalTest, ::testing::ValuesIn(kAllCellTypes),
                         [](const auto& info) { return std::string(name(info.param)); });

// Tests that need every cell to be its optimal cell on a box: squares and cubes only (a box
// split into simplices is not equilateral).
class Q1FunctionalTest : public ::testing::TestWithParam<CellType> {};

INSTANTIATE_TEST_SUITE_P(Q1Cells, Q1FunctionalTest,
                         ::testing::Values(CellType::Quadrilateral, CellType::Hexahedron),
                         [](const auto& info) { return std::string(name(info.param)); });

int cells_per_direction(CellType type) {
  return dimension(type) == 2 ? 4 : 3;
}

TEST_P(FunctionalTest, GradientMatchesFiniteDifferencesOfValue) {
  MeshCase p(perturbed_box(GetParam(), cells_per_direction(GetParam()), 21));
  p.set_volumes(0.5, 22);
  const std::vector<double> free = p.free_dofs();
  testing::expect_gradient_matches_differences(p.functional, p.x,
                                               [&free](PetscInt i) { return free[i] != 0; });
}

TEST_P(FunctionalTest, HessianMatchesFiniteDifferencesOfGradient) {
  MeshCase p(perturbed_box(GetParam(), cells_per_direction(GetParam()), 23));
  p.set_volumes(0.5, 24);
  const std::vector<double> free = p.free_dofs();
  testing::expect_hessian_matches_differences(p.functional, p.x,
                                              [&free](PetscInt i) { return free[i] != 0; });
}

// Every cell of a uniform square/cube grid with equal desired volumes is its optimal cell.
TEST_P(Q1FunctionalTest, UniformGridWithEqualVolumesIsOptimal) {
  MeshCase p(box(GetParam(), 4));
  p.set_volumes();
  OwnedVec gradient = p.dofs.create_global_vector();
  EXPECT_NEAR(p.functional.value_and_gradient(p.x, gradient), 0.0, 1e-13);
  EXPECT_LT(norm(gradient), 1e-12);
  const CellFields fields = p.functional.cell_fields(p.x);
  for (PetscInt c = 0; c < p.view.num_cells; ++c) {
    EXPECT_NEAR(fields.energy[c], 0.0, 1e-14);
    EXPECT_NEAR(fields.min_det[c], 1.0, 1e-13);
    EXPECT_NEAR(fields.volume_ratio[c], 1.0, 1e-13);
  }
}

TEST_P(FunctionalTest, InvariantUnderRotationAndTranslation) {
  const CellType type = GetParam();
  MeshData moved = perturbed_box(type, cells_per_direction(type), 25);
  MeshCase original(moved);
  original.set_volumes(0.3, 26);
  rotate(moved, 27.0);
  for (std::size_t i = 0; i < moved.coords.size(); ++i) moved.coords[i] += 0.5 + i % moved.dim;
  MeshCase rigid(std::move(moved));
  rigid.set_desired_volumes(original.functional.problem().desired_volumes());
  const double f = original.functional.value(original.x);
  EXPECT_GT(f, 0.0);
  EXPECT_NEAR(rigid.functional.value(rigid.x), f, 1e-13 * f);
}

// On a mesh whose cells are their optimal cells, the current mesh's Laplacian is the
// optimal cells' one; either has the identity's rows at fixed dofs. The Laplacian's own
// pattern (no couplings between components) holds the same values as H's pattern.
TEST_P(Q1FunctionalTest, LaplaciansAgreeOnOptimalMesh) {
  MeshCase p(box(GetParam(), 3));
  p.set_volumes();
  OwnedMat optimal = p.functional.create_laplacian_matrix();
  OwnedMat current = p.functional.create_matrix();
  p.functional.assemble_laplacian(RieszLaplacian::OptimalCells, p.x, optimal);
  p.functional.assemble_laplacian(RieszLaplacian::CurrentMesh, p.x, current);
  PetscReal size = 0.0, difference = 0.0;
  NM_PETSC(MatNorm(optimal, NORM_FROBENIUS, &size));
  NM_PETSC(MatAXPY(current, -1.0, optimal, SUBSET_NONZERO_PATTERN));
  NM_PETSC(MatNorm(current, NORM_FROBENIUS, &difference));
  EXPECT_LT(difference, 1e-13 * size);
  // The first fixed dof: its diagonal entry is the identity's.
  PetscInt fixed_row = -1;
  const std::vector<double> free = p.free_dofs();
  for (PetscInt i = 0; i < p.dofs.num_global_dofs() && fixed_row < 0; ++i)
    if (!free[i]) fixed_row = i;
  PetscScalar diagonal = 0.0;
  NM_PETSC(MatGetValues(optimal, 1, &fixed_row, 1, &fixed_row, &diagonal));
  EXPECT_EQ(diagonal, 1.0);
}

// L = L₁ ⊗ I: the scalar Laplacian's MAIJ applies exactly the vector Laplacian (the same
// sums), with the identity at fixed vertices; for either kind of Laplacian.
TEST_P(FunctionalTest, ScalarLaplacianActsAsTheVectorLaplacian) {
  MeshCase p(perturbed_box(GetParam(), cells_per_direction(GetParam()), 31));
  p.set_volumes(0.3, 32);
  ASSERT_TRUE(p.functional.laplacian_is_scalar());
  OwnedVec v = p.dofs.create_global_vector(), expected = p.dofs.create_global_vector(),
           product = p.dofs.create_global_vector();
  {
    VecWriteView out(v);
    for (PetscInt i = 0; i < out.size(); ++i) out[i] = std::sin(1.0 + i);
  }
  for (RieszLaplacian kind : {RieszLaplacian::OptimalCells, RieszLaplacian::CurrentMesh}) {
    OwnedMat vector = p.functional.create_laplacian_matrix();
    OwnedMat scalar = p.functional.create_scalar_laplacian_matrix();
    p.functional.assemble_laplacian(kind, p.x, vector);
    p.functional.assemble_laplacian(kind, p.x, scalar);
    NM_PETSC(MatMult(vector, v, expected));
    NM_PETSC(MatMult(scalar, v, product));
    NM_PETSC(VecAXPY(product, -1.0, expected));
    EXPECT_LE(norm(product), 1e-14 * norm(expected));
  }
  // Some coordinates fixed, others not: no scalar Laplacian.
  MeshData mesh = box(CellType::Quadrilateral, 2);
  const MeshView view = serial_view(mesh);
  const DofMap dofs = DofMap::serial(2, view.num_vertices);
  FixedDofs fixed{std::vector<std::uint8_t>(2 * view.num_vertices, 0)};
  fixed.flags[0] = 1;
  const Functional partly(EnergyOptions{}, Problem(view, dofs, fixed));
  EXPECT_FALSE(partly.laplacian_is_scalar());
  EXPECT_THROW(partly.create_scalar_laplacian_matrix(), Error);
}

// H(α) for products only (on one rank, the blocks on and above the diagonal) multiplies as
// the whole matrix does: to the bit where every cell block is exactly symmetric, to round-off
// where projectors of sliding vertices make it symmetric only in exact arithmetic. A whole
// matrix made after it and a scalar Laplacian (which free the pattern's columns) still gets
// its pattern.
TEST_P(FunctionalTest, HessianStoredOnceMultipliesAsTheWholeMatrix) {
  MeshCase p(perturbed_box(GetParam(), cells_per_direction(GetParam()), 41));
  p.set_volumes(0.4, 42);
  const int d = p.data.dim;
  // Three interior vertices slide along the line of direction t (P = t tᵀ), bending with
  // w = e_0 and M = t tᵀ.
  std::vector<double> t(d);
  for (int a = 0; a < d; ++a) t[a] = (a + 1.0) / std::sqrt(d * (d + 1.0) * (2 * d + 1.0) / 6.0);
  SlidingVertices sliding;
  for (PetscInt v = 0; v < p.view.num_vertices && sliding.vertices.size() < 3; ++v)
    if (!p.view.on_boundary[v]) sliding.vertices.push_back(v);
  sliding.tangent_spaces = [d, t, count = sliding.vertices.size()](std::span<const double>,
                                                                   std::span<double> out) {
    for (std::size_t i = 0; i < count; ++i) {
      double* space = out.data() + i * tangent_space_size(d);
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) space[a * d + b] = space[d * d + d + a * d + b] = t[a] * t[b];
      for (int a = 0; a < d; ++a) space[d * d + a] = a == 0 ? 1.0 : 0.0;
    }
  };
  sliding.project = [](Vec) {};
  std::vector<std::uint8_t> fixed(d * p.view.num_vertices);
  for (PetscInt l = 0; l < d * p.view.num_vertices; ++l) fixed[l] = p.view.on_boundary[l / d];
  const Functional slides(EnergyOptions{},
                          Problem(p.view, p.dofs, FixedDofs{fixed}, std::move(sliding))
                              .with_desired_volumes(p.functional.problem().desired_volumes()));

  OwnedVec v = p.dofs.create_global_vector(), gradient = p.dofs.create_global_vector();
  {
    VecWriteView out(v);
    for (PetscInt i = 0; i < out.size(); ++i) out[i] = std::sin(1.0 + i);
  }
  for (const Functional* f : {static_cast<const Functional*>(&p.functional), &slides}) {
    f->value_and_gradient(p.x, gradient);  // the forces of the curvature term
    OwnedMat once = f->create_matrix(HessianUse::Products);
    const bool scalar = f->laplacian_is_scalar();
    OwnedMat laplacian =
        scalar ? f->create_scalar_laplacian_matrix() : f->create_laplacian_matrix();
    OwnedMat whole = f->create_matrix();
    f->assemble_hessian(p.x, 0.7, once);
    f->assemble_hessian(p.x, 0.7, whole);
    OwnedVec expected = p.dofs.create_global_vector(), product = p.dofs.create_global_vector();
    NM_PETSC(MatMult(whole, v, expected));
    NM_PETSC(MatMult(once, v, product));
    NM_PETSC(VecAXPY(product, -1.0, expected));
    EXPECT_LE(norm(product), (scalar ? 0.0 : 1e-14) * norm(expected))
        << (scalar ? "fixed" : "sliding");
    NM_PETSC(MatGetDiagonal(whole, expected));
    NM_PETSC(MatGetDiagonal(once, product));
    NM_PETSC(VecAXPY(product, -1.0, expected));
    EXPECT_EQ(norm(product), 0.0);
  }
}

TEST(Functional, InvertedCellGivesInfiniteValueAndRejectsHessian) {
  MeshData mesh = box(CellType::Quadrilateral, 2);
  mesh.coords[2 * 4] = 1.5;  // the centre vertex (1,1 in lattice order) moves outside
  MeshCase p(std::move(mesh));
  p.set_desired_volumes(std::vector<double>(4, 1.0));
  EXPECT_TRUE(std::isinf(p.functional.value(p.x)));
  OwnedVec gradient = p.dofs.create_global_vector();
  EXPECT_TRUE(std::isinf(p.functional.value_and_gradient(p.x, gradient)));
  OwnedMat H = p.functional.create_matrix();
  EXPECT_THROW(p.functional.assemble_hessian(p.x, 1.0, H), Error);
}

// value() stops at the first cell whose energy is not finite; wherever that cell is in
// each thread's share of the cells, the sum is not finite, and without it nothing changes.
TEST(Functional, ValueIsInfiniteWhereverTheInvertedCellIs) {
  const int n = 8;
  for (int threads : {1, 2}) {
    const testing::ThreadCount count(threads);
    for (int vertex : {n + 2, (n + 1) * (n / 2) + n / 2, (n + 1) * (n - 1) + n - 1}) {
      MeshData mesh = box(CellType::Quadrilateral, n);
      const double finite = [&] {
        MeshCase p{MeshData(mesh)};
        p.set_desired_volumes(std::vector<double>(n * n, 1.0));
        return p.functional.value(p.x);
      }();
      EXPECT_TRUE(std::isfinite(finite));
      mesh.coords[2 * vertex] += 1.5;  // an interior vertex crosses its right-hand neighbour
      MeshCase p(std::move(mesh));
      p.set_desired_volumes(std::vector<double>(n * n, 1.0));
      EXPECT_TRUE(std::isinf(p.functional.value(p.x))) << threads << " threads, vertex " << vertex;
    }
  }
}

// A problem with new constraints (a retry with the boundary pinned, a fitted interface) keeps
// its desired volumes, target shapes and weights: the same energy on the same mesh.
TEST(Problem, NewConstraintsKeepTheTargets) {
  MeshData mesh = perturbed_box(CellType::Quadrilateral, 4, 5);
  MeshCase with_targets{MeshData(mesh)};
  const PetscInt cells = with_targets.view.num_cells;
  std::vector<double> volumes(cells), shapes(4 * cells), weights(cells);
  for (PetscInt c = 0; c < cells; ++c) {
    volumes[c] = 1.0 + 0.1 * (c % 3);
    weights[c] = 1.0 + 0.5 * (c % 2);
    const double stretch = 1.0 + 0.2 * (c % 4);
    shapes[4 * c] = stretch, shapes[4 * c + 1] = 0.1, shapes[4 * c + 2] = 0.0;
    shapes[4 * c + 3] = 1.0;
  }
  with_targets.set_desired_volumes(volumes);
  with_targets.set_target_shapes(shapes, weights);
  const Problem& problem = with_targets.functional.problem();
  MeshCase replacement{std::move(mesh)};
  const Functional replaced(EnergyOptions{},
                            problem.with_constraints(replacement.functional.problem().constraints));
  EXPECT_EQ(replaced.problem().desired_volumes(), volumes);
  EXPECT_EQ(replaced.value(replacement.x), with_targets.functional.value(with_targets.x));
  MeshCase other(box(CellType::Quadrilateral, 3));
  EXPECT_THROW(
      Functional(EnergyOptions{}, problem.with_constraints(other.functional.problem().constraints)),
      Error);
}

// A problem derived for a phase (an untangling round, the corner lift) shares the targets and
// the constraints, whose pattern serves its matrices, and leaves the problem it came from as it
// was.
TEST(Problem, DerivedProblemsShareTargetsConstraintsAndMatrices) {
  MeshCase p(perturbed_box(CellType::Quadrilateral, 4, 7));
  p.set_volumes(0.2, 8);
  const double f = p.functional.value(p.x);
  const Functional untangling(EnergyOptions{}, p.functional.problem().with_untangling(0.1));
  const Functional corners(EnergyOptions{}, p.functional.problem().with_corner_weight(0.5));
  EXPECT_NE(untangling.value(p.x), f);
  EXPECT_NE(corners.value(p.x), f);
  EXPECT_EQ(p.functional.value(p.x), f);
  EXPECT_EQ(untangling.problem().targets, p.functional.problem().targets);
  EXPECT_EQ(untangling.problem().constraints, p.functional.problem().constraints);
  const OwnedMat H = p.functional.create_matrix();
  EXPECT_NO_THROW(untangling.assemble_hessian(p.x, 0.5, H));
}

// The shapes are inverted cell by cell on every thread; a bad shape or weight is still named by
// its cell, the first one.
TEST(Functional, NamesTheFirstCellWithABadTargetShapeOrWeight) {
  MeshCase p(box(CellType::Quadrilateral, 40));
  p.set_volumes();
  const PetscInt cells = p.view.num_cells;
  std::vector<double> shapes(4 * cells, 0.0), weights(cells, 1.0);
  for (PetscInt c = 0; c < cells; ++c) shapes[4 * c] = shapes[4 * c + 3] = 1.0;
  shapes[4 * 1200 + 3] = -1.0;  // det −1
  weights[1500] = 0.0;
  const auto error = [&] {
    try {
      p.set_target_shapes(shapes, weights);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(), "the target shape of local cell 1200 has determinant -1 (must be positive)");
  weights[700] = -2.0;
  EXPECT_EQ(error(), "the target weight of local cell 700 is -2 (must be positive)");
  weights[700] = weights[1500] = 1.0;
  shapes[4 * 1200 + 3] = 1.0;
  EXPECT_EQ(error(), "");
}

TEST(Functional, MeshVolumeAndFreeDofs) {
  MeshCase p(box(CellType::Hexahedron, 3));
  EXPECT_NEAR(mesh_volume(p.view, p.dofs, p.x), 8.0, 1e-13);
  EXPECT_EQ(p.functional.free_dofs(), 3 * 8);  // 2×2×2 interior vertices
}

// Thesis Table 5.1: the moved-midpoint square at level 3 (16×16 quads), equal desired
// volumes 1/256, λ = 1, μ = 10, 3×3 Gauss points, boundary fixed. The first row's Newton
// defect (1.16E+01) is the free-dof gradient norm at the initial mesh.
TEST(SquareMidpoint, InitialEnergyAndDefectOfThesisTable51) {
  for (double degrees : {0.0, 27.0}) {  // Table 5.3: the same mesh rotated by 27°
    MeshData mesh = square_midpoint(16);
    rotate(mesh, degrees);
    MeshCase p(std::move(mesh));
    p.set_desired_volumes(std::vector<double>(256, 1.0 / 256.0));
    OwnedVec gradient = p.dofs.create_global_vector();
    const double f = p.functional.value_and_gradient(p.x, gradient);
    EXPECT_NEAR(f, 2.665203, 5e-7) << "rotated by " << degrees;
    EXPECT_NEAR(norm(gradient), 11.6383, 5e-5) << "rotated by " << degrees;
  }
}

}  // namespace
}  // namespace neomesh
