#include <neomesh/level_set.hpp>
#include <neomesh/mesh.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Dense>

#include "api/fitting.hpp"
#include "api/vertex_order.hpp"
#include "boundary/boundary_distance.hpp"
#include "boundary/interface.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "formats/mesh_io.hpp"
#include "geometry/curved_quality.hpp"
#include "geometry/quality.hpp"
#include "mesh/dm_input.hpp"
#include "mesh/gather.hpp"
#include "mesh/input_mesh.hpp"
#include "mesh/plane_embedding.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {

namespace {

// The arrays of from_arrays as an InputMesh (Gmsh order → canonical order), checking what
// the validation of the mesh layer cannot see: sizes, cell types of one dimension, indices.
// 2D cells with 3 coordinates per vertex are a surface mesh unless they lie in one plane.
InputMesh input_from_arrays(int coordinate_dim, std::span<const double> coordinates,
                            std::span<const std::int64_t> cells, std::span<const CellType> types,
                            const std::string& name) {
  const int dim = coordinate_dim;
  if (dim != 2 && dim != 3)
    fail("{}: dimension {} (neomesh optimizes 2D and 3D meshes)", name, dim);
  if (coordinates.size() % dim != 0)
    fail("{}: {} coordinates are not a whole number of {}D vertices", name, coordinates.size(),
         dim);
  const bool surface = dim == 3 && !types.empty() && neomesh::facts(types[0]).dim == 2;
  InputMesh input;
  input.dim = surface ? 2 : dim;
  input.coords.assign(coordinates.begin(), coordinates.end());
  const auto num_vertices = static_cast<std::int64_t>(coordinates.size()) / dim;
  std::size_t next = 0;
  for (std::size_t c = 0; c < types.size(); ++c) {
    const CellFacts& facts = neomesh::facts(types[c]);
    if (facts.dim != input.dim)
      fail("{}: cell {} is a {} in a {}D mesh", name, c, facts.name, input.dim);
    if (next + facts.vertices > cells.size())
      fail("{}: the cell array ends within cell {} ({} vertex numbers for {} cells)", name, c,
           cells.size(), types.size());
    PetscInt canonical[8];
    for (int i = 0; i < facts.vertices; ++i) {
      const std::int64_t v = cells[next + i];
      if (v < 0 || v >= num_vertices)
        fail("{}: cell {} names vertex {}, but there are {} vertices (0-based)", name, c, v,
             num_vertices);
      canonical[facts.gmsh_order[i]] = static_cast<PetscInt>(v);
    }
    next += facts.vertices;
    input.add_cell(types[c], canonical, 0);
  }
  if (next != cells.size())
    fail("{}: {} vertex numbers for {} cells that have {}", name, cells.size(), types.size(), next);
  if (surface) {
    std::vector<double> in_plane;
    if (PlaneEmbedding::fit(coordinates, in_plane, name))
      fail("{}: its 2D cells lie in one plane: give 2 coordinates per vertex, in that plane", name);
    input.surface = true;
  }
  return input;
}

// The curved cells' summary, computed on rank 0 from the gathered mesh and sent to every rank.
CurvedQualitySummary curved_summary(const PlexMesh& plex) {
  return curved_quality_on_root(gather_mesh(plex, {}).mesh, plex.comm());
}

}  // namespace

void check_readable_format(const std::filesystem::path& path) {
  require_readable_format(path);
}

void check_writable_format(const std::filesystem::path& path) {
  require_writable_format(path);
}

Mesh Mesh::read(const std::filesystem::path& path, MPI_Comm comm, InvertedCells inverted) {
  const double before = resident_bytes();
  return Mesh(std::make_unique<PlexMesh>(load_mesh(path, comm, inverted == InvertedCells::Keep)),
              before);
}

Mesh Mesh::read(const std::vector<std::filesystem::path>& paths, MPI_Comm comm,
                InvertedCells inverted) {
  if (paths.empty()) fail("no mesh file given");
  const double before = resident_bytes();
  return Mesh(std::make_unique<PlexMesh>(load_mesh(paths, comm, inverted == InvertedCells::Keep)),
              before);
}

Mesh Mesh::from_arrays(MPI_Comm comm, int coordinate_dim, std::span<const double> coordinates,
                       std::span<const std::int64_t> cells, std::span<const CellType> types,
                       const std::string& name, InvertedCells inverted) {
  const double before = resident_bytes();
  InputMesh input;
  collectively(comm, [&] {
    if (mpi_rank(comm) == 0)
      input = input_from_arrays(coordinate_dim, coordinates, cells, types, name);
  });
  return Mesh(std::make_unique<PlexMesh>(
                  PlexMesh::from_input(input, name, comm, inverted == InvertedCells::Keep)),
              before);
}

Mesh Mesh::from_dm(DM dm, const std::string& name, InvertedCells inverted) {
  const double before = resident_bytes();
  InputMesh input = input_from_dm(dm, name);
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  return Mesh(std::make_unique<PlexMesh>(
                  PlexMesh::from_input(input, name, comm, inverted == InvertedCells::Keep)),
              before);
}

struct Mesh::QualityCache {
  std::uint64_t coordinates_version;
  CellQuality quality;
};

Mesh::Mesh(std::unique_ptr<PlexMesh> plex, double resident_before)
    : plex_(std::move(plex)), creation_bytes_(std::max(0.0, resident_bytes() - resident_before)) {}
Mesh::Mesh(Mesh&&) noexcept = default;
Mesh& Mesh::operator=(Mesh&&) noexcept = default;
Mesh::~Mesh() = default;

MPI_Comm Mesh::comm() const {
  return plex_->comm();
}
int Mesh::dim() const {
  return plex_->dim();
}
int Mesh::coordinate_dim() const {
  return plex_->view().dim;
}
const std::string& Mesh::name() const {
  return plex_->source();
}
std::int64_t Mesh::num_cells() const {
  return plex_->global_num_cells();
}
std::int64_t Mesh::num_vertices() const {
  return plex_->global_num_vertices();
}
DM Mesh::dm() const {
  return plex_->dm();
}
PlexMesh& Mesh::plex() {
  quality_cache_.reset();  // also frees it while an optimizer works on the mesh
  return *plex_;
}
const PlexMesh& Mesh::plex() const {
  return *plex_;
}

std::vector<std::int64_t> Mesh::vertex_numbers() const {
  const MeshView& view = plex_->view();
  std::vector<std::int64_t> numbers;
  for (PetscInt u : owned_by_number(view)) numbers.push_back(view.input_vertex[u]);
  return numbers;
}

namespace {

// Relative to the size of a surface mesh, how far a vertex set by set_coordinates may lie from
// the surface its vertices slide on before the surface counts as moved: far above the round-off
// of the sliding projection, which leaves smoothed vertices on the surface.
constexpr double kOnSurfaceTolerance = 1e-9;

// True if a vertex of the surface mesh `view` lies off the surface it slides on (view.boundary).
bool moved_off_surface(const MeshView& view, MPI_Comm comm) {
  const BoundarySurface& surface = *view.boundary;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (PetscInt b = 0; b < surface.num_vertices(); ++b) {
    const Eigen::Vector3d p(surface.coords.data() + 3 * b);
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const double size = surface.num_vertices() > 0 ? (hi - lo).norm() : 0.0;
  const double distance =
      max_boundary_distance(view, view.coords, DistanceToBoundary(surface), comm);
  return distance > kOnSurfaceTolerance * size;
}

}  // namespace

std::vector<double> Mesh::coordinates() const {
  const MeshView& view = plex_->view();
  std::vector<double> out;
  for (PetscInt u : owned_by_number(view))
    for (int j = 0; j < view.dim; ++j) out.push_back(view.coords[u * view.dim + j]);
  return out;
}

void Mesh::set_coordinates(std::span<const double> coordinates) {
  const MeshView& view = plex_->view();
  const std::vector<PetscInt> owned = owned_by_number(view);
  collectively(comm(), [&] {
    if (coordinates.size() != owned.size() * view.dim)
      fail("{}: {} coordinates given for {} vertices of this process ({} each)", name(),
           coordinates.size(), owned.size(), view.dim);
    for (double c : coordinates)
      if (!std::isfinite(c)) fail("{}: a coordinate given is not a finite number", name());
  });
  // The owned vertices' new coordinates go into a global Vec; the mesh spreads them to ghosts.
  OwnedVec x = plex_->coordinates();
  const std::vector<PetscInt>& global_dof = plex_->dofs().global_dof();
  for (std::size_t i = 0; i < owned.size(); ++i)
    for (int j = 0; j < view.dim; ++j)
      NM_PETSC(VecSetValue(x, global_dof[owned[i] * view.dim + j], coordinates[i * view.dim + j],
                           INSERT_VALUES));
  NM_PETSC(VecAssemblyBegin(x));
  NM_PETSC(VecAssemblyEnd(x));
  plex_->set_coordinates(x);
  // A surface moved by the caller (a deforming shell in a time loop) is the surface from now
  // on; vertices moved along it keep sliding on the cells the mesh was made with.
  if (view.surface && moved_off_surface(view, comm())) plex_->move_surface_to_coordinates();
}

const CellQuality& Mesh::cell_quality() const {
  const std::uint64_t version = plex_->coordinates_version();
  if (!quality_cache_ || quality_cache_->coordinates_version != version) {
    const MeshView& view = plex_->view();
    quality_cache_ = std::make_unique<QualityCache>(
        QualityCache{version, neomesh::cell_quality(view, view.coords, &plex_->dofs())});
  }
  return quality_cache_->quality;
}

QualitySummary Mesh::quality() const {
  QualitySummary summary = summarize(cell_quality(), comm());
  if (plex_->curved()) summary.curved = curved_summary(*plex_);
  return summary;
}

bool Mesh::curved() const {
  return plex_->curved();
}

void Mesh::write(const std::filesystem::path& path, const std::vector<Field>& cell_fields,
                 const std::vector<Field>& vertex_fields,
                 const std::vector<FacetGroup>& facet_groups) const {
  const MeshView& view = plex_->view();
  MeshFields fields;
  fields.cell = quality_fields(cell_quality());
  fields.cell.insert(fields.cell.end(), cell_fields.begin(), cell_fields.end());
  collectively(comm(), [&] {
    for (const Field& f : vertex_fields) fields.vertex.push_back(local_vertex_field(view, f));
  });
  fields.facet_groups = facet_groups;
  write_mesh(*plex_, path, fields);
}

FacetGroup Mesh::interface(const LevelSet& phi) const {
  const MeshView& view = plex_->view();
  const LevelSetFunction function = level_set_function(phi, view.dim);
  const Interface found = find_interface(view, plex_->dofs(), view.coords, function);
  return public_facet_group(view, "interface", found.offsets, found.facet_vertices);
}

std::vector<std::int64_t> Mesh::cell_numbers() const {
  const std::vector<PetscInt>& numbers = plex_->view().global_cell;
  return {numbers.begin(), numbers.end()};
}

std::vector<Field> Mesh::quality_by_cell() const {
  const CellQuality& quality = cell_quality();
  std::vector<Field> fields = quality_fields(quality);
  Field inverted{"inverted", std::vector<double>(quality.size(), 0.0)};
  for (std::size_t c = 0; c < quality.size(); ++c)
    if (!(quality.min_corner_det[c] > 0 && quality.min_gauss_det[c] > 0)) inverted.values[c] = 1;
  fields.push_back(std::move(inverted));
  return fields;
}

double Mesh::volume() const {
  const MeshView& view = plex_->view();
  const std::vector<double> volumes = neomesh::cell_volumes(view, view.coords, &plex_->dofs());
  double sum = std::accumulate(volumes.begin(), volumes.end(), 0.0);
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, comm());
  return sum;
}

double Mesh::max_boundary_distance(const Mesh& reference) const {
  if (reference.dim() != dim())
    fail("{} is {}D, {} {}D: their boundaries cannot be compared", reference.name(),
         reference.dim(), name(), dim());
  const MeshView& view = plex_->view();
  return neomesh::max_boundary_distance(
      view, view.coords, DistanceToBoundary(*reference.plex().view().boundary), comm());
}

MeshArrays Mesh::gather(const std::vector<Field>& cell_fields) const {
  MeshFields fields;
  fields.cell = cell_fields;
  const GatheredMesh gathered = gather_mesh(*plex_, fields);
  const InputMesh& m = gathered.mesh;
  MeshArrays out;
  out.dim = m.dim;
  out.coordinate_dim = m.coord_dim();
  out.cell_fields = gathered.fields.cell;
  if (mpi_rank(comm()) != 0) return out;
  out.coordinates = m.coords;
  out.types = m.cell_types;
  out.cells.reserve(m.cell_vertices.size());
  for (PetscInt c = 0; c < m.num_cells(); ++c) {
    const CellFacts& facts = neomesh::facts(m.cell_types[c]);
    for (int i = 0; i < facts.vertices; ++i)  // canonical → Gmsh order
      out.cells.push_back(m.cell_vertices[m.cell_offsets[c] + facts.gmsh_order[i]]);
  }
  for (const PhysicalGroup& g : m.groups) out.groups.push_back({g.dim, g.tag, g.name});
  out.cell_tags = m.cell_tags;
  for (const TaggedEntities* tagged : {&m.facets, &m.points})
    for (PetscInt e = 0; e < tagged->size(); ++e) {
      out.entity_vertices.insert(out.entity_vertices.end(),
                                 tagged->vertices.begin() + tagged->offsets[e],
                                 tagged->vertices.begin() + tagged->offsets[e + 1]);
      out.entity_offsets.push_back(static_cast<std::int64_t>(out.entity_vertices.size()));
      out.entity_tags.push_back(tagged->tags[e]);
    }
  for (auto [from, to] :
       {std::pair(&m.point_data, &out.point_data), std::pair(&m.cell_data, &out.cell_data)})
    for (const DataArray& a : *from) to->push_back({a.name, a.values, a.components});
  return out;
}

void Mesh::write_mesh_only(const std::filesystem::path& path) const {
  write_mesh(*plex_, path);
}

}  // namespace neomesh
