#include "solver/repair_search.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "mesh/gather.hpp"

namespace neomesh {

namespace {

// WholeMesh's cell types in one int: a straight cell's CellType, a curved cell's kCurved + its
// CurvedType.
constexpr int kCurved = 1000;

int nodes(int type) {
  return type >= kCurved ? facts(static_cast<CurvedType>(type - kCurved)).nodes
                         : facts(static_cast<CellType>(type)).vertices;
}

}  // namespace

WholeMesh gather_whole_mesh(const MeshView& view, std::span<const double> local,
                            const RepairFreedom& freedom, MPI_Comm comm) {
  const int d = view.dim;
  std::vector<std::int64_t> ids;
  std::vector<double> coords;
  std::vector<int> flags, geometry;
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    if (!view.owned[v]) continue;
    ids.push_back(view.input_vertex[v]);
    for (int a = 0; a < d; ++a) {  // (not insert(): a call per vertex)
      coords.push_back(local[d * v + a]);
      flags.push_back(freedom.fixed[d * v + a]);
    }
    geometry.push_back(freedom.geometry[v]);
  }
  std::vector<std::int64_t> cell_ids, cell_vertices;
  std::vector<int> types;  // a straight cell's CellType, a curved one's kCurved + its CurvedType
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      cell_ids.push_back(view.global_cell[block.first_cell + c]);
      types.push_back(block.curved ? kCurved + static_cast<int>(*block.curved)
                                   : static_cast<int>(block.type));
      const PetscInt* vertex = block.cell(c);
      for (int i = 0; i < block.nodes(); ++i) cell_vertices.push_back(view.input_vertex[vertex[i]]);
    }
  const auto all_ids = gatherv(comm, ids, MPI_INT64_T);
  const auto all_coords = gatherv(comm, coords, MPI_DOUBLE);
  const auto all_flags = gatherv(comm, flags, MPI_INT);
  const auto all_geometry = gatherv(comm, geometry, MPI_INT);
  const auto all_cell_ids = gatherv(comm, cell_ids, MPI_INT64_T);
  const auto all_types = gatherv(comm, types, MPI_INT);
  const auto all_cell_vertices = gatherv(comm, cell_vertices, MPI_INT64_T);

  WholeMesh m;
  m.dim = d;
  m.surface = view.surface;
  if (mpi_rank(comm) != 0) return m;
  std::vector<std::size_t> order(all_ids.size());
  std::iota(order.begin(), order.end(), 0);
  // (On one process the input's order already: nothing to sort.)
  if (!std::is_sorted(all_ids.begin(), all_ids.end()))
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return all_ids[a] < all_ids[b]; });
  for (std::size_t k : order) {
    m.vertex_id.push_back(all_ids[k]);
    for (int a = 0; a < d; ++a) {
      m.coords.push_back(all_coords[d * k + a]);
      m.fixed.push_back(static_cast<std::uint8_t>(all_flags[d * k + a]));
    }
    m.geometry.push_back(all_geometry[k]);
  }
  // The input numbers, ascending and distinct, are mostly 0, 1, 2, ...: a vertex's index is then
  // its number less the first.
  const bool consecutive =
      m.vertex_id.empty() ||
      m.vertex_id.back() - m.vertex_id.front() == static_cast<std::int64_t>(m.vertex_id.size()) - 1;
  auto index_of = [&m, consecutive](std::int64_t id) -> std::int64_t {
    if (consecutive) return id - m.vertex_id.front();
    return std::lower_bound(m.vertex_id.begin(), m.vertex_id.end(), id) - m.vertex_id.begin();
  };
  std::vector<std::int64_t> first(all_cell_ids.size() + 1, 0);
  for (std::size_t c = 0; c < all_cell_ids.size(); ++c)
    first[c + 1] = first[c] + nodes(all_types[c]);
  std::vector<std::size_t> cells(all_cell_ids.size());
  std::iota(cells.begin(), cells.end(), 0);
  if (!std::is_sorted(all_cell_ids.begin(), all_cell_ids.end()))
    std::sort(cells.begin(), cells.end(),
              [&](auto a, auto b) { return all_cell_ids[a] < all_cell_ids[b]; });
  m.offsets.push_back(0);
  for (std::size_t c : cells) {
    const bool curved = all_types[c] >= kCurved;
    m.types.push_back(curved ? facts(static_cast<CurvedType>(all_types[c] - kCurved)).linear
                             : static_cast<CellType>(all_types[c]));
    m.curved.push_back(static_cast<std::int8_t>(curved ? all_types[c] - kCurved : -1));
    for (std::int64_t k = first[c]; k < first[c + 1]; ++k)
      m.vertices.push_back(index_of(all_cell_vertices[k]));
    m.offsets.push_back(static_cast<std::int64_t>(m.vertices.size()));
  }
  return m;
}

std::int64_t scatter_moved(const MeshView& view, const DofMap& dofs, std::vector<std::int64_t> ids,
                           std::vector<double> coords, Vec x) {
  const MPI_Comm comm = dofs.comm();
  const int d = view.dim;
  std::int64_t count = static_cast<std::int64_t>(ids.size());
  MPI_Bcast(&count, 1, MPI_INT64_T, 0, comm);
  if (count == 0) return 0;
  ids.resize(count);
  coords.resize(d * count);
  MPI_Bcast(ids.data(), static_cast<int>(ids.size()), MPI_INT64_T, 0, comm);
  MPI_Bcast(coords.data(), static_cast<int>(coords.size()), MPI_DOUBLE, 0, comm);

  // Each rank writes its owned vertices among the moved ones.
  PetscInt first = 0;
  NM_PETSC(VecGetOwnershipRange(x, &first, nullptr));
  PetscScalar* values = nullptr;
  NM_PETSC(VecGetArray(x, &values));
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    if (!view.owned[v]) continue;
    const auto it = std::lower_bound(ids.begin(), ids.end(), view.input_vertex[v]);
    if (it == ids.end() || *it != view.input_vertex[v]) continue;
    const std::size_t k = static_cast<std::size_t>(it - ids.begin());
    for (int a = 0; a < d; ++a) values[dofs.global_dof()[d * v + a] - first] = coords[d * k + a];
  }
  NM_PETSC(VecRestoreArray(x, &values));
  return count;
}

std::vector<std::array<double, 3>> repair_directions(int dim) {
  std::vector<std::array<double, 3>> dirs;
  if (dim == 2) {
    for (int k = 0; k < 16; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 16;
      dirs.push_back({std::cos(a), std::sin(a), 0.0});
    }
    return dirs;
  }
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const double n = std::sqrt(double(i * i + j * j + k * k));
        dirs.push_back({i / n, j / n, k / n});
      }
  return dirs;
}

}  // namespace neomesh
