#include "mesh/plex_mesh.hpp"

#include <algorithm>
#include <sstream>

#include "core/collective_error.hpp"
#include "mesh/boundary_surface.hpp"
#include "mesh/cell_order.hpp"
#include "mesh/from_input_vertices.hpp"
#include "mesh/input_topology.hpp"
#include "mesh/mesh_impl.hpp"
#include "mesh/plex_builder.hpp"
#include "mesh/validate.hpp"

namespace neomesh {

namespace {

using Impl = MeshAccess::Impl;

void broadcast_groups(MPI_Comm comm, std::vector<PhysicalGroup>& groups) {
  std::ostringstream out;
  for (const auto& g : groups) out << g.dim << ' ' << g.tag << ' ' << g.name << '\n';
  std::string text = out.str();
  int size = static_cast<int>(text.size());
  MPI_Bcast(&size, 1, MPI_INT, 0, comm);
  text.resize(size);
  MPI_Bcast(text.data(), size, MPI_CHAR, 0, comm);
  groups.clear();
  std::istringstream in(text);
  PhysicalGroup g;
  while (in >> g.dim >> g.tag) {
    in.get();
    std::getline(in, g.name);
    groups.push_back(g);
  }
}

// Distributes the cells over the ranks (no overlap) as distribute_plex splits `graph`, `groups`
// kept together. Returns, per local point, its point number in the undistributed DM.
std::vector<PetscInt> distribute(Impl& m, CellGraph& graph, std::span<const PetscInt> groups) {
  PetscInt pStart, pEnd;
  OwnedSF migration;
  if (mpi_size(m.comm) > 1) {
    Distributed distributed = distribute_plex(m.dm, graph, groups);
    m.dm = std::move(distributed.dm);
    migration = std::move(distributed.migration);
  }
  NM_PETSC(DMPlexGetChart(m.dm, &pStart, &pEnd));
  std::vector<PetscInt> original(pEnd - pStart);
  for (PetscInt p = pStart; p < pEnd; ++p) original[p - pStart] = p;
  if (migration) {
    PetscInt nroots, nleaves;
    const PetscInt* ilocal;
    const PetscSFNode* iremote;
    NM_PETSC(PetscSFGetGraph(migration, &nroots, &nleaves, &ilocal, &iremote));
    for (PetscInt i = 0; i < nleaves; ++i)
      original[(ilocal ? ilocal[i] : i) - pStart] = iremote[i].index;
  }
  return original;
}

void build_cells(const Impl& m, const std::vector<PetscInt>& original, MeshView& view) {
  PetscInt cStart, cEnd, vStart;
  NM_PETSC(DMPlexGetHeightStratum(m.dm, 0, &cStart, &cEnd));
  NM_PETSC(DMPlexGetDepthStratum(m.dm, 0, &vStart, nullptr));
  // A cell's type follows from its dimension and number of vertices (faster than the
  // "celltype" label).
  std::vector<CellType> type(cEnd - cStart);
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscInt n;
    NM_PETSC(DMPlexGetConeSize(m.dm, c, &n));
    const int t = cell_type_index(m.dim, static_cast<int>(n));
    if (t < 0) fail("{}: cell {} has {} vertices in {}D", m.source, c, n, m.dim);
    type[c - cStart] = static_cast<CellType>(t);
  }
  view.global_cell.reserve(cEnd - cStart);
  for (CellType t : kAllCellTypes) {
    CellBlock block{t, view.num_cells, {}};
    block.vertices.reserve(std::count(type.begin(), type.end(), t) * num_vertices(t));
    for (PetscInt c = cStart; c < cEnd; ++c) {
      if (type[c - cStart] != t) continue;
      const PetscInt* cone;  // the cell's vertices
      NM_PETSC(DMPlexGetCone(m.dm, c, &cone));
      for (int i = 0; i < num_vertices(t); ++i)
        block.vertices.push_back(cone[canonical_from_plex(t)[i]] - vStart);
      view.global_cell.push_back(original[c]);  // cells come first in the original chart
    }
    view.num_cells += block.size();
    if (block.size() > 0) view.blocks.push_back(std::move(block));
  }
}

// Per local point (relative to the chart start): 1 if another rank owns it (a leaf of the
// point SF).
std::vector<std::uint8_t> ghost_points(DM dm) {
  PetscInt pStart, pEnd;
  NM_PETSC(DMPlexGetChart(dm, &pStart, &pEnd));
  std::vector<std::uint8_t> ghost(pEnd - pStart, 0);
  PetscSF sf;
  NM_PETSC(DMGetPointSF(dm, &sf));
  PetscInt nroots, nleaves;
  const PetscInt* ilocal;
  const PetscSFNode* iremote;
  NM_PETSC(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, &iremote));
  for (PetscInt i = 0; nroots >= 0 && i < nleaves; ++i)
    ghost[(ilocal ? ilocal[i] : i) - pStart] = 1;
  return ghost;
}

// Rank 0 knows the boundary by input vertex; each rank fetches its local vertices' share.
void build_boundary(const Impl& m, const InputTopology& root, MeshView& view) {
  // A surface's parts are its cell groups, as its cells are its boundary facets.
  const int part_dim = m.surface ? m.dim : m.dim - 1;
  for (const PhysicalGroup& g : m.groups)
    if (g.dim == part_dim || g.dim == 0) view.parts.push_back({g.name, g.tag});
  const FromInputVertices fetch(view, static_cast<PetscInt>(root.on_boundary.size()), m.comm);
  view.on_boundary = fetch(root.on_boundary);
  view.boundary_part = fetch(root.boundary_part);
  view.part_count = fetch(root.part_count);
}

void build_view(Impl& m, const std::vector<PetscInt>& original, PetscInt root_vStart,
                const InputTopology& root, BoundarySurface surface) {
  auto view = std::make_unique<MeshView>();
  view->dim = m.coord_dim();
  view->surface = m.surface;
  PetscInt pStart, pEnd, vStart, vEnd;
  NM_PETSC(DMPlexGetChart(m.dm, &pStart, &pEnd));
  NM_PETSC(DMPlexGetDepthStratum(m.dm, 0, &vStart, &vEnd));
  view->num_vertices = vEnd - vStart;

  Vec local;
  NM_PETSC(DMGetCoordinatesLocal(m.dm, &local));
  VecReadView x(local);
  // Built from a cell list, the coordinate section is dim values per vertex, in vertex order.
  if (x.size() != view->num_vertices * view->dim)
    fail("{}: unexpected coordinate layout", m.source);
  view->coords.assign(x.data(), x.data() + x.size());

  const auto ghost = ghost_points(m.dm);
  view->owned.resize(view->num_vertices);
  view->input_vertex.resize(view->num_vertices);
  for (PetscInt v = vStart; v < vEnd; ++v) {
    view->owned[v - vStart] = !ghost[v - pStart];
    view->input_vertex[v - vStart] = original[v - pStart] - root_vStart;
  }
  build_cells(m, original, *view);
  build_boundary(m, root, *view);
  view->boundary = std::make_shared<const BoundarySurface>(std::move(surface));
  m.view = std::move(view);
}

// Per-vertex vectors with dim components: a section with dim dofs on every vertex; its
// global section numbers the owned dofs and encodes a ghost's global dof g as -(g+1).
void build_dofs(Impl& m) {
  PetscInt pStart, pEnd, vStart, vEnd;
  NM_PETSC(DMPlexGetChart(m.dm, &pStart, &pEnd));
  NM_PETSC(DMPlexGetDepthStratum(m.dm, 0, &vStart, &vEnd));
  OwnedSection local, global;
  NM_PETSC(PetscSectionCreate(m.comm, local.out()));
  NM_PETSC(PetscSectionSetChart(local, pStart, pEnd));
  const int d = m.coord_dim();
  for (PetscInt v = vStart; v < vEnd; ++v) NM_PETSC(PetscSectionSetDof(local, v, d));
  NM_PETSC(PetscSectionSetUp(local));
  PetscSF point_sf;
  NM_PETSC(DMGetPointSF(m.dm, &point_sf));
  NM_PETSC(
      PetscSectionCreateGlobalSection(local, point_sf, PETSC_FALSE, PETSC_FALSE, global.out()));
  PetscInt owned_dofs;
  NM_PETSC(PetscSectionGetConstrainedStorageSize(global, &owned_dofs));

  std::vector<PetscInt> global_dof((vEnd - vStart) * d);
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt offset;
    NM_PETSC(PetscSectionGetOffset(global, v, &offset));
    if (offset < 0) offset = -(offset + 1);
    for (int k = 0; k < d; ++k) global_dof[(v - vStart) * d + k] = offset + k;
  }
  // On one process local dof i is global dof i (the section numbers the vertices in order):
  // the DofMap copies values without an SF.
  OwnedSF sf;
  if (mpi_size(m.comm) != 1 || !DofMap::is_identity(global_dof)) {
    PetscLayout layout;
    NM_PETSC(PetscLayoutCreateFromSizes(m.comm, owned_dofs, PETSC_DECIDE, 1, &layout));
    NM_PETSC(PetscSFCreate(m.comm, sf.out()));
    NM_PETSC(PetscSFSetGraphLayout(sf, layout, static_cast<PetscInt>(global_dof.size()), nullptr,
                                   PETSC_OWN_POINTER, global_dof.data()));
    NM_PETSC(PetscLayoutDestroy(&layout));
    NM_PETSC(PetscSFSetUp(sf));
  }
  m.dofs =
      std::make_unique<DofMap>(m.comm, d, vEnd - vStart, owned_dofs, sf, std::move(global_dof));
}

// The common end of from_data and from_input (and so of load_mesh()): validate on rank 0, build,
// distribute, view.
PlexMesh create(MPI_Comm comm, InputMesh& input, const std::string& source,
                bool keep_inverted = false, std::span<const PetscInt> cell_groups = {}) {
  validate(input, source, comm, keep_inverted);
  auto m = std::make_unique<Impl>();
  m->comm = comm;
  m->source = source;
  InputTopology root;
  CellGraph graph;
  BoundarySurface surface;
  on_root(comm, [&] {
    const FacetTable table(input);
    root = input_topology(input, table, source);
    surface = boundary_surface(input, table, root);
    if (mpi_size(comm) > 1) graph = table.cell_graph();
  });
  broadcast(surface, comm);
  m->dm = build_plex(comm, input);
  PetscInt dim, vStart, vEnd, cStart, cEnd;
  NM_PETSC(DMGetDimension(m->dm, &dim));
  m->dim = static_cast<int>(dim);
  int is_surface = input.surface;
  MPI_Bcast(&is_surface, 1, MPI_INT, 0, comm);
  m->surface = is_surface != 0;
  NM_PETSC(DMPlexGetDepthStratum(m->dm, 0, &vStart, &vEnd));
  NM_PETSC(DMPlexGetHeightStratum(m->dm, 0, &cStart, &cEnd));
  PetscInt counts[3] = {cEnd - cStart, vEnd - vStart, vStart};
  MPI_Bcast(counts, 3, MPIU_INT, 0, comm);
  m->global_num_cells = counts[0];
  m->global_num_vertices = counts[1];
  m->groups = input.groups;
  broadcast_groups(comm, m->groups);
  m->cell_tags = std::move(input.cell_tags);
  m->plane = std::move(input.plane);
  m->facets = std::move(root.facets);
  m->points = std::move(root.points);
  m->point_data = std::move(input.point_data);
  m->cell_data = std::move(input.cell_data);
  m->steps = std::move(input.steps);
  int is_curved = input.curved();
  MPI_Bcast(&is_curved, 1, MPI_INT, 0, comm);
  m->curved = is_curved != 0;
  m->high_order = std::move(input.high_order);

  const auto original = distribute(*m, graph, cell_groups);
  build_view(*m, original, counts[2], root, std::move(surface));
  build_dofs(*m);
  return MeshAccess::create(std::move(m));
}

}  // namespace

PlexMesh PlexMesh::from_data(const MeshData& data, const std::string& source, MPI_Comm comm,
                             bool keep_inverted) {
  InputMesh input = mpi_rank(comm) == 0 ? input_from_data(data) : InputMesh{};
  return create(comm, input, source, keep_inverted);
}

PlexMesh PlexMesh::from_input(InputMesh& input, const std::string& source, MPI_Comm comm,
                              bool keep_inverted, std::span<const PetscInt> cell_groups) {
  return create(comm, input, source, keep_inverted, cell_groups);
}

PlexMesh::PlexMesh(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PlexMesh::PlexMesh(PlexMesh&&) noexcept = default;
PlexMesh& PlexMesh::operator=(PlexMesh&&) noexcept = default;
PlexMesh::~PlexMesh() = default;

MPI_Comm PlexMesh::comm() const {
  return impl_->comm;
}
DM PlexMesh::dm() const {
  Impl& m = *impl_;
  if (m.dm_coordinates_stale) {
    // The same layout as view.coords (build_view checked it); set again so that the DM drops
    // its cached global coordinates.
    Vec local;
    NM_PETSC(DMGetCoordinatesLocal(m.dm, &local));
    {
      VecWriteView x(local);
      std::copy(m.view->coords.begin(), m.view->coords.end(), x.data());
    }
    NM_PETSC(DMSetCoordinatesLocal(m.dm, local));
    m.dm_coordinates_stale = false;
  }
  return m.dm;
}
bool PlexMesh::curved() const {
  return impl_->curved;
}
int PlexMesh::dim() const {
  return impl_->dim;
}
const std::string& PlexMesh::source() const {
  return impl_->source;
}
PetscInt PlexMesh::global_num_cells() const {
  return impl_->global_num_cells;
}
PetscInt PlexMesh::global_num_vertices() const {
  return impl_->global_num_vertices;
}
const MeshView& PlexMesh::view() const {
  return *impl_->view;
}
const DofMap& PlexMesh::dofs() const {
  return *impl_->dofs;
}

OwnedVec PlexMesh::coordinates() const {
  const DofMap& dofs = *impl_->dofs;
  const MeshView& view = *impl_->view;
  OwnedVec x = dofs.create_global_vector();
  PetscInt first;
  NM_PETSC(VecGetOwnershipRange(x, &first, nullptr));
  VecWriteView out(x);
  for (PetscInt i = 0; i < dofs.num_local_dofs(); ++i)
    if (view.owned[i / view.dim]) out[dofs.global_dof()[i] - first] = view.coords[i];
  return x;
}

void PlexMesh::set_coordinates(Vec coords) {
  impl_->dofs->global_to_local(coords, impl_->view->coords);
  impl_->dm_coordinates_stale = true;
  ++impl_->coordinates_version;
}

void PlexMesh::set_high_order_nodes(std::span<const double> x) {
  Impl& m = *impl_;
  HighOrderNodes& h = m.high_order;
  if (!m.curved) fail("{}: has no high-order nodes to move", m.source);
  if (mpi_rank(m.comm) == 0) set_high_order_coordinates(h, m.dim, m.plane.get(), x);
  ++m.coordinates_version;
}

void PlexMesh::move_surface_to_coordinates() {
  MeshView& view = *impl_->view;
  if (!view.surface) fail("{}: only a surface mesh moves its surface", impl_->source);
  // Every process holds the whole surface; each vertex's owner gives its coordinates, the
  // others add zeros.
  BoundarySurface moved = *view.boundary;
  std::fill(moved.coords.begin(), moved.coords.end(), 0.0);
  for (PetscInt u = 0; u < view.num_vertices; ++u) {
    const PetscInt b = view.owned[u] ? moved.find(view.input_vertex[u]) : -1;
    if (b >= 0)
      std::copy_n(view.coords.begin() + u * view.dim, view.dim,
                  moved.coords.begin() + b * view.dim);
  }
  MPI_Allreduce(MPI_IN_PLACE, moved.coords.data(), static_cast<int>(moved.coords.size()),
                MPI_DOUBLE, MPI_SUM, impl_->comm);
  view.boundary = std::make_shared<const BoundarySurface>(std::move(moved));
}

std::uint64_t PlexMesh::coordinates_version() const {
  return impl_->coordinates_version;
}

}  // namespace neomesh
