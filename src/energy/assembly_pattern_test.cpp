#include "energy/assembly_pattern.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {
namespace {

// Every pair of dofs of a cell has its entry, at the column it names; chunks of one colour
// share no vertex; the rows hold exactly the couplings of the mesh.
void check_pattern(const MeshData& data) {
  const MeshView view = serial_view(data);
  const int d = view.dim;
  const DofMap dofs = DofMap::serial(d, view.num_vertices);
  const AssemblyPattern pattern = make_assembly_pattern(view, dofs);
  EXPECT_EQ(pattern.off_diagonal_entries, 0u);  // one rank: no B, no G
  EXPECT_EQ(pattern.ghost_entries, 0u);
  const auto [row_start, column] = layout_csr(pattern, MatrixLayout::Coupled, d);
  std::vector<std::set<PetscInt>> coupled(d * view.num_vertices);
  for (std::size_t b = 0; b < view.blocks.size(); ++b) {
    const CellBlock& block = view.blocks[b];
    const int n = num_vertices(block.type);
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          for (int a = 0; a < d; ++a)
            for (int bb = 0; bb < d; ++bb) {
              const PetscInt vi = block.cell(c)[i], vj = block.cell(c)[j];
              const PetscInt e =
                  pattern.block_entry[b][(c * n + i) * n + j] + a * pattern.row_stride[vi] + bb;
              EXPECT_EQ(column[e], d * vj + bb);
              EXPECT_GE(e, row_start[d * vi + a]);
              EXPECT_LT(e, row_start[d * vi + a + 1]);
              coupled[d * vi + a].insert(d * vj + bb);
            }
    const auto& chunks = pattern.colour_chunks[b];
    const auto& start = pattern.colour_start[b];
    const PetscInt chunk = AssemblyPattern::kChunk;
    EXPECT_EQ(start.back(), (block.size() + chunk - 1) / chunk);
    std::set<PetscInt> all_chunks(chunks.begin(), chunks.end());
    EXPECT_EQ(all_chunks.size(), chunks.size());
    for (std::size_t k = 0; k + 1 < start.size(); ++k) {
      std::vector<PetscInt> owner(view.num_vertices, -1);  // the chunk of this colour at a vertex
      for (PetscInt i = start[k]; i < start[k + 1]; ++i)
        for (PetscInt c = chunks[i] * chunk; c < std::min(block.size(), (chunks[i] + 1) * chunk);
             ++c)
          for (int v = 0; v < n; ++v) {
            PetscInt& at = owner[block.cell(c)[v]];
            EXPECT_TRUE(at < 0 || at == chunks[i]);
            at = chunks[i];
          }
    }
  }
  for (PetscInt row = 0; row < d * view.num_vertices; ++row) {
    EXPECT_EQ(row_start[row + 1] - row_start[row], static_cast<PetscInt>(coupled[row].size()));
    EXPECT_EQ(column[pattern.diagonal[row]], row);
  }
  // The smaller layouts hold the coupled rows' entries within a component, or component 0's.
  const auto [uncoupled_start, uncoupled_column] = layout_csr(pattern, MatrixLayout::Uncoupled, d);
  const auto [scalar_start, scalar_column] = layout_csr(pattern, MatrixLayout::Scalar, d);
  for (PetscInt row = 0; row < d * view.num_vertices; ++row) {
    std::vector<PetscInt> within, scalar;
    for (const PetscInt c : coupled[row])
      if (c % d == row % d) within.push_back(c);
    EXPECT_EQ(std::vector<PetscInt>(uncoupled_column.begin() + uncoupled_start[row],
                                    uncoupled_column.begin() + uncoupled_start[row + 1]),
              within);
    if (row % d) continue;
    for (const PetscInt c : within) scalar.push_back(c / d);
    EXPECT_EQ(std::vector<PetscInt>(scalar_column.begin() + scalar_start[row / d],
                                    scalar_column.begin() + scalar_start[row / d + 1]),
              scalar);
  }
}

TEST(AssemblyPattern, EntriesColumnsAndColoursMatchTheMesh) {
  check_pattern(square_random(5, 0.2, 1));
  check_pattern(box(CellType::Triangle, 4));
  check_pattern(box(CellType::Tetrahedron, 2));
  check_pattern(box(CellType::Hexahedron, 3));
  check_pattern(box(CellType::Tetrahedron, 12));  // 10 368 cells: several chunks per colour
}

}  // namespace
}  // namespace neomesh
