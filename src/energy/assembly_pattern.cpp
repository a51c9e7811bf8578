#include "energy/assembly_pattern.hpp"

#include <algorithm>
#include <numeric>

namespace neomesh {

namespace {

// The cells around each local vertex, as CSR over vertices (cells numbered as in MeshView).
struct VertexCells {
  std::vector<PetscInt> start, cells;
  std::vector<const PetscInt*> cell_vertices;  // per cell
  std::vector<int> cell_size;                  // vertices per cell

  explicit VertexCells(const MeshView& view)
      : start(view.num_vertices + 1, 0), cell_vertices(view.num_cells), cell_size(view.num_cells) {
    for (const CellBlock& block : view.blocks)
      for (PetscInt c = 0; c < block.size(); ++c) {
        cell_vertices[block.first_cell + c] = block.cell(c);
        cell_size[block.first_cell + c] = num_vertices(block.type);
        for (int i = 0; i < num_vertices(block.type); ++i) ++start[block.cell(c)[i] + 1];
      }
    std::partial_sum(start.begin(), start.end(), start.begin());
    cells.resize(start.back());
    std::vector<PetscInt> next(start.begin(), start.end() - 1);
    for (PetscInt cell = 0; cell < view.num_cells; ++cell)
      for (int i = 0; i < cell_size[cell]; ++i) cells[next[cell_vertices[cell][i]]++] = cell;
  }
};

// Greedy colouring: each cell takes the smallest colour no earlier cell sharing a vertex has.
std::vector<PetscInt> colour_cells(const VertexCells& around, PetscInt num_cells) {
  std::vector<PetscInt> colour(num_cells, -1);
  std::vector<PetscInt> taken_by;  // taken_by[k] == cell: colour k is taken near `cell`
  for (PetscInt cell = 0; cell < num_cells; ++cell) {
    for (int i = 0; i < around.cell_size[cell]; ++i) {
      const PetscInt v = around.cell_vertices[cell][i];
      for (PetscInt k = around.start[v]; k < around.start[v + 1]; ++k) {
        const PetscInt other = colour[around.cells[k]];
        if (other < 0) continue;
        if (other >= static_cast<PetscInt>(taken_by.size())) taken_by.resize(other + 1, -1);
        taken_by[other] = cell;
      }
    }
    PetscInt k = 0;
    while (k < static_cast<PetscInt>(taken_by.size()) && taken_by[k] == cell) ++k;
    colour[cell] = k;
  }
  return colour;
}

}  // namespace

std::pair<std::vector<PetscInt>, std::vector<PetscInt>> uncoupled_csr(const AssemblyPattern& p,
                                                                      int dim) {
  const std::size_t rows = p.row_start.size() - 1;
  std::vector<PetscInt> row_start(rows + 1), column(p.num_entries() / dim);
  for (std::size_t r = 0; r <= rows; ++r) row_start[r] = p.row_start[r] / dim;
#pragma omp parallel for schedule(static)
  for (std::size_t r = 0; r < rows; ++r)
    for (PetscInt e = p.row_start[r] + static_cast<PetscInt>(r % dim); e < p.row_start[r + 1];
         e += dim)
      column[e / dim] = p.column[e];
  return {std::move(row_start), std::move(column)};
}

std::optional<AssemblyPattern> make_assembly_pattern(const MeshView& view, const DofMap& dofs) {
  int ranks = 1;
  MPI_Comm_size(dofs.comm(), &ranks);
  if (ranks != 1) return std::nullopt;
  const int d = dofs.dim();
  const PetscInt nv = view.num_vertices;
  const std::vector<PetscInt>& global = dofs.global_dof();
  std::vector<PetscInt> global_vertex(nv), local_vertex(nv);
  for (PetscInt v = 0; v < nv; ++v) {
    const PetscInt g = global[d * v];
    if (g % d != 0) return std::nullopt;
    for (int a = 1; a < d; ++a)
      if (global[d * v + a] != g + a) return std::nullopt;
    global_vertex[v] = g / d;
    local_vertex[g / d] = v;
  }

  const VertexCells around(view);
  // Neighbour vertices (global numbers, sorted, the vertex itself included) in global order.
  // Two passes over the vertices, counting then filling, keep it parallel without allocations.
  std::vector<PetscInt> first_neighbour(nv + 1, 0), neighbours;
  auto collect = [&](PetscInt g, std::vector<PetscInt>& out) {
    const PetscInt v = local_vertex[g];
    out.clear();
    for (PetscInt k = around.start[v]; k < around.start[v + 1]; ++k) {
      const PetscInt cell = around.cells[k];
      for (int i = 0; i < around.cell_size[cell]; ++i)
        out.push_back(global_vertex[around.cell_vertices[cell][i]]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
#pragma omp parallel
  {
    std::vector<PetscInt> buffer;
#pragma omp for schedule(static)
    for (PetscInt g = 0; g < nv; ++g) {
      collect(g, buffer);
      first_neighbour[g + 1] = static_cast<PetscInt>(buffer.size());
    }
#pragma omp single
    {
      std::partial_sum(first_neighbour.begin(), first_neighbour.end(), first_neighbour.begin());
      neighbours.resize(first_neighbour.back());
    }
#pragma omp for schedule(static)
    for (PetscInt g = 0; g < nv; ++g) {
      collect(g, buffer);
      std::copy(buffer.begin(), buffer.end(), neighbours.begin() + first_neighbour[g]);
    }
  }

  AssemblyPattern p;
  auto degree = [&](PetscInt g) { return first_neighbour[g + 1] - first_neighbour[g]; };
  // First entry of vertex g's block row, and of its block (g, w).
  auto block_row = [&](PetscInt g) { return d * d * first_neighbour[g]; };
  auto vertex_entry = [&](PetscInt g, PetscInt w) {
    const auto row = neighbours.begin() + first_neighbour[g];
    return block_row(g) + d * (std::lower_bound(row, row + degree(g), w) - row);
  };
  p.row_start.resize(d * nv + 1);
  p.column.resize(static_cast<std::size_t>(d) * d * first_neighbour.back());
#pragma omp parallel for schedule(static)
  for (PetscInt g = 0; g < nv; ++g) {
    for (int a = 0; a < d; ++a) {
      PetscInt e = block_row(g) + a * d * degree(g);
      p.row_start[d * g + a] = e;
      for (PetscInt k = first_neighbour[g]; k < first_neighbour[g + 1]; ++k)
        for (int b = 0; b < d; ++b) p.column[e++] = d * neighbours[k] + b;
    }
  }
  p.row_start[d * nv] = static_cast<PetscInt>(p.column.size());

  p.row_stride.resize(nv);
  p.diagonal.resize(d * nv);
  for (PetscInt v = 0; v < nv; ++v) {
    const PetscInt g = global_vertex[v];
    p.row_stride[v] = d * degree(g);
    for (int a = 0; a < d; ++a)
      p.diagonal[d * v + a] = vertex_entry(g, g) + a * p.row_stride[v] + a;
  }

  const std::vector<PetscInt> colour = colour_cells(around, view.num_cells);
  for (const CellBlock& block : view.blocks) {
    const int n = num_vertices(block.type);
    std::vector<PetscInt>& entry = p.block_entry.emplace_back(block.vertices.size() * n);
#pragma omp parallel for schedule(static)
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          entry[(c * n + i) * n + j] =
              vertex_entry(global_vertex[block.cell(c)[i]], global_vertex[block.cell(c)[j]]);

    // Counting sort of the block's cells by colour.
    const PetscInt* first = colour.data() + block.first_cell;
    const PetscInt colours = block.size() ? *std::max_element(first, first + block.size()) + 1 : 0;
    std::vector<PetscInt>& start = p.colour_start.emplace_back(colours + 1, 0);
    for (PetscInt c = 0; c < block.size(); ++c) ++start[first[c] + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<PetscInt>& order = p.colour_order.emplace_back(block.size());
    std::vector<PetscInt> next(start.begin(), start.end() - 1);
    for (PetscInt c = 0; c < block.size(); ++c) order[next[first[c]]++] = c;
  }
  return p;
}

}  // namespace neomesh
