// The matrices of H(α) and L (docs/method.md §3, §4) and the addition of cell blocks into
// them. The assembler owns the sparsity pattern (assembly_pattern.hpp), creates every matrix
// it fills and tags it with its layout, so that assembly knows where each entry sits instead
// of inferring it from the matrix; a matrix it did not create is refused.
//
// Fixed dofs are eliminated here: their rows and columns are left out of every cell block
// and their diagonal entries set to 1 (docs/method.md §3). A Scalar matrix (one component of
// the vector Laplacian) needs every vertex fixed in all or none of its components.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/petsc.hpp"
#include "energy/assembly_pattern.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// MatMult of the coupled matrices (H(α), and L where vertices slide) that MatrixAssembler::create
// makes on one rank: PETSc's SeqAIJ product runs on one core, and it is most of a δ̃ solve's CG
// iteration besides the V-cycles. The rows are shared among the OpenMP threads, each summed in
// column order by one of them: the same result for any number of threads.
PetscErrorCode threaded_product(Mat A, Vec x, Vec y);

// The coupled pattern stored once, on one rank (MatrixLayout::Symmetric): in each vertex's row
// (the matrix's row order), the blocks of the vertices w ≥ v in that order, its own first; block
// k holds entry (D v + a, D w + b) at D² · k + D · a + b. The product reads the blocks below the
// diagonal as transposes of blocks above, and sums every row in the order of a Coupled
// matrix's row: an exactly symmetric matrix gives the same bits either way.
struct UpperBlocks {
  std::vector<PetscInt> row_start;  // per row vertex, and the total: its first block
  std::vector<PetscInt> column;     // per block: its column vertex
  // Per row vertex w, the blocks (v, w) with v < w, in increasing v: CSR lower_start into
  // lower_block (the block) and lower_row (v).
  std::vector<PetscInt> lower_start, lower_block, lower_row;
  // Per local vertex (MeshView order): block k of its coupled row, counted as
  // AssemblyPattern::scalar_entry counts them, is block k + shift here if k ≥ diagonal (its
  // diagonal block), and below the diagonal otherwise.
  std::vector<PetscInt> diagonal, shift;
};

class MatrixAssembler {
 public:
  // Collective: builds the pattern. `fixed`: per local dof (MeshView order), 1 if fixed.
  // `view` and `dofs` must outlive the assembler.
  MatrixAssembler(const MeshView& view, const DofMap& dofs, std::span<const std::uint8_t> fixed);
  ~MatrixAssembler();
  MatrixAssembler(const MatrixAssembler&) = delete;
  MatrixAssembler& operator=(const MatrixAssembler&) = delete;

  // Collective. A matrix with the sparsity of `layout`, values not yet assembled; symmetric.
  // Scalar: throws Error unless every vertex has all or none of its dofs fixed (on every rank).
  // Symmetric: a MATSHELL that multiplies (and gives its diagonal); throws Error on several
  // ranks.
  OwnedMat create(MatrixLayout layout);
  // The layout of a matrix made by create() of this assembler; throws Error for any other.
  MatrixLayout layout(Mat m) const;

  // The chunks of block b in colour order (assembly_pattern.hpp): no two chunks of one colour
  // share a vertex; colour j is colour_chunks(b)[colour_start(b)[j] .. colour_start(b)[j+1]),
  // chunk k the block's cells [k · kChunk, (k + 1) · kChunk).
  static constexpr PetscInt kChunk = AssemblyPattern::kChunk;
  const std::vector<PetscInt>& colour_chunks(std::size_t b) const {
    return pattern_.colour_chunks[b];
  }
  const std::vector<PetscInt>& colour_start(std::size_t b) const {
    return pattern_.colour_start[b];
  }

  class Values;

 private:
  // A Coupled, Uncoupled or Scalar matrix on a CSR of its own.
  OwnedMat create_first(MatrixLayout layout);
  // Symmetric: the upper blocks of the coupled pattern, and a matrix on new values for them.
  void make_upper_blocks();
  OwnedMat create_upper_matrix() const;

  const MeshView& view_;
  const DofMap& dofs_;
  std::vector<std::uint8_t> fixed_;         // per local dof
  std::vector<std::uint8_t> vertex_fixed_;  // per local vertex: some dof of it is fixed
  bool components_fixed_alike_ = true;      // no local vertex has only some dofs fixed
  AssemblyPattern pattern_;
  std::uint64_t id_;  // tells this assembler's matrices from those of others
  // The first Coupled matrix; later ones share its pattern (MAT_SHARE_NONZERO_PATTERN).
  OwnedMat first_coupled_;
  // Once a Symmetric matrix was made; every Symmetric matrix shares them.
  std::shared_ptr<const UpperBlocks> upper_;
};

// The values of one matrix made by MatrixAssembler::create, while it is assembled: all zero
// at first; cell blocks are added; gather() completes the rows, finish() hands the values
// back to the matrix. Without finish() (an exception) the matrix is left unassembled.
class MatrixAssembler::Values {
 public:
  // Throws Error if `m` was not made by `assembler`.
  Values(const MatrixAssembler& assembler, Mat m);
  ~Values();
  Values(const Values&) = delete;
  Values& operator=(const Values&) = delete;

  MatrixLayout layout() const { return layout_; }

  // Adds the (D·N) × (D·N) block of cell c of block b (column-major, dof D·i + a of local
  // vertex i), without the rows and columns of fixed dofs; an Uncoupled matrix takes only
  // the entries within a component, a Scalar one only those of component 0 (the block's
  // components must then be equal). Chunks of one colour may be added concurrently.
  template <int D, int N>
  void add_cell(std::size_t b, PetscInt c, const double* block) {
    switch (layout_) {
      case MatrixLayout::Coupled:
        add_cell<D, N, true>(b, c, block);
        break;
      case MatrixLayout::Uncoupled:
        add_cell<D, N, false>(b, c, block);
        break;
      case MatrixLayout::Scalar:
        add_scalar_cell<D, N>(b, c, block);
        break;
      case MatrixLayout::Symmetric:
        add_upper_cell<D, N>(b, c, block);
        break;
    }
  }
  // Collective: adds the rows of ghost vertices into their owners' rows and sets the
  // diagonal of fixed dofs to 1.
  void gather();
  // After gather: adds the D × D block (row-major) to the diagonal block of owned vertex v.
  // Coupled matrices only.
  void add_to_diagonal_block(PetscInt v, const double* block);
  // Collective: the matrix holds the values and is assembled.
  void finish();

 private:
  template <int D, int N, bool Coupled>
  void add_cell(std::size_t b, PetscInt c, const double* block);
  template <int D, int N>
  void add_scalar_cell(std::size_t b, PetscInt c, const double* block);
  template <int D, int N>
  void add_upper_cell(std::size_t b, PetscInt c, const double* block);
  // Adds the D × D block of vertices (v, w) of a cell's block (`in`: its entry (D vi, D vj),
  // leading dimension n) to `out`, row a at out + a · stride, without the rows and columns of
  // fixed dofs; only the entries within a component unless Coupled.
  template <int D, int n, bool Coupled>
  void add_pair(PetscScalar* out, PetscInt stride, const double* in, PetscInt v, PetscInt w) const;
  void restore();
  // Symmetric: the first value of local vertex v's diagonal block.
  PetscInt upper_diagonal(PetscInt v) const;

  const MatrixAssembler& assembler_;
  Mat m_;
  Mat diagonal_part_ = nullptr, off_diagonal_part_ = nullptr;  // A and B; B null on one rank
  MatrixLayout layout_ = MatrixLayout::Coupled;
  PetscScalar* diagonal_ = nullptr;  // A's values, or a Symmetric matrix's blocks
  PetscScalar* off_diagonal_ = nullptr;
  std::vector<PetscScalar> ghost_;  // G of assembly_pattern.hpp
};

template <int D, int N, bool Coupled>
void MatrixAssembler::Values::add_cell(std::size_t b, PetscInt c, const double* block) {
  constexpr int n = D * N;  // leading dimension of `block`
  const AssemblyPattern& p = assembler_.pattern_;
  const PetscInt* vertex = assembler_.view_.blocks[b].cell(c);
  const PetscInt* entry = p.block_entry[b].data() + c * N * N;
  // Uncoupled matrices hold entry e of the coupled pattern at e / D, rows D times shorter.
  constexpr int shrink = Coupled ? 1 : D;
  PetscScalar* const ghost = ghost_.data();
  for (int vi = 0; vi < N; ++vi) {
    const PetscInt v = vertex[vi];
    // The row of a ghost vertex goes to G, and from there to its owner.
    PetscScalar* const row = assembler_.view_.owned[v] ? diagonal_ : ghost;
    const PetscInt row_stride = p.row_stride[v] / shrink;
    const PetscInt off_row_stride = p.off_row_stride[v] / shrink;
    for (int vj = 0; vj < N; ++vj) {
      const PetscInt e = entry[vi * N + vj];
      PetscScalar* const out = e >= 0 ? row + e / shrink : off_diagonal_ + ~e / shrink;
      const PetscInt stride = e >= 0 ? row_stride : off_row_stride;
      add_pair<D, n, Coupled>(out, stride, block + D * vj * n + D * vi, v, vertex[vj]);
    }
  }
}

template <int D, int n, bool Coupled>
void MatrixAssembler::Values::add_pair(PetscScalar* out, PetscInt stride, const double* in,
                                       PetscInt v, PetscInt w) const {
  const std::vector<std::uint8_t>& fixed = assembler_.fixed_;
  // Most vertex pairs have no fixed dof: add without looking at each one.
  const bool plain = !assembler_.vertex_fixed_[v] && !assembler_.vertex_fixed_[w];
  for (int a = 0; a < D; ++a) {
    if (!plain && fixed[D * v + a]) continue;
    if constexpr (!Coupled) {
      if (plain || !fixed[D * w + a]) out[a * stride] += in[a * n + a];
    } else {
      for (int bb = 0; bb < D; ++bb)
        if (plain || !fixed[D * w + bb]) out[a * stride + bb] += in[bb * n + a];
    }
  }
}

template <int D, int N>
void MatrixAssembler::Values::add_scalar_cell(std::size_t b, PetscInt c, const double* block) {
  constexpr int n = D * N;  // leading dimension of `block`
  const AssemblyPattern& p = assembler_.pattern_;
  const std::vector<std::uint8_t>& vertex_fixed = assembler_.vertex_fixed_;
  const PetscInt* vertex = assembler_.view_.blocks[b].cell(c);
  const PetscInt* entry = p.block_entry[b].data() + c * N * N;
  PetscScalar* const ghost = ghost_.data();
  for (int vi = 0; vi < N; ++vi) {
    const PetscInt v = vertex[vi];
    if (vertex_fixed[v]) continue;  // and so are all its dofs
    PetscScalar* const row = assembler_.view_.owned[v] ? diagonal_ : ghost;
    for (int vj = 0; vj < N; ++vj) {
      if (vertex_fixed[vertex[vj]]) continue;
      const PetscInt e = p.scalar_entry(v, entry[vi * N + vj], D);
      *(e >= 0 ? row + e : off_diagonal_ + ~e) += block[D * vj * n + D * vi];  // (D vi, D vj)
    }
  }
}

template <int D, int N>
void MatrixAssembler::Values::add_upper_cell(std::size_t b, PetscInt c, const double* block) {
  constexpr int n = D * N;  // leading dimension of `block`
  const AssemblyPattern& p = assembler_.pattern_;
  const UpperBlocks& upper = *assembler_.upper_;
  const PetscInt* vertex = assembler_.view_.blocks[b].cell(c);
  const PetscInt* entry = p.block_entry[b].data() + c * N * N;
  for (int vi = 0; vi < N; ++vi) {
    const PetscInt v = vertex[vi];
    for (int vj = 0; vj < N; ++vj) {
      const PetscInt k = p.scalar_entry(v, entry[vi * N + vj], D);
      if (k < upper.diagonal[v]) continue;  // the transpose of the block in w's row
      add_pair<D, n, true>(diagonal_ + D * D * (k + upper.shift[v]), D, block + D * vj * n + D * vi,
                           v, vertex[vj]);
    }
  }
}

}  // namespace neomesh
