#include "energy/matrix_assembler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "core/testing/thread_count.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {
namespace {

// A serial mesh with some dofs fixed (every coordinate of the first vertex of each cell
// block's first cell, and one coordinate of every fifth vertex, or all of its coordinates
// with `whole_vertices`) and its assembler.
struct TestMesh {
  MeshData data;
  MeshView view;
  DofMap dofs;
  std::vector<std::uint8_t> fixed;
  MatrixAssembler assembler;

  explicit TestMesh(MeshData mesh, bool whole_vertices = false)
      : data(std::move(mesh)),
        view(serial_view(data)),
        dofs(DofMap::serial(data.dim, static_cast<PetscInt>(data.num_vertices()))),
        fixed(fixed_dofs(view, whole_vertices)),
        assembler(view, dofs, fixed) {}

  static std::vector<std::uint8_t> fixed_dofs(const MeshView& view, bool whole_vertices) {
    std::vector<std::uint8_t> fixed(view.dim * view.num_vertices, 0);
    for (PetscInt v = 0; v < view.num_vertices; v += 5)
      for (int a = 0; a < view.dim; ++a)
        if (whole_vertices || a == v % view.dim) fixed[view.dim * v + a] = 1;
    for (const CellBlock& block : view.blocks)
      for (int a = 0; a < view.dim; ++a) fixed[view.dim * block.cell(0)[0] + a] = 1;
    return fixed;
  }
};

double value(Mat m, PetscInt row, PetscInt column) {
  PetscScalar v = 0.0;
  NM_PETSC(MatGetValues(m, 1, &row, 1, &column, &v));
  return v;
}

// Adds a random block per cell through the assembler, and the same blocks entry by entry
// into a dense reference with the rule of docs/method.md §3 (fixed rows and columns are
// those of the identity; Uncoupled keeps entries within a component only, Scalar those of
// component 0, in a row and column per vertex).
void check_assembly(const MeshData& mesh, MatrixLayout layout) {
  const bool scalar = layout == MatrixLayout::Scalar;
  TestMesh s(mesh, scalar);
  const int d = s.view.dim;
  const PetscInt n = (scalar ? 1 : d) * s.view.num_vertices;  // rows
  std::vector<double> reference(static_cast<std::size_t>(n * n), 0.0);
  OwnedMat m = s.assembler.create(layout);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  {
    MatrixAssembler::Values values(s.assembler, m);
    EXPECT_EQ(values.layout(), layout);
    for (std::size_t b = 0; b < s.view.blocks.size(); ++b) {
      const CellBlock& block = s.view.blocks[b];
      visit_cell_type(block.type, [&]<CellType Type>(CellTag<Type>) {
        constexpr int nv = num_vertices(Type);
        constexpr int dim = dimension(Type);
        constexpr int k = dim * nv;
        for (PetscInt c = 0; c < block.size(); ++c) {
          double cell_block[k * k];
          for (double& x : cell_block) x = u(rng);
          values.add_cell<dim, nv>(b, c, cell_block);
          for (int i = 0; i < k; ++i)
            for (int j = 0; j < k; ++j) {
              const PetscInt row = d * block.cell(c)[i / d] + i % d;
              const PetscInt column = d * block.cell(c)[j / d] + j % d;
              if (s.fixed[row] || s.fixed[column]) continue;
              if (layout == MatrixLayout::Uncoupled && i % d != j % d) continue;
              if (scalar && (i % d != 0 || j % d != 0)) continue;
              const PetscInt at_row = scalar ? row / d : row;
              const PetscInt at_column = scalar ? column / d : column;
              reference[at_row * n + at_column] += cell_block[i + j * k];
            }
        }
      });
    }
    values.gather();
    values.finish();
  }
  for (PetscInt l = 0; l < n; ++l)
    if (s.fixed[scalar ? d * l : l]) reference[l * n + l] = 1.0;
  for (PetscInt row = 0; row < n; ++row)
    for (PetscInt column = 0; column < n; ++column)
      ASSERT_NEAR(value(m, row, column), reference[row * n + column], 1e-12)
          << "row " << row << ", column " << column;
  PetscBool assembled = PETSC_FALSE;
  NM_PETSC(MatAssembled(m, &assembled));
  EXPECT_TRUE(assembled);
  // The product (on one rank the coupled layout's is neomesh's own, its rows shared among the
  // threads): the reference's, and the same bits on 1 and 2 threads.
  void (*product)(void) = nullptr;
  NM_PETSC(MatGetOperation(m, MATOP_MULT, &product));
  EXPECT_EQ(product == reinterpret_cast<void (*)(void)>(threaded_product),
            layout == MatrixLayout::Coupled);
  OwnedVec x, y;
  NM_PETSC(MatCreateVecs(m, x.out(), y.out()));
  std::vector<double> in(n), expected(n, 0.0);
  for (double& v : in) v = u(rng);
  for (PetscInt row = 0; row < n; ++row)
    for (PetscInt column = 0; column < n; ++column)
      expected[row] += reference[row * n + column] * in[column];
  PetscScalar* xa = nullptr;
  NM_PETSC(VecGetArrayWrite(x, &xa));
  std::copy(in.begin(), in.end(), xa);
  NM_PETSC(VecRestoreArrayWrite(x, &xa));
  std::vector<double> products[2];
  for (int t : {1, 2}) {
    const testing::ThreadCount count(t);
    NM_PETSC(MatMult(m, x, y));
    const PetscScalar* ya = nullptr;
    NM_PETSC(VecGetArrayRead(y, &ya));
    products[t - 1].assign(ya, ya + n);
    NM_PETSC(VecRestoreArrayRead(y, &ya));
  }
  for (PetscInt row = 0; row < n; ++row)
    ASSERT_NEAR(products[0][row], expected[row], 1e-12) << "row " << row;
  EXPECT_EQ(products[0], products[1]);
}

TEST(MatrixAssembler, AddsCellBlocksWhereTheMatrixKeepsThem) {
  for (MatrixLayout layout :
       {MatrixLayout::Coupled, MatrixLayout::Uncoupled, MatrixLayout::Scalar}) {
    check_assembly(square_random(4, 0.2, 1), layout);
    check_assembly(box(CellType::Triangle, 3), layout);
    check_assembly(box(CellType::Tetrahedron, 2), layout);
    check_assembly(box(CellType::Hexahedron, 2), layout);
  }
}

double stored_entries(Mat m) {
  MatInfo info;
  NM_PETSC(MatGetInfo(m, MAT_GLOBAL_SUM, &info));
  return info.nz_allocated;
}

// Uncoupled: 1/dim of the coupled entries; Scalar: one row per vertex, 1/dim² of them (made
// last, from the columns the coupled matrix holds by then). A vertex with only some
// coordinates fixed has no scalar row.
TEST(MatrixAssembler, UncoupledAndScalarMatricesHoldFewerEntries) {
  TestMesh s(box(CellType::Tetrahedron, 2), true);
  OwnedMat coupled = s.assembler.create(MatrixLayout::Coupled);
  OwnedMat uncoupled = s.assembler.create(MatrixLayout::Uncoupled);
  OwnedMat scalar = s.assembler.create(MatrixLayout::Scalar);
  EXPECT_EQ(stored_entries(coupled), 3 * stored_entries(uncoupled));
  EXPECT_EQ(stored_entries(coupled), 9 * stored_entries(scalar));
  PetscInt rows = 0;
  NM_PETSC(MatGetSize(scalar, &rows, nullptr));
  EXPECT_EQ(rows, s.view.num_vertices);
  // Later matrices of a layout share the first one's pattern and keep their own tag.
  OwnedMat second = s.assembler.create(MatrixLayout::Uncoupled);
  EXPECT_EQ(s.assembler.layout(coupled), MatrixLayout::Coupled);
  EXPECT_EQ(s.assembler.layout(uncoupled), MatrixLayout::Uncoupled);
  EXPECT_EQ(s.assembler.layout(second), MatrixLayout::Uncoupled);
  EXPECT_EQ(s.assembler.layout(scalar), MatrixLayout::Scalar);
  TestMesh some_fixed(box(CellType::Tetrahedron, 2));
  EXPECT_THROW(some_fixed.assembler.create(MatrixLayout::Scalar), Error);
}

// Whatever its pattern, a matrix the assembler did not create is refused: the assembler
// would otherwise write its values by a layout the matrix may not have.
TEST(MatrixAssembler, RefusesMatricesItDidNotCreate) {
  TestMesh s(box(CellType::Triangle, 3));
  OwnedMat mine = s.assembler.create(MatrixLayout::Coupled);
  OwnedMat copy;
  NM_PETSC(MatDuplicate(mine, MAT_SHARE_NONZERO_PATTERN, copy.out()));
  const PetscInt n = s.dofs.num_global_dofs();
  OwnedMat dense;
  NM_PETSC(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, n, nullptr, dense.out()));
  TestMesh other(box(CellType::Triangle, 3));
  OwnedMat theirs = other.assembler.create(MatrixLayout::Coupled);
  for (Mat m : {copy.get(), dense.get(), theirs.get()}) {
    try {
      MatrixAssembler::Values values(s.assembler, m);
      ADD_FAILURE() << "a foreign matrix was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("not made by"), std::string::npos) << e.what();
    }
    EXPECT_THROW(s.assembler.layout(m), Error);
  }
  EXPECT_EQ(s.assembler.layout(mine), MatrixLayout::Coupled);
}

// ‖M · (1, …, 1)‖
double product_norm(Mat m) {
  OwnedVec ones, product;
  NM_PETSC(MatCreateVecs(m, ones.out(), product.out()));
  NM_PETSC(VecSet(ones, 1.0));
  NM_PETSC(MatMult(m, ones, product));
  double norm = 0.0;
  NM_PETSC(VecNorm(product, NORM_2, &norm));
  return norm;
}

// On one rank the first matrix of a layout uses the assembler's arrays in place; a duplicate
// shares them and must keep them when the first matrix and the assembler are gone.
TEST(MatrixAssembler, DuplicatesKeepTheSharedPatternAlive) {
  OwnedMat duplicate;
  double expected = 0.0;
  {
    TestMesh s(box(CellType::Triangle, 3));
    OwnedMat first = s.assembler.create(MatrixLayout::Coupled);
    duplicate = s.assembler.create(MatrixLayout::Coupled);
    MatrixAssembler::Values values(s.assembler, duplicate);
    values.gather();
    values.finish();
    expected = product_norm(duplicate);
  }
  EXPECT_EQ(product_norm(duplicate), expected);  // reads the columns and the values
  EXPECT_GT(expected, 0.0);                      // the identity rows of fixed dofs
}

}  // namespace
}  // namespace neomesh
