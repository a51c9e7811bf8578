// The matrices of H(α) and L (docs/method.md §3, §4) and the addition of cell blocks into
// them. The assembler owns the sparsity pattern (assembly_pattern.hpp), creates every matrix
// it fills and tags it with its layout, so that assembly knows where each entry sits instead
// of inferring it from the matrix; a matrix it did not create is refused.
//
// Fixed dofs are eliminated here: their rows and columns are left out of every cell block
// and their diagonal entries set to 1 (docs/method.md §3).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/petsc.hpp"
#include "energy/assembly_pattern.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

enum class MatrixLayout {
  Uncoupled,  // only couplings within a component (1/dim of the entries): the vector Laplacian
  Coupled,    // every coupling of two vertices' dofs: H(α), or L with projected vertices
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
  const MeshView& view_;
  const DofMap& dofs_;
  std::vector<std::uint8_t> fixed_;         // per local dof
  std::vector<std::uint8_t> vertex_fixed_;  // per local vertex: some dof of it is fixed
  AssemblyPattern pattern_;
  std::uint64_t id_;  // tells this assembler's matrices from those of others
  // The first matrix of each layout; later ones share its pattern (MAT_SHARE_NONZERO_PATTERN).
  OwnedMat first_[2];
  // On one rank, once the coupled matrix took the pattern's columns (and until both layouts
  // have a matrix): the columns in that matrix.
  const std::vector<PetscInt>* coupled_columns_ = nullptr;
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

  MatrixLayout layout() const { return coupled_ ? MatrixLayout::Coupled : MatrixLayout::Uncoupled; }

  // Adds the (D·N) × (D·N) block of cell c of block b (column-major, dof D·i + a of local
  // vertex i), without the rows and columns of fixed dofs; an Uncoupled matrix takes only
  // the entries within a component. Chunks of one colour may be added concurrently.
  template <int D, int N>
  void add_cell(std::size_t b, PetscInt c, const double* block) {
    if (coupled_)
      add_cell<D, N, true>(b, c, block);
    else
      add_cell<D, N, false>(b, c, block);
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
  void restore();

  const MatrixAssembler& assembler_;
  Mat m_;
  Mat diagonal_part_ = nullptr, off_diagonal_part_ = nullptr;  // A and B; B null on one rank
  bool coupled_ = true;
  PetscScalar* diagonal_ = nullptr;
  PetscScalar* off_diagonal_ = nullptr;
  std::vector<PetscScalar> ghost_;  // G of assembly_pattern.hpp
};

template <int D, int N, bool Coupled>
void MatrixAssembler::Values::add_cell(std::size_t b, PetscInt c, const double* block) {
  constexpr int n = D * N;  // leading dimension of `block`
  const AssemblyPattern& p = assembler_.pattern_;
  const std::vector<std::uint8_t>& fixed = assembler_.fixed_;
  const std::vector<std::uint8_t>& vertex_fixed = assembler_.vertex_fixed_;
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
      const PetscInt w = vertex[vj];
      const PetscInt e = entry[vi * N + vj];
      PetscScalar* const out = e >= 0 ? row + e / shrink : off_diagonal_ + ~e / shrink;
      const PetscInt stride = e >= 0 ? row_stride : off_row_stride;
      const double* in = block + D * vj * n + D * vi;  // entry (D vi, D vj)
      // Most vertex pairs have no fixed dof: add without looking at each one.
      const bool plain = !vertex_fixed[v] && !vertex_fixed[w];
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
  }
}

}  // namespace neomesh
