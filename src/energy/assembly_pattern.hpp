// The sparsity of H(α) and L on a single rank, built once per mesh, and where each cell's
// (dof × dof) block lands in the matrix's value array: assembly then adds cell blocks straight
// into the AIJ values (no COO sort of (dim·vertices)² entries per cell, no second copy of them).
//
// Rows are dofs in the DofMap's global order; each vertex's `dim` rows share the sorted list of
// its neighbour vertices (block size dim), so entry (row dim·v + a, column dim·w + b) sits at
// vertex_entry(v, w) + a · row_stride[v] + b.
//
// Cells are coloured so that no two cells of a colour share a vertex: threads add the cells of
// one colour without races, and every entry receives its contributions in the same order for
// any number of threads.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "mesh/dof_map.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

struct AssemblyPattern {
  std::vector<PetscInt> row_start;   // CSR: global rows + 1
  std::vector<PetscInt> column;      // global column per entry, sorted within each row; freed
                                     // once a matrix holds it
  std::vector<PetscInt> row_stride;  // per local vertex: entries per row (dim · neighbours)
  std::vector<PetscInt> diagonal;    // per local dof: its diagonal entry
  // Per block, per cell, per (i, j) in i · vertices + j: the entry of (dof 0 of vertex i, dof 0
  // of vertex j).
  std::vector<std::vector<PetscInt>> block_entry;
  // Per block: its cells (block-local indices) ordered by colour; colour k is
  // colour_order[colour_start[k] .. colour_start[k+1]).
  std::vector<std::vector<PetscInt>> colour_order, colour_start;

  std::size_t num_entries() const { return static_cast<std::size_t>(row_start.back()); }
};

// The CSR (row starts, columns) of the same rows without the couplings between different
// components: entry e of the coupled pattern with column ≡ row (mod dim) is entry e / dim here.
// Needs `column`.
std::pair<std::vector<PetscInt>, std::vector<PetscInt>> uncoupled_csr(const AssemblyPattern& p,
                                                                      int dim);

// The pattern of a mesh held by one rank, or nothing when the DofMap spans several ranks or
// does not number a vertex's dofs consecutively (then assembly goes through COO).
std::optional<AssemblyPattern> make_assembly_pattern(const MeshView& view, const DofMap& dofs);

}  // namespace neomesh
