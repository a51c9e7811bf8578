#include "mesh/input_topology.hpp"

#include <algorithm>
#include <numeric>
#include <span>

#include "core/error.hpp"

namespace neomesh {

namespace {

std::span<const PetscInt> entity(const TaggedEntities& e, PetscInt k) {
  return {e.vertices.data() + e.offsets[k],
          static_cast<std::size_t>(e.offsets[k + 1] - e.offsets[k])};
}

// Orders entities by (tag, vertices), without repeats, so the writers' order depends on nothing
// but the groups.
void sort_entities(TaggedEntities& entities) {
  auto less = [&](PetscInt a, PetscInt b) {
    if (entities.tags[a] != entities.tags[b]) return entities.tags[a] < entities.tags[b];
    const auto x = entity(entities, a), y = entity(entities, b);
    return std::lexicographical_compare(x.begin(), x.end(), y.begin(), y.end());
  };
  std::vector<PetscInt> order(entities.size());
  std::iota(order.begin(), order.end(), PetscInt{0});
  std::sort(order.begin(), order.end(), less);
  TaggedEntities sorted;
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i > 0 && !less(order[i - 1], order[i])) continue;
    const auto v = entity(entities, order[i]);
    sorted.add(v.data(), static_cast<PetscInt>(v.size()), entities.tags[order[i]]);
  }
  entities = std::move(sorted);
}

// The input's facets, found in the table (for their vertex order).
void add_tagged_facets(const InputMesh& mesh, const FacetTable& table, const std::string& source,
                       TaggedEntities& out) {
  const TaggedEntities& in = mesh.facets;
  for (PetscInt k = 0; k < in.size(); ++k) {
    const auto v = entity(in, k);
    const PetscInt f = table.find(v.data(), static_cast<int>(v.size()));
    if (f < 0)
      fail(
          "{}: has lower-dimensional elements that are not faces of its cells (2D and 3D cells "
          "mixed?); neomesh needs cells of one dimension",
          source);
    PetscInt vertices[4];
    out.add(vertices, table.vertices(f, vertices), in.tags[k]);
  }
}

void add_vertex_sets(InputMesh& mesh, const FacetTable& table,
                     const std::vector<PetscInt>& boundary, InputTopology& t) {
  std::vector<std::uint8_t> in_set(mesh.num_vertices()), covered(mesh.num_vertices());
  for (const VertexSet& set : mesh.vertex_sets) {
    std::fill(in_set.begin(), in_set.end(), 0);
    std::fill(covered.begin(), covered.end(), 0);
    for (auto v : set.vertices) in_set[v] = 1;
    for (PetscInt f : boundary) {
      PetscInt v[4];
      const int n = table.vertices(f, v);
      if (!std::all_of(v, v + n, [&](PetscInt p) { return in_set[p]; })) continue;
      t.facets.add(v, n, set.tag);
      for (int i = 0; i < n; ++i) covered[v[i]] = 1;
    }
    bool isolated = false;
    for (auto v : set.vertices)
      if (!covered[v]) {
        const PetscInt p = static_cast<PetscInt>(v);
        t.points.add(&p, 1, set.tag);
        isolated = true;
      }
    if (isolated) mesh.groups.push_back({0, set.tag, set.name});
  }
  std::sort(mesh.groups.begin(), mesh.groups.end(), [](const auto& a, const auto& b) {
    return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
  });
}

// Boundary parts are the facet and point groups, in the order of mesh.groups (MeshView::parts);
// a surface's are its cell groups and point groups (its cells are its boundary facets).
void mark_parts(const InputMesh& mesh, InputTopology& t) {
  const PetscInt nv = mesh.num_vertices();
  t.boundary_part.assign(nv, -1);
  t.part_count.assign(nv, 0);
  std::vector<int> seen(nv, -1);  // the last part that counted the vertex
  int part = 0;
  const auto count = [&](std::span<const PetscInt> vertices) {
    for (PetscInt v : vertices) {
      if (seen[v] == part) continue;
      seen[v] = part;
      if (t.boundary_part[v] < 0) t.boundary_part[v] = part;
      ++t.part_count[v];
    }
  };
  const int part_dim = mesh.surface ? mesh.dim : mesh.dim - 1;
  for (const PhysicalGroup& g : mesh.groups) {
    if (g.dim != part_dim && g.dim != 0) continue;
    if (g.dim == mesh.dim) {
      for (PetscInt c = 0; c < mesh.num_cells(); ++c)
        if (mesh.cell_tags[c] == g.tag)
          count({mesh.cell_vertices.data() + mesh.cell_offsets[c],
                 static_cast<std::size_t>(mesh.cell_offsets[c + 1] - mesh.cell_offsets[c])});
    } else {
      const TaggedEntities& e = g.dim == 0 ? t.points : t.facets;
      const auto [first, last] = std::equal_range(e.tags.begin(), e.tags.end(), g.tag);
      for (PetscInt k = first - e.tags.begin(); k < last - e.tags.begin(); ++k) count(entity(e, k));
    }
    ++part;
  }
}

}  // namespace

InputTopology input_topology(InputMesh& mesh, const FacetTable& table, const std::string& source) {
  InputTopology t;
  add_tagged_facets(mesh, table, source, t.facets);
  std::vector<PetscInt> boundary;
  t.on_boundary.assign(mesh.num_vertices(), 0);
  for (PetscInt f = 0; f < table.size(); ++f) {
    if (!table.on_boundary(f)) continue;
    boundary.push_back(f);
    PetscInt v[4];
    for (int i = 0, n = table.vertices(f, v); i < n; ++i) t.on_boundary[v[i]] = 1;
  }
  // Every vertex of a surface slides on it (its cells are the facets it slides on).
  if (mesh.surface) std::fill(t.on_boundary.begin(), t.on_boundary.end(), 1);
  add_vertex_sets(mesh, table, boundary, t);
  sort_entities(t.facets);
  sort_entities(t.points);
  mark_parts(mesh, t);
  return t;
}

}  // namespace neomesh
