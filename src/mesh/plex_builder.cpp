#include "mesh/plex_builder.hpp"

#include <algorithm>

#include "mesh/cell_order.hpp"
#include "mesh/collective_error.hpp"

namespace neomesh {

namespace {

OwnedDM build_topology(MPI_Comm comm, int dim, const InputMesh& mesh) {
  const PetscInt nc = mesh.num_cells(), nv = mesh.num_vertices();
  OwnedDM dm;
  NM_PETSC(DMCreate(comm, dm.out()));
  NM_PETSC(DMSetType(dm, DMPLEX));
  NM_PETSC(DMSetDimension(dm, dim));
  // Cell types are set below, not computed by PETSc.
  NM_PETSC(DMCreateLabel(dm, "celltype"));
  NM_PETSC(DMPlexSetChart(dm, 0, nc + nv));
  for (PetscInt c = 0; c < nc; ++c) {
    NM_PETSC(DMPlexSetConeSize(dm, c, num_vertices(mesh.cell_types[c])));
    NM_PETSC(DMPlexSetCellType(dm, c, plex_polytope(mesh.cell_types[c])));
  }
  for (PetscInt v = nc; v < nc + nv; ++v) NM_PETSC(DMPlexSetCellType(dm, v, DM_POLYTOPE_POINT));
  NM_PETSC(DMSetUp(dm));
  PetscInt cone[8];
  for (PetscInt c = 0; c < nc; ++c) {
    const CellType type = mesh.cell_types[c];
    const PetscInt* canonical = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    for (int i = 0; i < num_vertices(type); ++i)
      cone[i] = nc + canonical[plex_from_canonical(type)[i]];
    NM_PETSC(DMPlexSetCone(dm, c, cone));
  }
  NM_PETSC(DMPlexSymmetrize(dm));
  NM_PETSC(DMPlexStratify(dm));
  OwnedDM interpolated;
  NM_PETSC(DMPlexInterpolate(dm, interpolated.out()));
  NM_PETSC(DMPlexBuildCoordinatesFromCellList(interpolated, dim, mesh.coords.data()));
  return interpolated;
}

DMLabel label(DM dm, const char* name) {
  DMLabel l = nullptr;
  NM_PETSC(DMGetLabel(dm, name, &l));
  return l;
}

// The facet whose vertices are `vertices` (0-based), found as their join.
PetscInt facet_of(DM dm, PetscInt vStart, const PetscInt* vertices, PetscInt n) {
  PetscInt points[8];
  for (PetscInt i = 0; i < n; ++i) points[i] = vStart + vertices[i];
  PetscInt size = 0;
  const PetscInt* join = nullptr;
  NM_PETSC(DMPlexGetFullJoin(dm, n, points, &size, &join));
  const PetscInt facet = size == 1 ? join[0] : -1;
  NM_PETSC(DMPlexRestoreJoin(dm, n, points, &size, &join));
  if (facet < 0)
    fail("boundary element with vertices {}... is not a face of any cell", vertices[0]);
  return facet;
}

// Vertex sets become the boundary facets all of whose vertices are in the set; set vertices
// on no such facet (an isolated corner) become tagged points.
void label_vertex_sets(DM dm, InputMesh& mesh) {
  PetscInt vStart, vEnd, fStart, fEnd;
  NM_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  NM_PETSC(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  DMLabel boundary = label(dm, kBoundaryLabel), faces = label(dm, "Face Sets"),
          points = label(dm, "Vertex Sets");
  std::vector<PetscInt> facets;  // boundary facets with their vertices, CSR
  std::vector<PetscInt> offsets = {0}, vertices;
  for (PetscInt f = fStart; f < fEnd; ++f) {
    PetscInt value = -1;
    NM_PETSC(DMLabelGetValue(boundary, f, &value));
    if (value != 1) continue;
    PetscInt n = 0, *closure = nullptr;
    NM_PETSC(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &n, &closure));
    for (PetscInt i = 0; i < n; ++i)
      if (closure[2 * i] >= vStart && closure[2 * i] < vEnd) vertices.push_back(closure[2 * i]);
    NM_PETSC(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &n, &closure));
    facets.push_back(f);
    offsets.push_back(static_cast<PetscInt>(vertices.size()));
  }
  std::vector<std::uint8_t> in_set(vEnd - vStart), covered(vEnd - vStart);
  for (const VertexSet& set : mesh.vertex_sets) {
    std::fill(in_set.begin(), in_set.end(), 0);
    std::fill(covered.begin(), covered.end(), 0);
    for (auto v : set.vertices) in_set.at(v) = 1;
    for (std::size_t k = 0; k < facets.size(); ++k) {
      const auto first = vertices.begin() + offsets[k], last = vertices.begin() + offsets[k + 1];
      if (!std::all_of(first, last, [&](PetscInt p) { return in_set[p - vStart]; })) continue;
      NM_PETSC(DMLabelSetValue(faces, facets[k], set.tag));
      std::for_each(first, last, [&](PetscInt p) { covered[p - vStart] = 1; });
    }
    bool isolated = false;
    for (auto v : set.vertices)
      if (!covered[v]) {
        NM_PETSC(DMLabelSetValue(points, vStart + v, set.tag));
        isolated = true;
      }
    if (isolated) mesh.groups.push_back({0, set.tag, set.name});
  }
  std::sort(mesh.groups.begin(), mesh.groups.end(), [](const auto& a, const auto& b) {
    return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
  });
}

void label_root(DM dm, InputMesh& mesh) {
  PetscInt vStart, vEnd;
  NM_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  DMLabel cells = label(dm, "Cell Sets"), faces = label(dm, "Face Sets"),
          points = label(dm, "Vertex Sets");
  for (PetscInt c = 0; c < mesh.num_cells(); ++c)
    if (mesh.cell_tags[c] > 0) NM_PETSC(DMLabelSetValue(cells, c, mesh.cell_tags[c]));
  const TaggedEntities& f = mesh.facets;
  for (PetscInt k = 0; k < f.size(); ++k)
    NM_PETSC(DMLabelSetValue(
        faces,
        facet_of(dm, vStart, f.vertices.data() + f.offsets[k], f.offsets[k + 1] - f.offsets[k]),
        f.tags[k]));
  for (PetscInt k = 0; k < mesh.points.size(); ++k)
    NM_PETSC(DMLabelSetValue(points, vStart + mesh.points.vertices[k], mesh.points.tags[k]));
  label_vertex_sets(dm, mesh);
}

}  // namespace

OwnedDM build_plex(MPI_Comm comm, InputMesh& mesh) {
  int dim = mesh.dim;
  MPI_Bcast(&dim, 1, MPI_INT, 0, comm);
  OwnedDM dm = build_topology(comm, dim, mesh);

  for (const char* name : {"Cell Sets", "Face Sets", "Vertex Sets", kBoundaryLabel})
    NM_PETSC(DMCreateLabel(dm, name));
  DMLabel boundary = label(dm, kBoundaryLabel);
  NM_PETSC(DMPlexMarkBoundaryFaces(dm, 1, boundary));
  NM_PETSC(DMPlexLabelComplete(dm, boundary));
  on_root(comm, [&] { label_root(dm, mesh); });
  return dm;
}

}  // namespace neomesh
