#include "mesh/plex_builder.hpp"

#include <metis.h>
#include <petscpartitioner.h>

#include <algorithm>
#include <tuple>
#include <utility>
#include <vector>

#include "core/error.hpp"

#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// The "celltype" label, set a stratum at a time: set point by point, and copied into the
// coordinate DM, it costs more than the rest of the DM.
void set_cell_types(DM dm, const InputMesh& mesh) {
  const PetscInt nc = mesh.num_cells(), nv = mesh.num_vertices();
  DMLabel label;
  NM_PETSC(DMCreateLabel(dm, "celltype"));
  NM_PETSC(DMPlexGetCellTypeLabel(dm, &label));
  for (CellType t : kAllCellTypes) {
    std::vector<PetscInt> cells;
    for (PetscInt c = 0; c < nc; ++c)
      if (mesh.cell_types[c] == t) cells.push_back(c);
    if (cells.empty()) continue;
    OwnedIS is;
    NM_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(cells.size()), cells.data(),
                             PETSC_COPY_VALUES, is.out()));
    NM_PETSC(DMLabelSetStratumIS(label, plex_polytope(t), is));
  }
  OwnedIS vertices;
  NM_PETSC(ISCreateStride(PETSC_COMM_SELF, nv, nc, 1, vertices.out()));
  NM_PETSC(DMLabelSetStratumIS(label, DM_POLYTOPE_POINT, vertices));
}

}  // namespace

OwnedDM build_plex(MPI_Comm comm, const InputMesh& mesh) {
  int dims[2] = {mesh.dim, mesh.coord_dim()};
  MPI_Bcast(dims, 2, MPI_INT, 0, comm);
  const int dim = dims[0], coord_dim = dims[1];
  const PetscInt nc = mesh.num_cells(), nv = mesh.num_vertices();
  OwnedDM dm;
  NM_PETSC(DMCreate(comm, dm.out()));
  NM_PETSC(DMSetType(dm, DMPLEX));
  NM_PETSC(DMSetDimension(dm, dim));
  NM_PETSC(DMPlexSetChart(dm, 0, nc + nv));
  for (PetscInt c = 0; c < nc; ++c)
    NM_PETSC(DMPlexSetConeSize(dm, c, num_vertices(mesh.cell_types[c])));
  NM_PETSC(DMSetUp(dm));
  set_cell_types(dm, mesh);
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
  NM_PETSC(DMPlexBuildCoordinatesFromCellList(dm, coord_dim, mesh.coords.data()));
  return dm;
}

namespace {

// Rank 0's cells by part (METIS k-way, fixed seed), and the part sizes; empty elsewhere.
std::pair<std::vector<PetscInt>, std::vector<PetscInt>> metis_parts(const CellGraph& graph,
                                                                    int parts) {
  const idx_t nc = static_cast<idx_t>(graph.offsets.size()) - 1;
  std::vector<PetscInt> sizes(parts, 0), points;
  if (nc == 0) return {points, sizes};
  std::vector<idx_t> part(nc, 0);
  if (parts > 1 && nc > parts) {
    std::vector<idx_t> xadj(graph.offsets.begin(), graph.offsets.end());
    std::vector<idx_t> adjncy(graph.neighbours.begin(), graph.neighbours.end());
    idx_t options[METIS_NOPTIONS], constraints = 1, nparts = parts, cut = 0;
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1;
    idx_t vertices = nc;
    if (METIS_PartGraphKway(&vertices, &constraints, xadj.data(), adjncy.data(), nullptr, nullptr,
                            nullptr, &nparts, nullptr, nullptr, options, &cut,
                            part.data()) != METIS_OK)
      fail("METIS could not partition the {} cells into {} parts", nc, parts);
  } else {
    for (idx_t c = 0; c < nc; ++c) part[c] = static_cast<idx_t>(c * parts / nc);
  }
  for (idx_t c = 0; c < nc; ++c) ++sizes[part[c]];
  std::vector<PetscInt> at(parts + 1, 0);
  for (int p = 0; p < parts; ++p) at[p + 1] = at[p] + sizes[p];
  points.resize(nc);
  for (idx_t c = 0; c < nc; ++c) points[at[part[c]]++] = c;
  return {points, sizes};
}

// Rank 0's cells by part (as metis_parts), split as METIS splits `graph` or as the partitioner
// the user names.
std::pair<std::vector<PetscInt>, std::vector<PetscInt>> cell_parts(DM dm, CellGraph& graph) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  const int size = mpi_size(comm);
  PetscBool named = PETSC_FALSE;
  NM_PETSC(PetscOptionsHasName(nullptr, nullptr, "-petscpartitioner_type", &named));
  if (!named) return metis_parts(graph, size);
  std::vector<PetscInt> sizes(size), points;
  PetscPartitioner partitioner;
  NM_PETSC(DMPlexGetPartitioner(dm, &partitioner));
  NM_PETSC(PetscPartitionerSetFromOptions(partitioner));
  const PetscInt nc = static_cast<PetscInt>(graph.offsets.size()) - 1;
  // Unit cell weights, as DMPlexDistribute passes them.
  OwnedSection weights, part_sizes;
  NM_PETSC(PetscSectionCreate(PETSC_COMM_SELF, weights.out()));
  NM_PETSC(PetscSectionSetChart(weights, 0, nc));
  for (PetscInt c = 0; c < nc; ++c) NM_PETSC(PetscSectionSetDof(weights, c, 1));
  NM_PETSC(PetscSectionSetUp(weights));
  NM_PETSC(PetscSectionCreate(comm, part_sizes.out()));
  OwnedIS cells;  // by part
  NM_PETSC(PetscPartitionerPartition(partitioner, size, nc, graph.offsets.data(),
                                     graph.neighbours.data(), weights, nullptr, part_sizes,
                                     cells.out()));
  for (int r = 0; r < size; ++r) NM_PETSC(PetscSectionGetDof(part_sizes, r, &sizes[r]));
  const PetscInt* by_part;
  PetscInt n = 0;
  NM_PETSC(ISGetLocalSize(cells, &n));
  NM_PETSC(ISGetIndices(cells, &by_part));
  points.assign(by_part, by_part + n);
  NM_PETSC(ISRestoreIndices(cells, &by_part));
  return {points, sizes};
}

// The graph of the groups of consecutive cells (group g: cells [groups[g], groups[g + 1])):
// two groups are neighbours when cells of theirs are.
CellGraph group_graph(const CellGraph& cells, std::span<const PetscInt> groups) {
  const PetscInt ng = static_cast<PetscInt>(groups.size()) - 1;
  const PetscInt nc = static_cast<PetscInt>(cells.offsets.size()) - 1;
  if (groups.front() != 0 || groups.back() != nc)
    fail("internal error: {} cells in groups of {} cells", nc, groups.back() - groups.front());
  std::vector<PetscInt> group_of(nc);
  for (PetscInt g = 0; g < ng; ++g)
    std::fill(group_of.begin() + groups[g], group_of.begin() + groups[g + 1], g);
  CellGraph out;
  out.offsets.reserve(ng + 1);
  std::vector<PetscInt> neighbours;
  for (PetscInt g = 0; g < ng; ++g) {
    neighbours.clear();
    for (PetscInt c = groups[g]; c < groups[g + 1]; ++c)
      for (PetscInt k = cells.offsets[c]; k < cells.offsets[c + 1]; ++k)
        if (group_of[cells.neighbours[k]] != g) neighbours.push_back(group_of[cells.neighbours[k]]);
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    out.neighbours.insert(out.neighbours.end(), neighbours.begin(), neighbours.end());
    out.offsets.push_back(static_cast<PetscInt>(out.neighbours.size()));
  }
  return out;
}

// Parts of groups (as cell_parts gives them) as parts of their cells.
std::pair<std::vector<PetscInt>, std::vector<PetscInt>> cells_of_groups(
    const std::pair<std::vector<PetscInt>, std::vector<PetscInt>>& parts,
    std::span<const PetscInt> groups) {
  const auto& [by_part, group_sizes] = parts;
  std::vector<PetscInt> points, sizes(group_sizes.size(), 0);
  std::size_t at = 0;
  for (std::size_t r = 0; r < group_sizes.size(); ++r)
    for (PetscInt k = 0; k < group_sizes[r]; ++k, ++at) {
      const PetscInt g = by_part[at];
      for (PetscInt c = groups[g]; c < groups[g + 1]; ++c) points.push_back(c);
      sizes[r] += groups[g + 1] - groups[g];
    }
  return {points, sizes};
}

// Collective: whether rank 0's cells are of several types.
bool mixes_cell_types(DM dm) {
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  int several = 0;
  if (mpi_rank(comm) == 0) {
    PetscInt cStart = 0, cEnd = 0;
    NM_PETSC(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    DMPolytopeType first = DM_POLYTOPE_UNKNOWN, type;
    for (PetscInt c = cStart; c < cEnd && !several; ++c) {
      NM_PETSC(DMPlexGetCellType(dm, c, &type));
      if (c == cStart) first = type;
      several = type != first;
    }
  }
  MPI_Bcast(&several, 1, MPI_INT, 0, comm);
  return several != 0;
}

// DMPlexDistribute's migration before it is stratified, made from the parts at once: the leaves
// on rank r are rank 0's points that go to r, its cells and their vertices, in increasing point
// number (the closure that DMPlexDistribute makes through a partition label and inverts). With
// one cell type that is also the stratified order, cells before vertices.
OwnedSF part_migration(DM dm, const std::vector<PetscInt>& points,
                       const std::vector<PetscInt>& sizes) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  const int size = mpi_size(comm);
  PetscInt pStart = 0, pEnd = 0;
  NM_PETSC(DMPlexGetChart(dm, &pStart, &pEnd));
  std::vector<PetscInt> send;
  std::vector<int> counts(size, 0), displacements(size, 0);
  if (mpi_rank(comm) == 0) {
    std::vector<int> taken_by(pEnd - pStart, -1);
    send.reserve(pEnd - pStart);
    std::size_t first = 0;
    for (int r = 0; r < size; ++r) {
      displacements[r] = static_cast<int>(send.size());
      for (std::size_t i = first; i < first + static_cast<std::size_t>(sizes[r]); ++i) {
        const PetscInt c = points[i];
        send.push_back(c);
        PetscInt n = 0;
        const PetscInt* cone = nullptr;
        NM_PETSC(DMPlexGetConeSize(dm, c, &n));
        NM_PETSC(DMPlexGetCone(dm, c, &cone));
        for (PetscInt k = 0; k < n; ++k)
          if (taken_by[cone[k] - pStart] != r) {
            taken_by[cone[k] - pStart] = r;
            send.push_back(cone[k]);
          }
      }
      first += static_cast<std::size_t>(sizes[r]);
      std::sort(send.begin() + displacements[r], send.end());
      counts[r] = static_cast<int>(send.size()) - displacements[r];
    }
  }
  int count = 0;
  MPI_Scatter(counts.data(), 1, MPI_INT, &count, 1, MPI_INT, 0, comm);
  std::vector<PetscInt> mine(count);
  MPI_Scatterv(send.data(), counts.data(), displacements.data(), MPIU_INT, mine.data(), count,
               MPIU_INT, 0, comm);
  std::vector<PetscSFNode> remote(count);
  for (int i = 0; i < count; ++i) remote[i] = {0, mine[i]};
  OwnedSF sf;
  NM_PETSC(PetscSFCreate(comm, sf.out()));
  NM_PETSC(PetscSFSetGraph(sf, pEnd - pStart, count, nullptr, PETSC_COPY_VALUES, remote.data(),
                           PETSC_COPY_VALUES));
  return sf;
}

}  // namespace

Distributed distribute_plex(DM dm, CellGraph& graph, std::span<const PetscInt> groups) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  // Only rank 0 has cells and groups; the others pass their empty graph to the partitioner.
  CellGraph grouped = groups.empty() ? CellGraph{} : group_graph(graph, groups);
  const auto [points, sizes] =
      groups.empty() ? cell_parts(dm, graph) : cells_of_groups(cell_parts(dm, grouped), groups);
  Distributed d;
  d.migration = part_migration(dm, points, sizes);
  if (mixes_cell_types(dm)) {  // cells by type, as DMPlex numbers them
    const OwnedSF unordered = std::move(d.migration);
    NM_PETSC(DMPlexStratifyMigrationSF(dm, unordered, d.migration.out()));
  }
  NM_PETSC(PetscSFSetUp(d.migration));
  // What DMPlexDistribute does with its migration, for a mesh without overlap, discretization
  // or periodicity.
  NM_PETSC(DMPlexCreate(comm, d.dm.out()));
  NM_PETSC(PetscObjectSetName(reinterpret_cast<PetscObject>(d.dm.get()), "Parallel Mesh"));
  NM_PETSC(DMPlexMigrate(dm, d.migration, d.dm));
  OwnedSF point_sf;
  NM_PETSC(DMPlexCreatePointSF(d.dm, d.migration, PETSC_TRUE, point_sf.out()));
  NM_PETSC(DMSetPointSF(d.dm, point_sf));
  DM coordinates = nullptr;
  NM_PETSC(DMGetCoordinateDM(d.dm, &coordinates));
  if (coordinates) NM_PETSC(DMSetPointSF(coordinates, point_sf));
  return d;
}

}  // namespace neomesh
