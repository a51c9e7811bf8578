// The sparsity of H(α) and L, built once per mesh, and where each cell's (dof × dof) block
// lands in the matrix's value arrays: assembly adds cell blocks straight into the AIJ values
// (no COO sort of (dim·vertices)² entries per cell, no second copy of them).
//
// Each rank builds the rows of the vertices it owns, in the DofMap's global order. PETSc's
// MPIAIJ keeps them in two parts: A, the columns of this rank's vertices, and B, all other
// columns (B is empty on one rank). A cell's block in the row of a ghost vertex (owned by
// another rank) goes into a ghost buffer G laid out like rows of its own; once per assembly
// a PetscSF built here adds G into the owners' A and B. So no entry is sorted or searched
// after setup, on one rank or many.
//
// A, B and G are vertex-blocked: the dim rows of a vertex share its sorted list of neighbour
// vertices (in that part), so entry (row dim·v + a, column dim·w + b) sits at
// vertex_entry(v, w) + a · stride(v) + b.
//
// Cells are added in chunks of consecutive cells, and the chunks coloured so that no two
// chunks of a colour share a vertex: threads add the chunks of one colour without races, and
// every entry receives its contributions in the same order for any number of threads. A chunk
// rather than a cell per colour keeps the entries a thread adds to in cache: with one cell
// per colour each colour swept the whole matrix.
//
// The same pattern serves four layouts of matrix (MatrixLayout): every coupling, only those
// within a component, one component alone (the n × n scalar matrix), and every coupling
// stored once (the blocks on and above the diagonal). The smaller ones keep the
// vertex-blocked order, so their entries follow from the coupled pattern's.
#pragma once

#include <utility>
#include <vector>

#include "core/petsc.hpp"
#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

// Which entries of the pattern a matrix holds (dof = dim · vertex + component):
enum class MatrixLayout {
  Uncoupled,  // only couplings within a component (1/dim of the entries): the vector Laplacian
  Coupled,    // every coupling of two vertices' dofs: H(α), or L with projected vertices
  Scalar,     // one component: n × n, a row per vertex (1/dim² of the entries); the scalar
              // Laplacian whose dim copies the Uncoupled vector Laplacian holds
  Symmetric,  // every coupling, on one rank, stored once: the dim × dim blocks on and above
              // the diagonal (about half of Coupled's memory), in a matrix that only
              // multiplies (MatrixAssembler's UpperBlocks)
};

struct AssemblyPattern {
  // Per owned vertex (in the DofMap's order), its neighbours: the vertices it shares a cell
  // with, itself included, as global vertex numbers (global dof / dim), sorted; CSR
  // neighbour[neighbour_start[r] .. neighbour_start[r + 1]). Each layout's rows follow from
  // them (layout_csr); they are dim² times smaller than the coupled matrix's columns.
  std::vector<PetscInt> neighbour_start, neighbour;
  std::size_t diagonal_entries = 0;      // in A
  std::size_t off_diagonal_entries = 0;  // in B
  std::size_t ghost_entries = 0;         // in G
  PetscInt global_entries = 0;           // of the whole matrix, over all ranks
  // Per local vertex: entries per row in A (owned vertex) or G (ghost), and in B (0 for ghosts).
  std::vector<PetscInt> row_stride, off_row_stride;
  std::vector<PetscInt> diagonal;  // per local dof: its diagonal entry in A, or −1 (ghost)
  // Per local vertex, counted in vertex blocks: the first block of its rows in A (owned
  // vertex) or G (ghost), and in B (0 for ghosts). Its blocks' entries are dim² apart.
  std::vector<PetscInt> row_first, off_row_first;
  // Per block, per cell, per (i, j) in i · vertices + j: the entry of (dof 0 of vertex i, dof 0
  // of vertex j) in A or G (as vertex i is owned or a ghost), or e < 0 for entry ~e of B.
  std::vector<std::vector<PetscInt>> block_entry;
  // Chunk k of a block is its cells [k · kChunk, (k + 1) · kChunk) (block-local indices).
  static constexpr PetscInt kChunk = 1024;
  // Per block: its chunks ordered by colour; colour j is
  // colour_chunks[colour_start[j] .. colour_start[j+1]).
  std::vector<std::vector<PetscInt>> colour_chunks, colour_start;
  // From G (leaves) into the owners' A and B values (roots), per MatrixLayout: the coupled
  // SFs move every entry, the uncoupled ones only entries within a component, at entry / dim,
  // the scalar ones only component 0's, at scalar_entry. Null on one rank.
  OwnedSF ghost_to_diagonal[3], ghost_to_off_diagonal[3];

  // Entry e of block_entry (or diagonal), in the row of local vertex v, as an entry of the
  // scalar matrix (dof 0 of both vertices): in A or G for e ≥ 0, else ~result in B.
  PetscInt scalar_entry(PetscInt v, PetscInt e, int dim) const {
    // e = dim² · first + dim · k for the k-th block of the row; the scalar row holds it at
    // first + k.
    if (e >= 0) return e / dim - (dim - 1) * row_first[v];
    return ~(~e / dim - (dim - 1) * off_row_first[v]);
  }
};

// The CSR of a layout's owned rows (Coupled, Uncoupled or Scalar; not Symmetric) with global
// columns, sorted within each row, as MatXAIJSetPreallocationCSR takes it. Row dim · v + a of
// the coupled matrix has the columns dim · w + b of each neighbour w of v; of the uncoupled one
// the columns dim · w + a; the scalar matrix's row v has the columns w.
std::pair<std::vector<PetscInt>, std::vector<PetscInt>> layout_csr(const AssemblyPattern& p,
                                                                   MatrixLayout layout, int dim);

// Collective. Throws Error if the DofMap does not number each rank's vertices consecutively
// from its first owned dof, with a vertex's dofs next to each other (as PlexMesh does).
AssemblyPattern make_assembly_pattern(const MeshView& view, const DofMap& dofs);

}  // namespace neomesh
