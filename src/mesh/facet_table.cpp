#include "mesh/facet_table.hpp"

#include <algorithm>

namespace neomesh {

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
  for (CellType t : mesh.cell_types) estimate += facts(t).num_facets;
  keys_.reserve(estimate / 2 + 1);
  cells_.reserve(estimate / 2 + 1);
  local_.reserve(estimate / 2 + 1);
  next_.reserve(estimate / 2 + 1);
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    const CellFacts& cell_facts = facts(mesh.cell_types[c]);
    for (int i = 0; i < cell_facts.num_facets; ++i) {
      const FacetVertices& local = cell_facts.facets[i];
      PetscInt facet[4];
      for (int j = 0; j < local.size; ++j) facet[j] = cell[local.vertices[j]];
      const Key k = key(facet, local.size);
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
  const PetscInt* cell = mesh_.cell_vertices.data() + mesh_.cell_offsets[c];
  const FacetVertices& local = facts(mesh_.cell_types[c]).facets[local_[f]];
  for (int j = 0; j < local.size; ++j) out[j] = cell[local.vertices[j]];
  return local.size;
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
