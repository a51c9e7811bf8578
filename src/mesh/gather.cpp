#include "mesh/gather.hpp"

#include <algorithm>
#include <numeric>

#include "core/collective_error.hpp"
#include "mesh/cell_order.hpp"
#include "mesh/mesh_impl.hpp"

namespace neomesh {

namespace {

// One rank's share, as a stream of integers and one of doubles, read back in the same order:
//   count, per owned vertex:  input number | coordinates, vertex field values
//   count, per cell:          input number, type, vertices (input numbers) | cell fields
struct Packet {
  std::vector<PetscInt> ints;
  std::vector<double> reals;
};

void check_sizes(const PlexMesh& mesh, const MeshFields& fields) {
  const MeshView& view = mesh.view();
  for (const Field& f : fields.cell)
    if (f.values.size() != static_cast<std::size_t>(view.num_cells * f.components))
      fail("cell field '{}' has {} values for {} cells", f.name, f.values.size(), view.num_cells);
  for (const Field& f : fields.vertex)
    if (f.values.size() != static_cast<std::size_t>(view.num_vertices * f.components))
      fail("vertex field '{}' has {} values for {} vertices", f.name, f.values.size(),
           view.num_vertices);
}

Packet pack(const PlexMesh& mesh, const MeshFields& fields) {
  const auto& m = MeshAccess::impl(mesh);
  const MeshView& view = mesh.view();
  Packet out;
  std::size_t num_ints = 2 + view.num_vertices, num_reals = view.num_vertices * view.dim;
  for (const CellBlock& block : view.blocks) num_ints += 2 * block.size() + block.vertices.size();
  for (const Field& f : fields.vertex) num_reals += f.values.size();
  for (const Field& f : fields.cell) num_reals += f.values.size();
  out.ints.reserve(num_ints);
  out.reals.reserve(num_reals);
  out.ints.push_back(std::count(view.owned.begin(), view.owned.end(), 1));
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    if (!view.owned[v]) continue;
    out.ints.push_back(m.view->input_vertex[v]);
    out.reals.insert(out.reals.end(), view.coords.begin() + v * view.dim,
                     view.coords.begin() + (v + 1) * view.dim);
    for (const Field& f : fields.vertex)
      out.reals.insert(out.reals.end(), f.values.begin() + v * f.components,
                       f.values.begin() + (v + 1) * f.components);
  }

  out.ints.push_back(view.num_cells);
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      const PetscInt cell = block.first_cell + c;
      out.ints.insert(out.ints.end(), {view.global_cell[cell], static_cast<PetscInt>(block.type)});
      for (int i = 0; i < block.nodes(); ++i)
        out.ints.push_back(m.view->input_vertex[block.cell(c)[i]]);
      for (const Field& f : fields.cell)
        out.reals.insert(out.reals.end(), f.values.begin() + cell * f.components,
                         f.values.begin() + (cell + 1) * f.components);
    }
  return out;
}

// The facet group on rank 0 as facets of `mesh` in a physical group of its own: the input's
// group of the same name and dimension if there is one (its facets are replaced), else a new
// tag.
void add_facet_group(const PlexMesh& mesh, const FacetGroup& group, InputMesh& out) {
  const auto& m = MeshAccess::impl(mesh);
  std::vector<PetscInt> sizes;
  for (std::size_t f = 0; f + 1 < group.offsets.size(); ++f)
    sizes.push_back(static_cast<PetscInt>(group.offsets[f + 1] - group.offsets[f]));
  const std::vector<PetscInt> vertices(group.vertices.begin(), group.vertices.end());
  const auto all_sizes = gatherv(mesh.comm(), sizes, MPIU_INT);
  const auto all_vertices = gatherv(mesh.comm(), vertices, MPIU_INT);
  if (mpi_rank(mesh.comm()) != 0) return;
  const int dim = m.dim - 1;
  int tag = 0, largest = 0;
  for (const PhysicalGroup& g : out.groups)
    if (g.dim == dim) {
      largest = std::max(largest, g.tag);
      if (g.name == group.name) tag = g.tag;
    }
  TaggedEntities kept;
  for (PetscInt k = 0; k < out.facets.size(); ++k)
    if (out.facets.tags[k] != tag || tag == 0)
      kept.add(out.facets.vertices.data() + out.facets.offsets[k],
               out.facets.offsets[k + 1] - out.facets.offsets[k], out.facets.tags[k]);
  if (tag == 0) {
    tag = largest + 1;
    out.groups.push_back({dim, tag, group.name});
    std::sort(out.groups.begin(), out.groups.end(), [](const auto& a, const auto& b) {
      return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
    });
  }
  std::size_t at = 0;
  for (PetscInt size : all_sizes) {
    kept.add(all_vertices.data() + at, size, tag);
    at += size;
  }
  out.facets = std::move(kept);
}

void make_room_for_data(const std::vector<Field>& fields, std::vector<DataArray>& data,
                        std::vector<std::string>& names) {
  const auto named = [&](const std::string& name) {
    return std::find_if(data.begin(), data.end(),
                        [&](const DataArray& a) { return a.name == name; });
  };
  for (const Field& f : fields) {
    std::string name = f.name;
    if (named(name) != data.end()) name = "neomesh_" + name;
    if (const auto it = named(name); it != data.end()) data.erase(it);
    names.push_back(std::move(name));
  }
}

}  // namespace

void make_room_for_data(GatheredMesh& gathered) {
  for (auto [fields, data] : {std::pair(&gathered.fields.vertex, &gathered.mesh.point_data),
                              std::pair(&gathered.fields.cell, &gathered.mesh.cell_data)}) {
    std::vector<std::string> names;
    make_room_for_data(*fields, *data, names);
    for (std::size_t k = 0; k < names.size(); ++k) (*fields)[k].name = std::move(names[k]);
  }
}

GatheredMesh gather_mesh(const PlexMesh& mesh, const MeshFields& fields) {
  std::string error;
  try {
    check_sizes(mesh, fields);
  } catch (const Error& e) {
    error = e.what();
  }
  throw_if_any(mesh.comm(), error);

  const auto& m = MeshAccess::impl(mesh);
  Packet local = pack(mesh, fields);
  const auto ints = gatherv(mesh.comm(), std::move(local.ints), MPIU_INT);
  const auto reals = gatherv(mesh.comm(), std::move(local.reals), MPI_DOUBLE);

  // The fields' names and shapes; their values come from the gathered packets.
  GatheredMesh out{{}, {}, false};
  for (const Field& f : fields.cell) out.fields.cell.push_back({f.name, {}, f.components});
  for (const Field& f : fields.vertex) out.fields.vertex.push_back({f.name, {}, f.components});
  out.fields.facet_groups = fields.facet_groups;
  out.mesh.dim = m.dim;
  out.mesh.surface = m.surface;
  out.mesh.groups = m.groups;
  out.has_cell_groups =
      std::any_of(m.groups.begin(), m.groups.end(), [&](const auto& g) { return g.dim == m.dim; });
  out.mesh.facets = m.facets;
  for (const FacetGroup& group : fields.facet_groups) add_facet_group(mesh, group, out.mesh);
  if (mpi_rank(mesh.comm()) != 0) return out;

  const PetscInt nc = m.global_num_cells, nv = m.global_num_vertices;
  out.mesh.coords.resize(nv * m.coord_dim());
  for (auto& f : out.fields.vertex) f.values.resize(nv * f.components);
  for (auto& f : out.fields.cell) f.values.resize(nc * f.components);
  std::vector<std::size_t> cell_at(nc);  // where each cell's type and vertices are in `ints`

  std::size_t i = 0, r = 0;
  auto take = [&](std::vector<double>& to, PetscInt at, int n) {
    std::copy_n(reals.begin() + r, n, to.begin() + at * n);
    r += n;
  };
  for (int rank = 0; rank < mpi_size(mesh.comm()); ++rank) {
    for (PetscInt k = 0, n = ints[i++]; k < n; ++k) {
      const PetscInt v = ints[i++];
      take(out.mesh.coords, v, m.coord_dim());
      for (auto& f : out.fields.vertex) take(f.values, v, f.components);
    }
    for (PetscInt k = 0, n = ints[i++]; k < n; ++k) {
      const PetscInt c = ints[i];
      cell_at[c] = i + 1;
      i += 2 + num_vertices(static_cast<CellType>(ints[i + 1]));
      for (auto& f : out.fields.cell) take(f.values, c, f.components);
    }
  }
  out.mesh.cell_types.reserve(nc);
  out.mesh.cell_offsets.reserve(nc + 1);
  out.mesh.cell_tags.reserve(nc);
  for (PetscInt c = 0; c < nc; ++c)
    out.mesh.add_cell(static_cast<CellType>(ints[cell_at[c]]), ints.data() + cell_at[c] + 1,
                      m.cell_tags[c]);
  out.mesh.points = m.points;
  out.mesh.plane = m.plane;
  out.mesh.point_data = m.point_data;
  out.mesh.cell_data = m.cell_data;
  out.mesh.steps = m.steps;
  out.mesh.high_order = m.high_order;
  return out;
}

}  // namespace neomesh
