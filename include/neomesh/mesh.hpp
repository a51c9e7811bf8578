// neomesh::Mesh: the mesh a simulation hands to neomesh and gets back with its vertices moved
// (the connectivity never changes). Read from a file, built from arrays, in the caller's
// vertex numbering; under MPI the cells are distributed over the communicator's processes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <mpi.h>

#include <neomesh/cell_type.hpp>
#include <neomesh/field.hpp>
#include <neomesh/quality.hpp>

typedef struct _p_DM* DM;  // PETSc's handle, as petscdm.h declares it

namespace neomesh {

class PlexMesh;          // the implementation (src/mesh/plex_mesh.hpp)
struct CellQuality;      // per-cell quality (src/geometry/quality.hpp)
struct GenerateOptions;  // neomesh/generate.hpp
struct MeshArrays;       // below
struct CurveOptions;     // neomesh/curve.hpp
struct CurveSummary;     // neomesh/curve.hpp

// Whether a mesh with inverted or degenerate cells is an error (Refuse) or read as it is
// (Keep: Optimizer::smooth untangles it, quality() counts the inverted cells).
enum class InvertedCells { Refuse, Keep };

class LevelSet;  // level_set.hpp

// Throws Error unless `path` has an extension neomesh reads (.msh, .xml, .vtk, .vtu, .pvtu,
// .mesh, .exo, .e, .ex2, .cgns) / writes (.msh, .vtu, .mesh, .exo, .e, .ex2, .cgns): a check before
// a long run.
void check_readable_format(const std::filesystem::path& path);
void check_writable_format(const std::filesystem::path& path);

class Mesh {
 public:
  // Reads .msh (Gmsh 2.2/4.1, ASCII or binary), .xml (FEAT3), .vtk (VTK legacy, ASCII or
  // binary, UNSTRUCTURED_GRID or POLYDATA), .vtu/.pvtu (VTK XML UnstructuredGrid, any encoding),
  // .mesh (Medit ASCII), .exo/.e/.ex2 (Exodus II) or .cgns (CGNS) on the first process and
  // distributes it over `comm`. Throws Error naming the file (and cell) for anything neomesh
  // cannot use: a missing file, a malformed mesh, an unsupported cell type, NaN coordinates.
  // 2D cells that do not lie in one plane are a surface mesh: dim() is 2 and coordinate_dim() 3
  // (docs/user-guide.md, "Surface meshes"). A 2D mesh whose file places it in another plane
  // than z = 0 is optimized in that plane (coordinates() are in-plane ones) and written back in
  // it (docs/user-guide.md, "What a run never changes").
  static Mesh read(const std::filesystem::path& path, MPI_Comm comm = MPI_COMM_WORLD,
                   InvertedCells inverted = InvertedCells::Refuse);
  // A FEAT3 mesh file together with the files holding its charts (FEAT3's chart files), in any
  // order, as FEAT3's applications take them (`--mesh chart.xml mesh.xml`); one path: as above.
  // The mesh is named after all of them ("chart.xml + mesh.xml").
  static Mesh read(const std::vector<std::filesystem::path>& paths, MPI_Comm comm = MPI_COMM_WORLD,
                   InvertedCells inverted = InvertedCells::Refuse);

  // Builds a mesh from arrays given on the communicator's first process (the others pass
  // empty spans) and distributes it. `coordinates`: `coordinate_dim` values per vertex;
  // `cells`: the vertices of each cell in Gmsh's order (docs/cell-types.md), 0-based, one
  // CellType per cell in `types` (types may be mixed, of one dimension: coordinate_dim's, or
  // triangles and quadrilaterals with 3 coordinates per vertex not in one plane, a surface
  // mesh). The vertices' positions in `coordinates` are their numbers (vertex_numbers()).
  // `name` names the mesh in messages.
  static Mesh from_arrays(MPI_Comm comm, int coordinate_dim, std::span<const double> coordinates,
                          std::span<const std::int64_t> cells, std::span<const CellType> types,
                          const std::string& name = "mesh from arrays",
                          InvertedCells inverted = InvertedCells::Refuse);

  // Takes over a DMPlex the caller built (serial or distributed, interpolated or not): its
  // owned cells and vertex coordinates, with the vertices numbered by DMPlexGetVertexNumbering
  // (their vertex_numbers()). neomesh builds and distributes its own DMPlex over the DM's
  // communicator; `dm` stays the caller's and is not changed. Labels are not taken over (the
  // boundary's parts then come from its corners and ridges). Throws Error for a DM neomesh
  // cannot use (not a DMPlex, not 2D/3D, high-order or periodic coordinates, other cell
  // types) and, like read(), for inverted or degenerate cells.
  static Mesh from_dm(DM dm, const std::string& name = "mesh from a DMPlex",
                      InvertedCells inverted = InvertedCells::Refuse);

  Mesh(Mesh&&) noexcept;
  Mesh& operator=(Mesh&&) noexcept;
  ~Mesh();

  MPI_Comm comm() const;
  int dim() const;  // of the cells
  // Coordinates per vertex: dim(), or 3 for a surface mesh (2D cells in space).
  int coordinate_dim() const;
  const std::string& name() const;  // file name, or from_arrays' name
  std::int64_t num_cells() const;   // over all processes
  std::int64_t num_vertices() const;

  // The vertices this process owns, by their number in the input (the file's order, or the
  // position in from_arrays' coordinates), ascending; every vertex is owned by one process.
  std::vector<std::int64_t> vertex_numbers() const;
  // Their current coordinates, coordinate_dim() values per vertex of vertex_numbers().
  std::vector<double> coordinates() const;
  // Moves them (same layout as coordinates()); the next optimization starts there. A surface
  // mesh's vertices slide on its cells as it was made; coordinates that take a vertex off that
  // surface move the surface: from then on they slide on the cells at these coordinates
  // (docs/user-guide.md, "Surface meshes").
  void set_coordinates(std::span<const double> coordinates);

  // The quality of all cells (collective); of a curved mesh also that of its curved cells.
  QualitySummary quality() const;

  // True for a mesh of second-order (curved) cells (docs/user-guide.md, "Curved meshes"): read
  // from .msh, .vtk and .vtu, its cells are the straight cells of their corners, which the
  // vertices are, and keep their other nodes; quality() measures the curved cells too and
  // write() writes them to .msh, .vtu and .vtk. They are not optimized yet: Optimizer refuses
  // the mesh.
  bool curved() const;

  // Writes .msh (Gmsh 4.1, with the input's physical groups and `facet_groups`), .mesh (Medit,
  // with the groups' numbers as references), .exo/.e/.ex2 (Exodus II, with element blocks and
  // side sets), .cgns (CGNS, with sections and boundary conditions) or .vtu/.vtk (with the
  // groups, the cell quality fields, `cell_fields` and `vertex_fields`) atomically: an error
  // leaves no partial file. The point and cell data of the file read (VTK data arrays, Exodus
  // variables, Gmsh $NodeData/$ElementData) are written back unchanged to .vtu, .vtk, .exo and
  // .msh; a field whose name they have is written as "neomesh_<name>" (docs/user-guide.md).
  // Collective.
  void write(const std::filesystem::path& path, const std::vector<Field>& cell_fields = {},
             const std::vector<Field>& vertex_fields = {},
             const std::vector<FacetGroup>& facet_groups = {}) const;

  // The facets that fitting to `phi` (Optimizer::adapt with a LevelSet) would pull onto its
  // zero set, at the current coordinates and φ's time: between the cells with φ < 0 at the
  // centroid and the others, after the clean-up of docs/adaptivity.md. Throws Error if φ has
  // one sign at every centroid or the interface touches the domain's boundary. Collective:
  // each process gets the facets whose inside cell it holds.
  FacetGroup interface(const LevelSet& phi) const;

  // The distributed DMPlex, for a caller that works with PETSc directly (owned by the Mesh).
  DM dm() const;

  // One of the thesis' test meshes (neomesh/generate.hpp), built on the communicator's first
  // process and distributed like from_arrays; named after the case, its boundary sides in
  // named groups ("left", "right", ..., "circle") as .msh physical groups. A large jitter
  // folds cells over: such a mesh is kept as it is (InvertedCells::Keep), for smooth() to
  // untangle. Throws OptionError for options out of range. Collective.
  static Mesh generate(const GenerateOptions& options, MPI_Comm comm = MPI_COMM_WORLD);

  // The cells of this process by their number in the input (the file's order, or the position
  // in from_arrays' types), in this process' order: the order of per-cell fields
  // (quality_by_cell(), Optimizer::cell_fields(), write()).
  std::vector<std::int64_t> cell_numbers() const;
  // Per local cell at the current coordinates (this process' order, as write() takes fields):
  // "volume" (signed), "scaled_jacobian", "min_angle", "max_angle", "edge_ratio",
  // "inverse_mean_ratio" (as quality() summarizes them) and "inverted" (1 where det J ≤ 0 at a
  // corner or Gauss point, else 0).
  std::vector<Field> quality_by_cell() const;
  // The volume of the domain: the sum of the cells' signed volumes (collective).
  double volume() const;
  // The largest distance of a boundary vertex from `reference`'s boundary facets, e.g. the
  // mesh before an optimization with sliding boundary vertices: how far the domain moved.
  // Throws Error if the dimensions differ. Collective (both meshes on the same communicator).
  double max_boundary_distance(const Mesh& reference) const;

  // The whole mesh at its current coordinates on the communicator's first process, as
  // from_arrays takes it and in the same numbering (its vertex numbers, cells in input order),
  // with `cell_fields` (per local cell, as quality_by_cell() gives them) by cell number, and
  // the file's groups and data. The other processes get only the dimensions and the fields'
  // names.
  // Throws Error if a field does not have a value per cell. Collective.
  MeshArrays gather(const std::vector<Field>& cell_fields = {}) const;

  // Writes the mesh without fields (.vtu: no quality fields either; the input's data are
  // written as by write()), atomically. Collective.
  void write_mesh_only(const std::filesystem::path& path) const;

 private:
  friend class Optimizer;    // works on the implementation
  friend class SizeField;    // a metric per vertex is interpolated over the mesh
  friend struct MeshAccess;  // src/report/render.cpp draws a curved mesh's high-order nodes
  friend Mesh curve_mesh(const std::vector<std::filesystem::path>& inputs,
                         const CurveOptions& options, CurveSummary* summary, MPI_Comm comm);
  // The implementation; the non-const one may move the vertices, so it drops the quality cache.
  PlexMesh& plex();
  const PlexMesh& plex() const;
  // `resident_before`: this process' resident set before the mesh was made.
  Mesh(std::unique_ptr<PlexMesh> plex, double resident_before);
  // The cells' quality at the current coordinates, computed once for quality(),
  // quality_by_cell() and write() (a run asks for it three times after optimizing).
  const CellQuality& cell_quality() const;
  struct QualityCache;  // mesh.cpp
  std::unique_ptr<PlexMesh> plex_;
  mutable std::unique_ptr<QualityCache> quality_cache_;
  // What making the mesh added to this process' resident set: the mesh, and what its reader
  // freed, which malloc keeps for the run (the memory check counts it as held).
  double creation_bytes_ = 0.0;
};

// A physical group of the input file (Gmsh's, or an Exodus block or side set, ...): cells
// (dim = the mesh's), boundary facets (dim − 1) or single vertices (0).
struct MeshGroup {
  int dim = 0;
  int tag = 0;
  std::string name;
};

// A whole mesh as arrays (Mesh::gather), the inverse of Mesh::from_arrays:
// Mesh::from_arrays(comm, a.coordinate_dim, a.coordinates, a.cells, a.types) builds the same
// mesh.
struct MeshArrays {
  int dim = 0;                      // of the cells (Mesh::dim())
  int coordinate_dim = 0;           // values per vertex: dim, or 3 for a surface mesh
  std::vector<double> coordinates;  // `coordinate_dim` values per vertex, by vertex number
  std::vector<std::int64_t> cells;  // each cell's vertices in Gmsh's order, by cell number
  std::vector<CellType> types;      // one per cell
  std::vector<Field> cell_fields;   // `components` values per cell, by cell number
  // What the file of Mesh::read carries besides the mesh, as write() writes it back (empty for
  // a mesh from arrays or a DM): its groups; the tag of each cell's group (0: none); the facets
  // and single vertices in groups (vertex numbers, facets in Gmsh's order) with their groups'
  // tags; its point and cell data by vertex and cell number.
  std::vector<MeshGroup> groups;
  std::vector<int> cell_tags;
  std::vector<std::int64_t> entity_offsets = {
      0};  // entity e is entity_vertices[offsets[e], [e + 1])
  std::vector<std::int64_t> entity_vertices;
  std::vector<int> entity_tags;
  std::vector<Field> point_data, cell_data;
};

}  // namespace neomesh
