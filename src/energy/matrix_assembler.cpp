#include "energy/matrix_assembler.hpp"

#include <algorithm>
#include <atomic>
#include <memory>
#include <tuple>

#include "core/collective_error.hpp"

namespace neomesh {

namespace {

// What create() attaches to each matrix (PetscObjectCompose under kTagName).
struct Tag {
  std::uint64_t assembler;
  MatrixLayout layout;
};
constexpr const char* kTagName = "neomesh_matrix_assembler";

using OwnedContainer = PetscOwner<PetscContainer, PetscContainerDestroy>;

// The arrays of a SeqAIJ matrix made by MatCreateSeqAIJWithArrays, which PETSc uses in place
// (no copy of the columns, no MatSetValues pass over them). They hang on the matrix and on
// every duplicate of it (PetscObjectCompose under kArraysName), and go with the last of them.
struct CsrArrays {
  std::vector<PetscInt> row_start, column;
  std::vector<PetscScalar> values;
};
constexpr const char* kArraysName = "neomesh_csr_arrays";

PetscErrorCode destroy_arrays(void* arrays) {
  delete static_cast<CsrArrays*>(arrays);
  return 0;
}

void compose(Mat m, const char* name, PetscObject object) {
  NM_PETSC(PetscObjectCompose(reinterpret_cast<PetscObject>(m), name, object));
}

// A SeqAIJ matrix on these arrays, which it keeps.
OwnedMat matrix_on_arrays(MPI_Comm comm, std::vector<PetscInt> row_start,
                          std::vector<PetscInt> column) {
  auto arrays = std::make_unique<CsrArrays>(
      CsrArrays{std::move(row_start), std::move(column), std::vector<PetscScalar>()});
  arrays->values.resize(arrays->column.size());
  const PetscInt rows = static_cast<PetscInt>(arrays->row_start.size()) - 1;
  OwnedMat m;
  NM_PETSC(MatCreateSeqAIJWithArrays(comm, rows, rows, arrays->row_start.data(),
                                     arrays->column.data(), arrays->values.data(), m.out()));
  OwnedContainer container;
  NM_PETSC(PetscContainerCreate(comm, container.out()));
  NM_PETSC(PetscContainerSetPointer(container, arrays.release()));
  NM_PETSC(PetscContainerSetUserDestroy(container, destroy_arrays));
  compose(m, kArraysName, reinterpret_cast<PetscObject>(container.get()));
  return m;
}

// Coupled matrices on one rank multiply with threaded_product. Set when create() makes them:
// on one rank PETSc never assembles them again (Values writes the values in place), which
// would put its own product back.
void use_threaded_product(Mat m, MatrixLayout layout) {
  PetscBool sequential = PETSC_FALSE;
  NM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m), MATSEQAIJ, &sequential));
  if (layout == MatrixLayout::Coupled && sequential)
    NM_PETSC(MatSetOperation(m, MATOP_MULT, reinterpret_cast<void (*)(void)>(threaded_product)));
}

// A Symmetric matrix: the shared upper blocks and its own values (hung on the matrix under
// kArraysName, the shell's context).
struct UpperMatrix {
  std::shared_ptr<const UpperBlocks> blocks;
  int dim;
  std::vector<PetscScalar> values;
};

PetscErrorCode destroy_upper_matrix(void* matrix) {
  delete static_cast<UpperMatrix*>(matrix);
  return 0;
}

UpperMatrix& upper_matrix(Mat m) {
  void* context = nullptr;
  NM_PETSC(MatShellGetContext(m, &context));
  return *static_cast<UpperMatrix*>(context);
}

template <int D>
void upper_block_rows(const UpperBlocks& u, const PetscScalar* value, const PetscScalar* in,
                      PetscScalar* out) {
  const PetscInt rows = static_cast<PetscInt>(u.row_start.size()) - 1;
  // Row (D w + a) sums its columns in increasing order, as a Coupled matrix's row does: the
  // blocks (v, w) below the diagonal, transposed, then those of w's own row.
#pragma omp parallel for schedule(static)
  for (PetscInt w = 0; w < rows; ++w) {
    PetscScalar sum[D] = {};
    for (PetscInt t = u.lower_start[w]; t < u.lower_start[w + 1]; ++t) {
      const PetscScalar* block = value + D * D * u.lower_block[t];
      const PetscScalar* x = in + D * u.lower_row[t];
      for (int b = 0; b < D; ++b)
        for (int a = 0; a < D; ++a) sum[a] += block[D * b + a] * x[b];
    }
    for (PetscInt k = u.row_start[w]; k < u.row_start[w + 1]; ++k) {
      const PetscScalar* block = value + D * D * k;
      const PetscScalar* x = in + D * u.column[k];
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) sum[a] += block[D * a + b] * x[b];
    }
    for (int a = 0; a < D; ++a) out[D * w + a] = sum[a];
  }
}

PetscErrorCode upper_block_diagonal(Mat A, Vec diagonal) {
  PetscFunctionBeginUser;
  void* context = nullptr;
  PetscCall(MatShellGetContext(A, &context));
  const UpperMatrix& m = *static_cast<const UpperMatrix*>(context);
  const int d = m.dim;
  const PetscInt rows = static_cast<PetscInt>(m.blocks->row_start.size()) - 1;
  PetscScalar* out = nullptr;
  PetscCall(VecGetArrayWrite(diagonal, &out));
  for (PetscInt w = 0; w < rows; ++w)  // a row's first block is its diagonal one
    for (int a = 0; a < d; ++a)
      out[d * w + a] = m.values[d * d * m.blocks->row_start[w] + (d + 1) * a];
  PetscCall(VecRestoreArrayWrite(diagonal, &out));
  PetscFunctionReturn(0);
}

// MatMult of a Symmetric matrix: its rows shared among the OpenMP threads.
PetscErrorCode upper_block_product(Mat A, Vec x, Vec y) {
  PetscFunctionBeginUser;
  void* context = nullptr;
  PetscCall(MatShellGetContext(A, &context));
  const UpperMatrix& m = *static_cast<const UpperMatrix*>(context);
  PetscCheck(m.dim == 2 || m.dim == 3, PETSC_COMM_SELF, PETSC_ERR_SUP, "%d-D blocks", m.dim);
  const PetscScalar* in = nullptr;
  PetscScalar* out = nullptr;
  PetscCall(VecGetArrayRead(x, &in));
  PetscCall(VecGetArrayWrite(y, &out));
  if (m.dim == 2)
    upper_block_rows<2>(*m.blocks, m.values.data(), in, out);
  else
    upper_block_rows<3>(*m.blocks, m.values.data(), in, out);
  PetscCall(VecRestoreArrayWrite(y, &out));
  PetscCall(VecRestoreArrayRead(x, &in));
  const PetscLogDouble blocks = static_cast<PetscLogDouble>(m.blocks->column.size()) +
                                static_cast<PetscLogDouble>(m.blocks->lower_block.size());
  PetscCall(PetscLogFlops(2.0 * m.dim * m.dim * blocks));
  PetscFunctionReturn(0);
}

std::uint64_t next_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

// A and B of an AIJ matrix; B is null on one rank (SeqAIJ).
std::pair<Mat, Mat> aij_parts(Mat m) {
  PetscBool distributed = PETSC_FALSE;
  NM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m), MATMPIAIJ, &distributed));
  if (!distributed) return {m, nullptr};
  Mat a = nullptr, b = nullptr;
  NM_PETSC(MatMPIAIJGetSeqAIJ(m, &a, &b, nullptr));
  return {a, b};
}

std::size_t stored_entries(Mat part) {
  if (!part) return 0;
  MatInfo info;
  NM_PETSC(MatGetInfo(part, MAT_LOCAL, &info));
  return static_cast<std::size_t>(info.nz_used);
}

void attach_tag(Mat m, std::uint64_t assembler, MatrixLayout layout) {
  Tag* tag = nullptr;
  NM_PETSC(PetscNew(&tag));
  *tag = Tag{assembler, layout};
  OwnedContainer container;
  NM_PETSC(
      PetscContainerCreate(PetscObjectComm(reinterpret_cast<PetscObject>(m)), container.out()));
  NM_PETSC(PetscContainerSetPointer(container, tag));
  NM_PETSC(PetscContainerSetUserDestroy(container, PetscContainerUserDestroyDefault));
  compose(m, kTagName, reinterpret_cast<PetscObject>(container.get()));
}

}  // namespace

PetscErrorCode threaded_product(Mat A, Vec x, Vec y) {
  PetscFunctionBeginUser;
  PetscObject arrays = nullptr;
  PetscCall(PetscObjectQuery(reinterpret_cast<PetscObject>(A), kArraysName, &arrays));
  PetscCheck(arrays, PETSC_COMM_SELF, PETSC_ERR_PLIB, "a threaded product without its arrays");
  void* pointer = nullptr;
  PetscCall(PetscContainerGetPointer(reinterpret_cast<PetscContainer>(arrays), &pointer));
  const CsrArrays& csr = *static_cast<const CsrArrays*>(pointer);
  const PetscInt rows = static_cast<PetscInt>(csr.row_start.size()) - 1;
  const PetscInt* start = csr.row_start.data();
  const PetscInt* column = csr.column.data();
  const PetscScalar *a = nullptr, *in = nullptr;
  PetscScalar* out = nullptr;
  PetscCall(MatSeqAIJGetArrayRead(A, &a));
  PetscCall(VecGetArrayRead(x, &in));
  PetscCall(VecGetArrayWrite(y, &out));
  // Each row summed in column order by one thread: the same bits for any number of threads.
  // (Reading a vertex's shared columns once for its D rows measured slower: hexes-40's δ̃
  // solves 0.17-0.18 s row by row, 0.20-0.23 s by vertex.)
#pragma omp parallel for schedule(static)
  for (PetscInt r = 0; r < rows; ++r) {
    PetscScalar sum = 0.0;
    for (PetscInt k = start[r]; k < start[r + 1]; ++k) sum += a[k] * in[column[k]];
    out[r] = sum;
  }
  PetscCall(VecRestoreArrayWrite(y, &out));
  PetscCall(VecRestoreArrayRead(x, &in));
  PetscCall(MatSeqAIJRestoreArrayRead(A, &a));
  PetscCall(PetscLogFlops(2.0 * static_cast<PetscLogDouble>(start[rows]) - rows));
  PetscFunctionReturn(0);
}

MatrixAssembler::MatrixAssembler(const MeshView& view, const DofMap& dofs,
                                 std::span<const std::uint8_t> fixed)
    : view_(view),
      dofs_(dofs),
      fixed_(fixed.begin(), fixed.end()),
      vertex_fixed_(view.num_vertices, 0),
      pattern_(make_assembly_pattern(view, dofs)),
      id_(next_id()) {
  const int d = dofs.dim();
  if (static_cast<PetscInt>(fixed_.size()) != d * view.num_vertices)
    fail("MatrixAssembler: {} fixed flags for {} local dofs", fixed_.size(), d * view.num_vertices);
  for (PetscInt l = 0; l < d * view.num_vertices; ++l)
    if (fixed_[l]) vertex_fixed_[l / d] = 1;
  for (PetscInt l = 0; l < d * view.num_vertices; ++l)
    if (fixed_[l] != vertex_fixed_[l / d]) components_fixed_alike_ = false;
}

MatrixAssembler::~MatrixAssembler() = default;

void MatrixAssembler::make_upper_blocks() {
  const int d = dofs_.dim();
  const PetscInt nv = view_.num_vertices;
  const std::vector<PetscInt>& global_dof = dofs_.global_dof();
  auto u = std::make_shared<UpperBlocks>();
  // On one rank every vertex is owned and its rows are those of global vertex global_dof / d.
  std::vector<PetscInt> local(nv);
  for (PetscInt v = 0; v < nv; ++v) local[global_dof[d * v] / d] = v;
  u->row_start.assign(nv + 1, 0);
  u->lower_start.assign(nv + 1, 0);
  u->diagonal.resize(nv);
  u->shift.resize(nv);
  u->column.reserve((pattern_.neighbour.size() + nv) / 2);  // the pattern is symmetric
  for (PetscInt w = 0; w < nv; ++w) {
    const PetscInt v = local[w];
    const PetscInt* row = pattern_.neighbour.data() + pattern_.neighbour_start[w];
    const PetscInt blocks = pattern_.neighbour_start[w + 1] - pattern_.neighbour_start[w];
    PetscInt k = 0;  // the diagonal block's place in the row (neighbours are sorted)
    while (k < blocks && row[k] < w) ++k;
    u->diagonal[v] = pattern_.row_first[v] + k;
    u->shift[v] = u->row_start[w] - u->diagonal[v];
    u->row_start[w + 1] = u->row_start[w] + blocks - k;
    u->lower_start[w + 1] = u->lower_start[w] + k;
    u->column.insert(u->column.end(), row + k, row + blocks);
  }
  // The blocks below the diagonal are the transposes of those above, found in row order.
  u->lower_block.resize(u->lower_start.back());
  u->lower_row.resize(u->lower_start.back());
  std::vector<PetscInt> next(u->lower_start.begin(), u->lower_start.end() - 1);
  for (PetscInt v = 0; v < nv; ++v)
    for (PetscInt k = u->row_start[v] + 1; k < u->row_start[v + 1]; ++k) {
      const PetscInt w = u->column[k];
      u->lower_block[next[w]] = k;
      u->lower_row[next[w]++] = v;
    }
  upper_ = std::move(u);
}

OwnedMat MatrixAssembler::create_upper_matrix() const {
  const int d = dofs_.dim();
  const PetscInt rows = dofs_.num_owned_dofs();
  auto matrix = std::make_unique<UpperMatrix>(
      UpperMatrix{upper_, d, std::vector<PetscScalar>(d * d * upper_->column.size())});
  OwnedMat m;
  NM_PETSC(MatCreateShell(dofs_.comm(), rows, rows, rows, rows, matrix.get(), m.out()));
  NM_PETSC(
      MatShellSetOperation(m, MATOP_MULT, reinterpret_cast<void (*)(void)>(upper_block_product)));
  NM_PETSC(MatShellSetOperation(m, MATOP_MULT_TRANSPOSE,
                                reinterpret_cast<void (*)(void)>(upper_block_product)));
  NM_PETSC(MatShellSetOperation(m, MATOP_GET_DIAGONAL,
                                reinterpret_cast<void (*)(void)>(upper_block_diagonal)));
  OwnedContainer container;
  NM_PETSC(PetscContainerCreate(dofs_.comm(), container.out()));
  NM_PETSC(PetscContainerSetPointer(container, matrix.release()));
  NM_PETSC(PetscContainerSetUserDestroy(container, destroy_upper_matrix));
  compose(m, kArraysName, reinterpret_cast<PetscObject>(container.get()));
  return m;
}

OwnedMat MatrixAssembler::create_first(MatrixLayout layout) {
  const int d = dofs_.dim();
  if (layout == MatrixLayout::Scalar)
    throw_if_any(dofs_.comm(), components_fixed_alike_
                                   ? ""
                                   : "internal error: a scalar Laplacian of a mesh whose vertices "
                                     "have only some coordinates fixed");
  const bool coupled = layout == MatrixLayout::Coupled;
  // Entries per entry of the layout: the coupled pattern holds dim (Uncoupled) or dim² (Scalar).
  const std::size_t shrink = coupled ? 1 : layout == MatrixLayout::Uncoupled ? d : d * d;
  const PetscInt block_size = layout == MatrixLayout::Scalar ? 1 : d;  // rows per vertex
  const PetscInt rows = dofs_.num_owned_dofs() / d * block_size;
  const PetscInt global_rows = dofs_.num_global_dofs() / d * block_size;
  auto [row_start, column] = layout_csr(pattern_, layout, d);
  OwnedMat m;
  if (mpi_size(dofs_.comm()) == 1) {
    m = matrix_on_arrays(dofs_.comm(), std::move(row_start), std::move(column));
    // hypre's BoomerAMG reads the block size as its number of functions.
    NM_PETSC(MatSetBlockSize(m, block_size));
  } else {
    NM_PETSC(MatCreate(dofs_.comm(), m.out()));
    NM_PETSC(MatSetSizes(m, rows, rows, global_rows, global_rows));
    NM_PETSC(MatSetType(m, MATMPIAIJ));
    NM_PETSC(MatSetBlockSize(m, block_size));
    NM_PETSC(MatMPIAIJSetPreallocationCSR(m, row_start.data(), column.data(), nullptr));
  }
  // Values are written where assembly_pattern.hpp says PETSc keeps each entry; a different
  // number of entries in A or B means a PETSc that stores them differently.
  const auto [a, b] = aij_parts(m);
  if (stored_entries(a) != pattern_.diagonal_entries / shrink ||
      stored_entries(b) != pattern_.off_diagonal_entries / shrink)
    fail("internal error: PETSc stores {} in {} + {} entries, not {} + {}", coupled ? "H" : "L",
         stored_entries(a), stored_entries(b), pattern_.diagonal_entries / shrink,
         pattern_.off_diagonal_entries / shrink);
  return m;
}

OwnedMat MatrixAssembler::create(MatrixLayout layout) {
  OwnedMat m;
  if (layout == MatrixLayout::Symmetric) {
    if (mpi_size(dofs_.comm()) != 1)
      fail("internal error: a matrix of the upper blocks alone on several ranks");
    if (!upper_) make_upper_blocks();
    m = create_upper_matrix();
  } else if (layout == MatrixLayout::Coupled && first_coupled_) {
    NM_PETSC(MatDuplicate(first_coupled_, MAT_SHARE_NONZERO_PATTERN, m.out()));
    // A duplicate shares the first matrix's columns: it keeps them too.
    PetscObject arrays = nullptr;
    NM_PETSC(PetscObjectQuery(reinterpret_cast<PetscObject>(first_coupled_.get()), kArraysName,
                              &arrays));
    if (arrays) compose(m, kArraysName, arrays);
  } else {
    m = create_first(layout);
    // A Laplacian's matrix is not kept: a solver may hold L in its own format alone
    // (LinearSolver::copies_operator).
    if (layout == MatrixLayout::Coupled) {
      NM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(m.get())));
      first_coupled_ = OwnedMat(m.get());
    }
  }
  attach_tag(m, id_, layout);
  use_threaded_product(m, layout);
  // H(α) and L are symmetric by construction (cell_kernels.hpp), exactly in floating point.
  NM_PETSC(MatSetOption(m, MAT_SYMMETRIC, PETSC_TRUE));
  NM_PETSC(MatSetOption(m, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  // Rows of ghost vertices reach their owners through the pattern's PetscSFs.
  NM_PETSC(MatSetOption(m, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  return m;
}

MatrixLayout MatrixAssembler::layout(Mat m) const {
  PetscObject container = nullptr;
  if (m) NM_PETSC(PetscObjectQuery(reinterpret_cast<PetscObject>(m), kTagName, &container));
  void* tag = nullptr;
  if (container)
    NM_PETSC(PetscContainerGetPointer(reinterpret_cast<PetscContainer>(container), &tag));
  if (!tag || static_cast<const Tag*>(tag)->assembler != id_)
    fail(
        "internal error: the matrix to assemble was not made by this Functional's "
        "create_matrix or create_laplacian_matrix");
  return static_cast<const Tag*>(tag)->layout;
}

MatrixAssembler::Values::Values(const MatrixAssembler& assembler, Mat m)
    : assembler_(assembler), m_(m) {
  layout_ = assembler.layout(m);
  const AssemblyPattern& p = assembler.pattern_;
  const std::size_t d = assembler.dofs_.dim();
  if (layout_ == MatrixLayout::Symmetric) {
    std::vector<PetscScalar>& values = upper_matrix(m).values;
    std::fill(values.begin(), values.end(), 0.0);
    diagonal_ = values.data();
    return;
  }
  const std::size_t shrink = layout_ == MatrixLayout::Coupled     ? 1
                             : layout_ == MatrixLayout::Uncoupled ? d
                                                                  : d * d;
  std::tie(diagonal_part_, off_diagonal_part_) = aij_parts(m);
  NM_PETSC(MatSeqAIJGetArrayWrite(diagonal_part_, &diagonal_));
  if (off_diagonal_part_) NM_PETSC(MatSeqAIJGetArrayWrite(off_diagonal_part_, &off_diagonal_));
  std::fill_n(diagonal_, p.diagonal_entries / shrink, 0.0);
  std::fill_n(off_diagonal_, p.off_diagonal_entries / shrink, 0.0);
  ghost_.assign(p.ghost_entries / shrink, 0.0);
}

MatrixAssembler::Values::~Values() {
  restore();
}

void MatrixAssembler::Values::restore() {
  if (layout_ == MatrixLayout::Symmetric) diagonal_ = nullptr;
  if (diagonal_) MatSeqAIJRestoreArrayWrite(diagonal_part_, &diagonal_);
  if (off_diagonal_) MatSeqAIJRestoreArrayWrite(off_diagonal_part_, &off_diagonal_);
  diagonal_ = off_diagonal_ = nullptr;
}

void MatrixAssembler::Values::gather() {
  const AssemblyPattern& p = assembler_.pattern_;
  const int l = static_cast<int>(layout_);
  if (layout_ != MatrixLayout::Symmetric && p.ghost_to_diagonal[l]) {
    PetscSF to_a = p.ghost_to_diagonal[l], to_b = p.ghost_to_off_diagonal[l];
    PetscScalar* const ghost = ghost_.data();
    NM_PETSC(PetscSFReduceBegin(to_a, MPIU_SCALAR, ghost, diagonal_, MPI_SUM));
    NM_PETSC(PetscSFReduceBegin(to_b, MPIU_SCALAR, ghost, off_diagonal_, MPI_SUM));
    NM_PETSC(PetscSFReduceEnd(to_a, MPIU_SCALAR, ghost, diagonal_, MPI_SUM));
    NM_PETSC(PetscSFReduceEnd(to_b, MPIU_SCALAR, ghost, off_diagonal_, MPI_SUM));
  }
  const int d = assembler_.dofs_.dim();
  const std::vector<std::uint8_t>& fixed = assembler_.fixed_;
  for (PetscInt k = 0; k < static_cast<PetscInt>(fixed.size()); ++k) {
    if (!fixed[k] || p.diagonal[k] < 0) continue;
    switch (layout_) {
      case MatrixLayout::Coupled:
        diagonal_[p.diagonal[k]] = 1.0;
        break;
      case MatrixLayout::Uncoupled:
        diagonal_[(p.diagonal[k] - k % d) / d] = 1.0;
        break;
      case MatrixLayout::Scalar:  // the vertex's row, once
        if (k % d == 0) diagonal_[p.scalar_entry(k / d, p.diagonal[k], d)] = 1.0;
        break;
      case MatrixLayout::Symmetric:
        diagonal_[upper_diagonal(k / d) + (d + 1) * (k % d)] = 1.0;
        break;
    }
  }
}

PetscInt MatrixAssembler::Values::upper_diagonal(PetscInt v) const {
  const UpperBlocks& u = *assembler_.upper_;
  const int d = assembler_.dofs_.dim();
  return d * d * (u.diagonal[v] + u.shift[v]);
}

void MatrixAssembler::Values::add_to_diagonal_block(PetscInt v, const double* block) {
  const int d = assembler_.dofs_.dim();
  if (layout_ == MatrixLayout::Symmetric) {
    for (int k = 0; k < d * d; ++k) diagonal_[upper_diagonal(v) + k] += block[k];
    return;
  }
  if (layout_ != MatrixLayout::Coupled)
    fail("internal error: a diagonal block added to a matrix without couplings");
  const AssemblyPattern& p = assembler_.pattern_;
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      diagonal_[p.diagonal[d * v] + a * p.row_stride[v] + b] += block[a * d + b];
}

void MatrixAssembler::Values::finish() {
  restore();
  // Restoring the arrays marks A and B as changed, but solvers look at the state of the
  // MPIAIJ matrix itself; a shell's values change without PETSc's knowing.
  if (off_diagonal_part_ || layout_ == MatrixLayout::Symmetric) {
    NM_PETSC(MatAssemblyBegin(m_, MAT_FINAL_ASSEMBLY));
    NM_PETSC(MatAssemblyEnd(m_, MAT_FINAL_ASSEMBLY));
  }
}

}  // namespace neomesh
