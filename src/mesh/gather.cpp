#include "mesh/gather.hpp"

#include <algorithm>
#include <numeric>

#include "mesh/cell_order.hpp"
#include "mesh/collective_error.hpp"
#include "mesh/mesh_impl.hpp"
#include "mesh/plex_util.hpp"

namespace neomesh {

namespace {

// Concatenation of every rank's `local` on rank 0, with each rank's length.
template <typename T>
std::vector<T> gatherv(MPI_Comm comm, const std::vector<T>& local, MPI_Datatype type) {
  const int size = mpi_size(comm), rank = mpi_rank(comm);
  int count = static_cast<int>(local.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<T> all(rank == 0 ? offsets[size] : 0);
  MPI_Gatherv(local.data(), count, type, all.data(), counts.data(), offsets.data(), type, 0, comm);
  return all;
}

// One rank's share, as a stream of integers and one of doubles, read back in the same order:
//   count, per owned vertex:  input number | coordinates, vertex field values
//   count, per cell:          input number, type, tag, vertices (input numbers) | cell fields
//   count, per owned tagged facet or point: kind (0 point, 1 facet), tag, n, n vertices
struct Packet {
  std::vector<PetscInt> ints;
  std::vector<double> reals;
};

void check_sizes(const Mesh& mesh, const MeshFields& fields) {
  const MeshView& view = mesh.view();
  for (const Field& f : fields.cell)
    if (f.values.size() != static_cast<std::size_t>(view.num_cells * f.components))
      fail("cell field '{}' has {} values for {} cells", f.name, f.values.size(), view.num_cells);
  for (const Field& f : fields.vertex)
    if (f.values.size() != static_cast<std::size_t>(view.num_vertices * f.components))
      fail("vertex field '{}' has {} values for {} vertices", f.name, f.values.size(),
           view.num_vertices);
}

// Tagged facets and points this rank owns (another rank's ghosts are written by their owner).
void pack_tagged(const MeshAccess::Impl& m, Packet& out) {
  const std::size_t count_at = out.ints.size() - 1;
  PetscInt pStart, pEnd, vStart, vEnd;
  NM_PETSC(DMPlexGetChart(m.dm, &pStart, &pEnd));
  NM_PETSC(DMPlexGetDepthStratum(m.dm, 0, &vStart, &vEnd));
  const auto ghost = ghost_points(m.dm);
  for (const PhysicalGroup& g : m.groups) {
    if (g.dim == m.dim) continue;
    for (PetscInt p : stratum(m.dm, g.dim == 0 ? "Vertex Sets" : "Face Sets", g.tag)) {
      if (ghost[p - pStart]) continue;
      auto vertices = closure_vertices(m.dm, p, vStart, vEnd);
      for (PetscInt& v : vertices) v = m.input_vertex[v];
      ++out.ints[count_at];
      out.ints.insert(out.ints.end(),
                      {g.dim == 0 ? 0 : 1, g.tag, static_cast<PetscInt>(vertices.size())});
      out.ints.insert(out.ints.end(), vertices.begin(), vertices.end());
    }
  }
}

Packet pack(const Mesh& mesh, const MeshFields& fields) {
  const auto& m = MeshAccess::impl(mesh);
  const MeshView& view = mesh.view();
  Packet out;
  out.ints.push_back(std::count(view.owned.begin(), view.owned.end(), 1));
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    if (!view.owned[v]) continue;
    out.ints.push_back(m.input_vertex[v]);
    out.reals.insert(out.reals.end(), view.coords.begin() + v * m.dim,
                     view.coords.begin() + (v + 1) * m.dim);
    for (const Field& f : fields.vertex)
      out.reals.insert(out.reals.end(), f.values.begin() + v * f.components,
                       f.values.begin() + (v + 1) * f.components);
  }

  DMLabel cell_sets;
  NM_PETSC(DMGetLabel(m.dm, "Cell Sets", &cell_sets));
  out.ints.push_back(view.num_cells);
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      const PetscInt cell = block.first_cell + c;
      PetscInt tag = -1;
      NM_PETSC(DMLabelGetValue(cell_sets, m.view_cell_point[cell], &tag));
      out.ints.insert(out.ints.end(), {view.global_cell[cell], static_cast<PetscInt>(block.type),
                                       std::max<PetscInt>(tag, 0)});
      for (int i = 0; i < num_vertices(block.type); ++i)
        out.ints.push_back(m.input_vertex[block.cell(c)[i]]);
      for (const Field& f : fields.cell)
        out.reals.insert(out.reals.end(), f.values.begin() + cell * f.components,
                         f.values.begin() + (cell + 1) * f.components);
    }
  out.ints.push_back(0);  // the number of tagged facets and points, counted by pack_tagged
  pack_tagged(m, out);
  return out;
}

// Orders entities by (tag, vertices), so the order does not depend on the partition.
void sort_entities(TaggedEntities& entities) {
  auto key = [&](PetscInt k) {
    return std::pair(entities.tags[k],
                     std::vector<PetscInt>(entities.vertices.begin() + entities.offsets[k],
                                           entities.vertices.begin() + entities.offsets[k + 1]));
  };
  std::vector<PetscInt> order(entities.size());
  std::iota(order.begin(), order.end(), PetscInt{0});
  std::sort(order.begin(), order.end(), [&](PetscInt a, PetscInt b) { return key(a) < key(b); });
  TaggedEntities sorted;
  for (PetscInt k : order) {
    const auto [tag, vertices] = key(k);
    sorted.add(vertices.data(), static_cast<PetscInt>(vertices.size()), tag);
  }
  entities = std::move(sorted);
}

}  // namespace

GatheredMesh gather_mesh(const Mesh& mesh, const MeshFields& fields) {
  std::string error;
  try {
    check_sizes(mesh, fields);
  } catch (const Error& e) {
    error = e.what();
  }
  throw_if_any(mesh.comm(), error);

  const auto& m = MeshAccess::impl(mesh);
  const Packet local = pack(mesh, fields);
  const auto ints = gatherv(mesh.comm(), local.ints, MPIU_INT);
  const auto reals = gatherv(mesh.comm(), local.reals, MPI_DOUBLE);

  GatheredMesh out{{}, fields, false};
  for (auto& f : out.fields.cell) f.values.clear();
  for (auto& f : out.fields.vertex) f.values.clear();
  out.mesh.dim = m.dim;
  out.mesh.groups = m.groups;
  out.has_cell_groups =
      std::any_of(m.groups.begin(), m.groups.end(), [&](const auto& g) { return g.dim == m.dim; });
  if (mpi_rank(mesh.comm()) != 0) return out;

  const PetscInt nc = m.global_num_cells, nv = m.global_num_vertices;
  out.mesh.coords.resize(nv * m.dim);
  for (auto& f : out.fields.vertex) f.values.resize(nv * f.components);
  for (auto& f : out.fields.cell) f.values.resize(nc * f.components);
  std::vector<CellType> types(nc);
  std::vector<int> tags(nc);
  std::vector<std::vector<PetscInt>> cells(nc);

  std::size_t i = 0, r = 0;
  auto take = [&](std::vector<double>& to, PetscInt at, int n) {
    std::copy_n(reals.begin() + r, n, to.begin() + at * n);
    r += n;
  };
  for (int rank = 0; rank < mpi_size(mesh.comm()); ++rank) {
    for (PetscInt k = 0, n = ints[i++]; k < n; ++k) {
      const PetscInt v = ints[i++];
      take(out.mesh.coords, v, m.dim);
      for (auto& f : out.fields.vertex) take(f.values, v, f.components);
    }
    for (PetscInt k = 0, n = ints[i++]; k < n; ++k) {
      const PetscInt c = ints[i];
      types[c] = static_cast<CellType>(ints[i + 1]);
      tags[c] = static_cast<int>(ints[i + 2]);
      cells[c].assign(ints.begin() + i + 3, ints.begin() + i + 3 + num_vertices(types[c]));
      i += 3 + num_vertices(types[c]);
      for (auto& f : out.fields.cell) take(f.values, c, f.components);
    }
    for (PetscInt k = 0, count = ints[i++]; k < count; ++k) {
      const PetscInt kind = ints[i], tag = ints[i + 1], n = ints[i + 2];
      (kind == 0 ? out.mesh.points : out.mesh.facets)
          .add(ints.data() + i + 3, n, static_cast<int>(tag));
      i += 3 + n;
    }
  }
  for (PetscInt c = 0; c < nc; ++c) out.mesh.add_cell(types[c], cells[c].data(), tags[c]);
  sort_entities(out.mesh.facets);
  sort_entities(out.mesh.points);
  return out;
}

}  // namespace neomesh
