#include "mesh/facet_table.hpp"

#include <algorithm>

#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// The cell's vertices in DMPlex cone order.
void plex_cone(const InputMesh& mesh, PetscInt c, PetscInt cone[8]) {
  const CellType type = mesh.cell_types[c];
  const PetscInt* canonical = mesh.cell_vertices.data() + mesh.cell_offsets[c];
  for (int i = 0; i < num_vertices(type); ++i) cone[i] = canonical[plex_from_canonical(type)[i]];
}

}  // namespace

FacetTable::Key FacetTable::key(const PetscInt* vertices, int n) {
  Key k{-1, -1, -1, -1};
  for (int i = 0; i < n; ++i) {  // insertion sort: n ≤ 4
    int j = i;
    for (; j > 0 && k[j - 1] > vertices[i]; --j) k[j] = k[j - 1];
    k[j] = vertices[i];
  }
  return k;
}

PetscInt FacetTable::lookup(const Key& k) const {
  if (k[0] < 0 || k[0] >= static_cast<PetscInt>(head_.size())) return -1;
  for (PetscInt f = head_[k[0]]; f >= 0; f = next_[f])
    if (keys_[f] == k) return f;
  return -1;
}

FacetTable::FacetTable(const InputMesh& mesh) : mesh_(mesh) {
  head_.assign(mesh.num_vertices(), -1);
  std::size_t estimate = 0;  // every interior facet is seen twice
  for (CellType t : mesh.cell_types) estimate += plex_facets(t).count;
  keys_.reserve(estimate / 2 + 1);
  cells_.reserve(estimate / 2 + 1);
  local_.reserve(estimate / 2 + 1);
  next_.reserve(estimate / 2 + 1);
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    PetscInt cone[8], facet[4];
    plex_cone(mesh, c, cone);
    const FacetShape& shape = plex_facets(mesh.cell_types[c]);
    for (int i = 0; i < shape.count; ++i) {
      for (int j = 0; j < shape.size; ++j) facet[j] = cone[shape.vertices[i][j]];
      const Key k = key(facet, shape.size);
      const PetscInt f = lookup(k);
      if (f >= 0) {
        if (cells_[f][1] < 0) cells_[f][1] = c;
        continue;
      }
      keys_.push_back(k);
      cells_.push_back({c, -1});
      local_.push_back(static_cast<std::uint8_t>(i));
      next_.push_back(head_[k[0]]);
      head_[k[0]] = size() - 1;
    }
  }
}

int FacetTable::vertices(PetscInt f, PetscInt out[4]) const {
  const PetscInt c = cells_[f][0];
  PetscInt cone[8];
  plex_cone(mesh_, c, cone);
  const FacetShape& shape = plex_facets(mesh_.cell_types[c]);
  for (int j = 0; j < shape.size; ++j) out[j] = cone[shape.vertices[local_[f]][j]];
  return shape.size;
}

PetscInt FacetTable::find(const PetscInt* vertices, int n) const {
  return n >= 1 && n <= 4 ? lookup(key(vertices, n)) : -1;
}

CellGraph FacetTable::cell_graph() const {
  const PetscInt nc = mesh_.num_cells();
  CellGraph g;
  g.offsets.assign(nc + 1, 0);
  for (const auto& [a, b] : cells_)
    if (b >= 0) ++g.offsets[a + 1], ++g.offsets[b + 1];
  for (PetscInt c = 0; c < nc; ++c) g.offsets[c + 1] += g.offsets[c];
  g.neighbours.resize(g.offsets[nc]);
  std::vector<PetscInt> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (const auto& [a, b] : cells_)
    if (b >= 0) g.neighbours[fill[a]++] = b, g.neighbours[fill[b]++] = a;
  for (PetscInt c = 0; c < nc; ++c)
    std::sort(g.neighbours.begin() + g.offsets[c], g.neighbours.begin() + g.offsets[c + 1]);
  return g;
}

}  // namespace neomesh
