#include "mesh/dm_input.hpp"

#include <petscdmplex.h>

#include <vector>

#include "core/collective_error.hpp"
#include "mesh/cell_order.hpp"
#include "mesh/gather.hpp"

namespace neomesh {

namespace {

// One process' share: its owned cells (type, vertex numbers in canonical order) and its owned
// vertices (number, coordinates).
struct Share {
  std::vector<PetscInt> types, cell_vertices, vertex_numbers;
  std::vector<double> coords;
};

// A number of DMPlexGet{Vertex,Cell}Numbering: −(n + 1) for a point another process owns.
PetscInt owner_number(PetscInt n) {
  return n < 0 ? -(n + 1) : n;
}

Share local_share(DM dm, int dim, const std::string& name) {
  PetscInt cStart, cEnd, vStart, vEnd;
  NM_PETSC(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  NM_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  IS cell_numbering = nullptr, vertex_numbering = nullptr;
  NM_PETSC(DMPlexGetCellNumbering(dm, &cell_numbering));
  NM_PETSC(DMPlexGetVertexNumbering(dm, &vertex_numbering));
  const PetscInt *cell_number = nullptr, *vertex_number = nullptr;
  NM_PETSC(ISGetIndices(cell_numbering, &cell_number));
  NM_PETSC(ISGetIndices(vertex_numbering, &vertex_number));

  Share share;
  std::string error;
  for (PetscInt c = cStart; c < cEnd && error.empty(); ++c) {
    if (cell_number[c - cStart] < 0) continue;  // another process' cell (overlap)
    PetscInt n = 0, *closure = nullptr;
    NM_PETSC(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &n, &closure));
    std::vector<PetscInt> vertices;  // in DMPlex's order
    for (PetscInt k = 0; k < n; ++k)
      if (closure[2 * k] >= vStart && closure[2 * k] < vEnd) vertices.push_back(closure[2 * k]);
    NM_PETSC(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &n, &closure));
    DMPolytopeType polytope;
    NM_PETSC(DMPlexGetCellType(dm, c, &polytope));
    const int t = cell_type_index(dim, static_cast<int>(vertices.size()));
    if (t < 0 || plex_polytope(static_cast<CellType>(t)) != polytope) {
      error =
          fmt::format("{}: cell {} is a {} ({} vertices), which neomesh does not optimize", name,
                      cell_number[c - cStart], DMPolytopeTypes[polytope], vertices.size());
      break;
    }
    const auto type = static_cast<CellType>(t);
    share.types.push_back(t);
    for (int i = 0; i < num_vertices(type); ++i)
      share.cell_vertices.push_back(
          owner_number(vertex_number[vertices[canonical_from_plex(type)[i]] - vStart]));
  }

  Vec coordinates = nullptr;
  PetscSection section = nullptr;
  NM_PETSC(DMGetCoordinatesLocal(dm, &coordinates));
  NM_PETSC(DMGetCoordinateSection(dm, &section));
  const PetscScalar* x = nullptr;
  NM_PETSC(VecGetArrayRead(coordinates, &x));
  for (PetscInt v = vStart; v < vEnd && error.empty(); ++v) {
    if (vertex_number[v - vStart] < 0) continue;
    PetscInt dof = 0, offset = 0;
    NM_PETSC(PetscSectionGetDof(section, v, &dof));
    NM_PETSC(PetscSectionGetOffset(section, v, &offset));
    if (dof != dim) {
      error = fmt::format(
          "{}: vertex {} has {} coordinates, not {}: neomesh needs one point per vertex (no "
          "high-order or periodic coordinates)",
          name, vertex_number[v - vStart], dof, dim);
      break;
    }
    share.vertex_numbers.push_back(vertex_number[v - vStart]);
    for (int j = 0; j < dim; ++j) share.coords.push_back(PetscRealPart(x[offset + j]));
  }
  NM_PETSC(VecRestoreArrayRead(coordinates, &x));
  NM_PETSC(ISRestoreIndices(cell_numbering, &cell_number));
  NM_PETSC(ISRestoreIndices(vertex_numbering, &vertex_number));
  throw_if_any(PetscObjectComm(reinterpret_cast<PetscObject>(dm)), error);
  return share;
}

}  // namespace

InputMesh input_from_dm(DM dm, const std::string& name) {
  if (!dm) fail("{}: no DM given", name);
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  PetscBool is_plex = PETSC_FALSE;
  NM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(dm), DMPLEX, &is_plex));
  PetscInt dim = 0, coordinate_dim = 0;
  NM_PETSC(DMGetDimension(dm, &dim));
  NM_PETSC(DMGetCoordinateDim(dm, &coordinate_dim));
  collectively(comm, [&] {
    if (!is_plex) fail("{}: the DM is not a DMPlex", name);
    if ((dim != 2 && dim != 3) || coordinate_dim != dim)
      fail("{}: a {}D DMPlex with {}D coordinates (neomesh optimizes 2D and 3D meshes)", name, dim,
           coordinate_dim);
  });
  const Share share = local_share(dm, static_cast<int>(dim), name);
  const auto types = gatherv(comm, share.types, MPIU_INT);
  const auto cell_vertices = gatherv(comm, share.cell_vertices, MPIU_INT);
  const auto numbers = gatherv(comm, share.vertex_numbers, MPIU_INT);
  const auto coords = gatherv(comm, share.coords, MPI_DOUBLE);

  InputMesh input;
  if (mpi_rank(comm) != 0) return input;
  input.dim = static_cast<int>(dim);
  input.coords.assign(coords.size(), 0.0);
  for (std::size_t i = 0; i < numbers.size(); ++i)
    for (PetscInt j = 0; j < dim; ++j) input.coords[numbers[i] * dim + j] = coords[i * dim + j];
  std::size_t next = 0;
  for (PetscInt t : types) {
    const auto type = static_cast<CellType>(t);
    input.add_cell(type, cell_vertices.data() + next, 0);
    next += num_vertices(type);
  }
  return input;
}

}  // namespace neomesh
