// The per-component preconditioner gives the same bits whether the components are
// preconditioned one after the other or at once, takes its further preconditioners of a shared
// A₁ into use only once they have paid for their set-up, and with an operator of its own per
// component applies to each component what a BoomerAMG of that component's matrix does.
#include "solver/component_preconditioner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <utility>
#include <vector>

#include "core/memory.hpp"
#include "core/testing/thread_count.hpp"
#include "energy/functional.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {
namespace {

using testing::ThreadCount;

OwnedPC boomeramg() {
  OwnedPC pc;
  NM_PETSC(PCCreate(PETSC_COMM_SELF, pc.out()));
  NM_PETSC(PCSetType(pc, PCHYPRE));
  NM_PETSC(PCHYPRESetType(pc, "boomeramg"));
  return pc;
}

// A shell PC applying `count` BoomerAMG preconditioners to the `dim` components of `vector`:
// of `scalar` (Shared) or of each component's rows of `vector` (Own, count = dim), at once on
// threads if `concurrent`.
struct Shell {
  Shell(Mat scalar, Mat vector, int dim, int count,
        ComponentOperators kind = ComponentOperators::Shared, bool concurrent = true) {
    std::vector<OwnedPC> scalars;
    for (int k = 0; k < count; ++k) scalars.push_back(boomeramg());
    components = std::make_unique<ComponentPreconditioner>(std::move(scalars), dim, kind,
                                                           /*boomeramg=*/true, concurrent);
    components->set_operator(kind == ComponentOperators::Shared ? scalar : vector, false);
    NM_PETSC(PCCreate(PETSC_COMM_SELF, pc.out()));
    components->install(pc);
    NM_PETSC(PCSetOperators(pc, vector, vector));
  }
  std::unique_ptr<ComponentPreconditioner> components;
  OwnedPC pc;
};

std::vector<double> values(Vec v) {
  PetscInt n = 0;
  NM_PETSC(VecGetLocalSize(v, &n));
  const PetscScalar* a = nullptr;
  NM_PETSC(VecGetArrayRead(v, &a));
  std::vector<double> out(a, a + n);
  NM_PETSC(VecRestoreArrayRead(v, &a));
  return out;
}

// How the boundary vertices of the test box are held.
enum class Held {
  Whole,   // every coordinate fixed: L = MatCreateMAIJ(L₁, dim)
  Normal,  // only the coordinate normal to their side (they slide along axis-aligned planes):
           // each component has Dirichlet rows of its own, and L is the uncoupled dn × dn matrix
};

// The optimal cells' Laplacian of a jittered box of quadrilaterals or tetrahedra.
OwnedMat laplacian(CellType type, int cells, Held held = Held::Whole) {
  MeshData mesh = box(type, cells);
  jitter(mesh, 2.0 / cells, 0.1, 3);
  const MeshView view = serial_view(mesh);
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  FixedDofs fixed;
  const auto on_side = [](double c) { return c < 1e-12 || c > 1.0 - 1e-12; };  // box [0, 1]^d
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const double* x = view.coords.data() + v * view.dim;
    const bool on_boundary = std::any_of(x, x + view.dim, on_side);
    for (int j = 0; j < view.dim; ++j)
      fixed.flags.push_back(held == Held::Whole ? on_boundary : on_side(x[j]));
  }
  const Functional functional(EnergyOptions{},
                              Problem(view, dofs, std::move(fixed))
                                  .with_desired_volumes(std::vector<double>(view.num_cells, 1.0)));
  EXPECT_EQ(functional.laplacian_is_scalar(), held == Held::Whole);
  EXPECT_FALSE(functional.slides());
  OwnedVec x = dofs.create_global_vector();
  OwnedMat vector = held == Held::Whole ? functional.create_scalar_laplacian_matrix()
                                        : functional.create_laplacian_matrix();
  functional.assemble_laplacian(RieszLaplacian::OptimalCells, x, vector);
  return vector;
}

// What a BoomerAMG preconditioner of component j's rows and columns of `vector` gives for
// component j of b, component by component: the reference for ComponentOperators::Own.
std::vector<double> separately(Mat vector, int dim, Vec b) {
  PetscInt rows = 0;
  NM_PETSC(MatGetSize(vector, &rows, nullptr));
  std::vector<double> in = values(b), out(in.size());
  for (int j = 0; j < dim; ++j) {
    IS part = nullptr;
    NM_PETSC(ISCreateStride(PETSC_COMM_SELF, rows / dim, j, dim, &part));
    OwnedMat A;
    NM_PETSC(MatCreateSubMatrix(vector, part, part, MAT_INITIAL_MATRIX, A.out()));
    NM_PETSC(ISDestroy(&part));
    OwnedPC pc = boomeramg();
    NM_PETSC(PCSetOperators(pc, A, A));
    OwnedVec x, y;
    NM_PETSC(MatCreateVecs(A, x.out(), y.out()));
    {
      VecWriteView xs(x);
      for (PetscInt i = 0; i < xs.size(); ++i) xs[i] = in[dim * i + j];
    }
    NM_PETSC(PCApply(pc, x, y));
    const std::vector<double> ys = values(y);
    for (std::size_t i = 0; i < ys.size(); ++i) out[dim * i + j] = ys[i];
  }
  return out;
}

OwnedVec right_hand_side(Mat vector, int k) {
  OwnedVec b;
  NM_PETSC(MatCreateVecs(vector, b.out(), nullptr));
  VecWriteView out(b);
  for (PetscInt i = 0; i < out.size(); ++i) out[i] = std::sin(0.1 * i + k);
  return b;
}

int components(Mat vector) {
  PetscInt all = 0, one = 0;
  NM_PETSC(MatGetSize(vector, &all, nullptr));
  NM_PETSC(MatGetSize(maij_scalar(vector), &one, nullptr));
  return static_cast<int>(all / one);
}

TEST(ComponentPreconditioner, ConcurrentComponentsGiveTheSameBitsOnceTheyPaid) {
  const ThreadCount two(2);
  for (const auto& [type, cells] :
       {std::pair{CellType::Quadrilateral, 40}, std::pair{CellType::Tetrahedron, 8}}) {
    const OwnedMat vector = laplacian(type, cells);
    const int dim = components(vector);
    SCOPED_TRACE(dim);
    const Mat scalar = maij_scalar(vector);
    Shell one(scalar, vector, dim, 1), two_at_once(scalar, vector, dim, 2);
    OwnedVec y1, y2;
    NM_PETSC(MatCreateVecs(vector, y1.out(), y2.out()));
    // Applies both to right-hand side k and compares the bits.
    const auto same_bits = [&](int k) {
      const OwnedVec b = right_hand_side(vector, k);
      NM_PETSC(PCApply(one.pc, b, y1));
      NM_PETSC(PCApply(two_at_once.pc, b, y2));
      return values(y1) == values(y2);
    };
    // Applies both until the second hierarchy is in use; false at the first difference.
    const auto same_bits_until_paid = [&] {
      for (int k = 0; k < 5000 && two_at_once.components->concurrent() < 2; ++k)
        if (!same_bits(k)) return false;
      return true;
    };
    ASSERT_TRUE(same_bits_until_paid());
    // Paid: the set-up takes some applications' time (8 in 2D, 15 in 3D here), not thousands.
    EXPECT_EQ(two_at_once.components->concurrent(), 2);
    EXPECT_EQ(one.components->concurrent(), 1);
    // At once from here on, and still the same bits.
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(same_bits(-k));

    // New values of the operator: its hierarchies have to pay again, and are built for the
    // new values (the one copy of A₁ in hypre's format the two share is updated in place).
    NM_PETSC(MatShift(scalar, 0.5));
    one.components->set_operator(scalar, false);
    two_at_once.components->set_operator(scalar, false);
    EXPECT_EQ(two_at_once.components->concurrent(), 1);
    ASSERT_TRUE(same_bits_until_paid());
    EXPECT_EQ(two_at_once.components->concurrent(), 2);
    EXPECT_TRUE(same_bits(7));
  }
}

TEST(ComponentPreconditioner, OwnOperatorsGiveEachComponentItsHierarchyAtOnce) {
  for (const auto& [type, cells] :
       {std::pair{CellType::Quadrilateral, 40}, std::pair{CellType::Tetrahedron, 8}}) {
    const OwnedMat vector = laplacian(type, cells, Held::Normal);
    const int dim = type == CellType::Quadrilateral ? 2 : 3;
    SCOPED_TRACE(dim);
    const ThreadCount two(2);
    Shell at_once(nullptr, vector, dim, dim, ComponentOperators::Own, /*concurrent=*/true);
    Shell in_turn(nullptr, vector, dim, dim, ComponentOperators::Own, /*concurrent=*/false);
    OwnedVec y1, y2;
    NM_PETSC(MatCreateVecs(vector, y1.out(), y2.out()));
    for (int k = 0; k < 3; ++k) {
      const OwnedVec b = right_hand_side(vector, k);
      NM_PETSC(PCApply(at_once.pc, b, y1));
      NM_PETSC(PCApply(in_turn.pc, b, y2));
      EXPECT_EQ(values(y1), values(y2));
      EXPECT_EQ(values(y1), separately(vector, dim, b));
    }
    EXPECT_EQ(at_once.components->concurrent(), 2);
    EXPECT_EQ(in_turn.components->concurrent(), 1);
    // New values: the hierarchies are built for them.
    NM_PETSC(MatShift(vector, 0.5));
    at_once.components->set_operator(vector, false);
    const OwnedVec b = right_hand_side(vector, 9);
    NM_PETSC(PCApply(at_once.pc, b, y1));
    EXPECT_EQ(values(y1), separately(vector, dim, b));
  }
}

// Without the memory for a second hierarchy, one serves every component however often it is
// applied: where the machine has none to give, and where the run's expected peak needs all it
// has.
void expect_one_hierarchy_for_every_component() {
  const ThreadCount two(2);
  const OwnedMat vector = laplacian(CellType::Quadrilateral, 40);
  Shell one(maij_scalar(vector), vector, 2, 1), two_at_once(maij_scalar(vector), vector, 2, 2);
  OwnedVec y1, y2;
  NM_PETSC(MatCreateVecs(vector, y1.out(), y2.out()));
  for (int k = 0; k < 200; ++k) {  // 25 times what paid for it above
    const OwnedVec b = right_hand_side(vector, k);
    NM_PETSC(PCApply(one.pc, b, y1));
    NM_PETSC(PCApply(two_at_once.pc, b, y2));
  }
  EXPECT_EQ(two_at_once.components->concurrent(), 1);
  EXPECT_EQ(values(y1), values(y2));
}

TEST(ComponentPreconditioner, NoSecondHierarchyWithoutTheMemoryForIt) {
  setenv("NEOMESH_MEMORY_AVAILABLE_MIB", "-1", 1);
  expect_one_hierarchy_for_every_component();
  unsetenv("NEOMESH_MEMORY_AVAILABLE_MIB");
}

TEST(ComponentPreconditioner, NoSecondHierarchyWhereTheRunsPeakNeedsTheMemory) {
  // A set-up that malloc served from memory it kept may count 0 bytes: the peak leaves less
  // than nothing.
  expect_peak(resident_bytes() + available_bytes() + 1024.0 * 1024 * 1024);
  expect_one_hierarchy_for_every_component();
  expect_peak(0.0);
}

// With BoomerAMG the operator is copied into hypre's format when it is given and not kept: the
// copies multiply as the operator does, each component by its own matrix, on one thread or
// several.
TEST(ComponentPreconditioner, ItsCopiesMultiplyAsTheOperatorItDoesNotKeep) {
  const ThreadCount two(2);
  for (const auto& [type, cells] :
       {std::pair{CellType::Quadrilateral, 40}, std::pair{CellType::Tetrahedron, 8}}) {
    for (const Held held : {Held::Whole, Held::Normal}) {
      const OwnedMat vector = laplacian(type, cells, held);
      const int dim = type == CellType::Quadrilateral ? 2 : 3;
      const ComponentOperators kind =
          held == Held::Whole ? ComponentOperators::Shared : ComponentOperators::Own;
      SCOPED_TRACE(::testing::Message() << "dim " << dim << ", own " << (held == Held::Normal));
      const Mat given = kind == ComponentOperators::Shared ? maij_scalar(vector) : vector.get();
      for (const bool concurrent : {false, true}) {
        std::vector<OwnedPC> scalars;
        const int count = kind == ComponentOperators::Own ? dim : concurrent ? 2 : 1;
        for (int k = 0; k < count; ++k) scalars.push_back(boomeramg());
        ComponentPreconditioner components(std::move(scalars), dim, kind, true, concurrent);
        PetscInt references = 0, after = 0;
        NM_PETSC(PetscObjectGetReference(reinterpret_cast<PetscObject>(given), &references));
        components.set_operator(given, false);
        components.setup();
        NM_PETSC(PetscObjectGetReference(reinterpret_cast<PetscObject>(given), &after));
        EXPECT_EQ(after, references);
        ASSERT_NE(components.product(), nullptr);
        OwnedVec y1, y2;
        NM_PETSC(MatCreateVecs(vector, y1.out(), y2.out()));
        const OwnedVec b = right_hand_side(vector, 4);
        NM_PETSC(MatMult(vector, b, y1));
        NM_PETSC(MatMult(components.product(), b, y2));
        const std::vector<double> expected = values(y1), got = values(y2);
        ASSERT_EQ(got.size(), expected.size());
        double largest = 0.0, error = 0.0;
        for (std::size_t i = 0; i < got.size(); ++i) {
          largest = std::max(largest, std::abs(expected[i]));
          error = std::max(error, std::abs(got[i] - expected[i]));
        }
        EXPECT_LE(error, 1e-13 * largest);
      }
    }
  }
}

}  // namespace
}  // namespace neomesh
