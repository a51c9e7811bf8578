#include "mesh/gmsh_reader.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/petsc.hpp"
#include "mesh/cell_order.hpp"
#include "mesh/plex_util.hpp"

namespace neomesh {

namespace {

using GroupKey = std::pair<int, int>;  // (dim, tag)

// The $PhysicalNames block, which PETSc reads but does not keep. It precedes $Nodes and is
// ASCII even in binary files.
std::map<GroupKey, std::string> read_physical_names(const std::filesystem::path& path) {
  std::map<GroupKey, std::string> names;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with("$Nodes") || line.starts_with("$Entities")) break;
    if (!line.starts_with("$PhysicalNames")) continue;
    int count = 0;
    in >> count;
    std::getline(in, line);
    for (int i = 0; i < count && std::getline(in, line); ++i) {
      std::istringstream fields(line);
      int dim = 0, tag = 0;
      fields >> dim >> tag;
      const auto open = line.find('"'), close = line.rfind('"');
      if (open != std::string::npos && close > open)
        names[{dim, tag}] = line.substr(open + 1, close - open - 1);
    }
    break;
  }
  return names;
}

// PETSc's message for a failed read, as one line without PETSc's decorations.
std::string petsc_reason(PetscErrorCode code) {
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  std::string reason = specific && *specific ? specific : (text ? text : "unknown error");
  std::replace(reason.begin(), reason.end(), '\n', ' ');
  return reason;
}

OwnedDM read_plex(const std::filesystem::path& path) {
  OwnedDM dm;
  // Return errors instead of printing PETSc's multi-line banner.
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode code =
      DMPlexCreateGmshFromFile(PETSC_COMM_SELF, path.c_str(), PETSC_TRUE, dm.out());
  const std::string reason = code != 0 ? petsc_reason(code) : "";
  // A reader that failed half-way may leave its DM inconsistent; destroying it may fail too.
  if (code != 0) dm.reset();
  PetscPopErrorHandler();
  if (code == 0) return dm;
  if (reason.find("Could not determine Plex facet") != std::string::npos)
    fail(
        "{}: has lower-dimensional elements that are not faces of its cells (2D and 3D cells "
        "mixed?); neomesh needs cells of one dimension",
        path.string());
  fail("{}: not a valid Gmsh mesh file ({})", path.string(), reason);
}

// Adds every point of `label_name` in [pStart, pEnd) to `out`, with its label value as tag.
void read_tagged(DM dm, const char* label_name, TaggedEntities& out, std::set<int>& tags) {
  DMLabel label = nullptr;
  NM_PETSC(DMGetLabel(dm, label_name, &label));
  if (!label) return;
  PetscInt vStart, vEnd;
  NM_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  OwnedIS values;
  NM_PETSC(DMLabelGetValueIS(label, values.out()));
  PetscInt nvalues = 0;
  const PetscInt* value = nullptr;
  NM_PETSC(ISGetLocalSize(values, &nvalues));
  NM_PETSC(ISGetIndices(values, &value));
  for (PetscInt i = 0; i < nvalues; ++i) {
    OwnedIS points;
    NM_PETSC(DMLabelGetStratumIS(label, value[i], points.out()));
    PetscInt npoints = 0;
    const PetscInt* point = nullptr;
    NM_PETSC(ISGetLocalSize(points, &npoints));
    NM_PETSC(ISGetIndices(points, &point));
    for (PetscInt k = 0; k < npoints; ++k) {
      const auto v = closure_vertices(dm, point[k], vStart, vEnd);
      out.add(v.data(), static_cast<PetscInt>(v.size()), static_cast<int>(value[i]));
    }
    NM_PETSC(ISRestoreIndices(points, &point));
    tags.insert(static_cast<int>(value[i]));
  }
  NM_PETSC(ISRestoreIndices(values, &value));
}

void read_coordinates(DM dm, const std::string& file, InputMesh& mesh) {
  PetscInt vStart, vEnd, cdim;
  NM_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  NM_PETSC(DMGetCoordinateDim(dm, &cdim));
  Vec local = nullptr;
  NM_PETSC(DMGetCoordinatesLocal(dm, &local));
  PetscInt size = 0;
  NM_PETSC(VecGetLocalSize(local, &size));
  // PETSc stores extra coordinates per cell (a higher-order field) for curved elements.
  if (size != (vEnd - vStart) * cdim || cdim != mesh.dim)
    fail(
        "{}: has second-order (curved) elements; neomesh needs first-order elements "
        "(Gmsh: Mesh.ElementOrder = 1)",
        file);
  VecReadView x(local);
  mesh.coords.assign(x.data(), x.data() + size);
}

void read_cells(DM dm, const std::string& file, InputMesh& mesh, std::set<int>& cell_tags) {
  PetscInt cStart, cEnd, vStart, vEnd;
  NM_PETSC(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  NM_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  DMLabel sets = nullptr;
  NM_PETSC(DMGetLabel(dm, "Cell Sets", &sets));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    DMPolytopeType polytope;
    NM_PETSC(DMPlexGetCellType(dm, c, &polytope));
    CellType type;
    if (!cell_type_of(polytope, type))
      fail(
          "{}: cell {} (0-based) is a {}; neomesh supports triangles, quadrilaterals, "
          "tetrahedra and hexahedra",
          file, c - cStart, DMPolytopeTypes[polytope]);
    const auto plex = closure_vertices(dm, c, vStart, vEnd);
    if (static_cast<int>(plex.size()) != num_vertices(type))
      fail("{}: cell {} (0-based) has a repeated vertex", file, c - cStart);
    PetscInt canonical[8];
    for (int i = 0; i < num_vertices(type); ++i) canonical[i] = plex[canonical_from_plex(type)[i]];
    PetscInt tag = -1;
    if (sets) NM_PETSC(DMLabelGetValue(sets, c, &tag));
    if (tag > 0) cell_tags.insert(static_cast<int>(tag));
    mesh.add_cell(type, canonical, tag > 0 ? static_cast<int>(tag) : 0);
  }
}

}  // namespace

InputMesh read_gmsh(const std::filesystem::path& path) {
  const std::string file = path.string();
  OwnedDM dm = read_plex(path);
  InputMesh mesh;
  PetscInt dim;
  NM_PETSC(DMGetDimension(dm, &dim));
  if (dim < 2)
    fail(
        "{}: has no 2D or 3D cells (only {}D elements); neomesh needs triangles, "
        "quadrilaterals, tetrahedra or hexahedra",
        file, dim);
  mesh.dim = static_cast<int>(dim);
  read_coordinates(dm, file, mesh);

  std::set<int> cell_tags, facet_tags, point_tags;
  read_cells(dm, file, mesh, cell_tags);
  read_tagged(dm, "Face Sets", mesh.facets, facet_tags);
  read_tagged(dm, "Vertex Sets", mesh.points, point_tags);

  const auto names = read_physical_names(path);
  auto add_groups = [&](int gdim, const std::set<int>& tags) {
    for (int tag : tags) {
      auto it = names.find({gdim, tag});
      mesh.groups.push_back({gdim, tag, it == names.end() ? "" : it->second});
    }
  };
  add_groups(0, point_tags);
  add_groups(mesh.dim - 1, facet_tags);
  add_groups(mesh.dim, cell_tags);
  return mesh;
}

}  // namespace neomesh
