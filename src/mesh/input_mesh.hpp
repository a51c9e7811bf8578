// InputMesh: a whole mesh as read from a file (or given as MeshData), on rank 0 only, before
// it becomes a distributed DMPlex. Cells are in canonical vertex order (cell_type.hpp) and
// in input order; physical groups keep their Gmsh (dim, tag, name).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <petscsys.h>

#include "mesh/cell_type.hpp"
#include "mesh/curved_type.hpp"
#include "mesh/mesh_data.hpp"
#include "mesh/nodes_by_corners.hpp"
#include "mesh/plane_embedding.hpp"

namespace neomesh {

// A Gmsh physical group: cells (dim = mesh dim), boundary facets (dim - 1) or points (0).
struct PhysicalGroup {
  int dim = 0;
  int tag = 0;
  std::string name;
};

// Entities of one kind with their vertices (CSR) and one physical tag each.
struct TaggedEntities {
  std::vector<PetscInt> offsets = {0};
  std::vector<PetscInt> vertices;
  std::vector<int> tags;

  PetscInt size() const { return static_cast<PetscInt>(tags.size()); }
  void add(const PetscInt* v, PetscInt n, int tag) {
    vertices.insert(vertices.end(), v, v + n);
    offsets.push_back(static_cast<PetscInt>(vertices.size()));
    tags.push_back(tag);
  }
};

// The type a file stores an array's values in, kept so that writing the array back gives the same
// type (values are held as double: exact for every type but 64-bit integers beyond 2^53).
enum class ValueType : std::uint8_t {
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float32,
  Float64
};

// An array of values per vertex or per cell that the input file carries (VTK point and cell
// data, Exodus nodal and element variables, Gmsh $NodeData/$ElementData): neomesh never uses
// them, it writes them back. `components` values per entity, in input numbering.
struct DataArray {
  std::string name;
  int components = 1;
  ValueType type = ValueType::Float64;
  std::vector<double> values;
};

// The values of an array read as text rounded to its type (Float32: to float), as they are
// written back.
void round_to_type(DataArray& array);

// The arrays restricted to the entities kept: entity `i` of the result is `kept[i]` of the file.
// Arrays whose values do not cover `count` entities are left out.
std::vector<DataArray> select_data(const std::vector<DataArray>& arrays, std::size_t count,
                                   const std::vector<std::int64_t>& kept);

// The time steps of an input that has them (Exodus): each step's time and global variables,
// and the point and cell data of the steps before the last (point_data and cell_data are the
// last step's), in input numbering. Only .exo writes them back.
struct TimeSteps {
  std::vector<double> times;                                  // per step
  std::vector<std::string> global_names;                      // the global variables
  std::vector<std::vector<double>> globals;                   // per step: a value per name
  std::vector<std::vector<DataArray>> point_data, cell_data;  // per step before the last
};

// The nodes of second-order (curved) cells beyond their corners. A curved mesh has only
// second-order cells: their corners are the mesh's vertices (InputMesh::cell_vertices, from which
// the DMPlex is built) and their other nodes (mid-edge, mid-face, centre) are numbered apart, in
// the order the file lists them; a node shared by cells is one node. Nothing moves them (curved
// cells are read, measured and written, not optimized), so they keep the file's 3D coordinates
// and are written back as they were read.
struct HighOrderNodes {
  std::vector<CurvedType> types;        // per cell; empty for a straight mesh
  std::vector<PetscInt> offsets = {0};  // per cell, into `nodes`
  std::vector<PetscInt> nodes;          // per cell: its nodes after the corners, in Gmsh order
  std::vector<double> xyz;              // 3 per node

  bool empty() const { return types.empty(); }
  PetscInt num_nodes() const { return static_cast<PetscInt>(xyz.size() / 3); }
  void add(CurvedType t, const PetscInt* n) {
    types.push_back(t);
    const int count = facts(t).nodes - num_vertices(facts(t).linear);
    nodes.insert(nodes.end(), n, n + count);
    offsets.push_back(static_cast<PetscInt>(nodes.size()));
  }
};

struct InputMesh {
  int dim = 2;  // of the cells
  // 2D cells whose vertices do not lie in one plane: a surface mesh, with 3 coordinates per
  // vertex as the file gives them (docs/method.md, "Surface cells").
  bool surface = false;
  std::vector<double> coords;  // coord_dim() values per vertex (2D: in the mesh's plane)
  // 2D: the plane the mesh lies in, when the file gave 3D coordinates off z = 0; null for z = 0.
  std::shared_ptr<const PlaneEmbedding> plane;
  std::vector<CellType> cell_types;  // per cell
  std::vector<PetscInt> cell_offsets = {0};
  std::vector<PetscInt> cell_vertices;  // canonical order
  std::vector<int> cell_tags;           // per cell: Gmsh physical tag, or 0 for none
  TaggedEntities facets;                // boundary facets in physical groups
  std::vector<VertexSet> vertex_sets;   // named vertex sets (turned into facets, input_topology)
  TaggedEntities points;                // single vertices in physical groups
  std::vector<PhysicalGroup> groups;    // every group above, sorted by (dim, tag)
  std::vector<Chart> charts;            // FEAT3 charts; VertexSet::chart names them
  // Per cell: the number the file gives it (Gmsh element tag), for messages; empty when the
  // format numbers cells by position only (FEAT3, generated meshes).
  std::vector<std::int64_t> element_tag;
  // Data the file gives per vertex and per cell, in input numbering, written back unchanged.
  std::vector<DataArray> point_data;
  std::vector<DataArray> cell_data;
  TimeSteps steps;
  HighOrderNodes high_order;  // second-order cells' further nodes; empty for a straight mesh

  bool curved() const { return !high_order.empty(); }
  int coord_dim() const { return surface ? 3 : dim; }
  PetscInt num_vertices() const { return static_cast<PetscInt>(coords.size()) / coord_dim(); }
  PetscInt num_cells() const { return static_cast<PetscInt>(cell_types.size()); }
  // The points files list: the vertices, then the high-order nodes (none for a straight mesh).
  PetscInt num_points() const { return num_vertices() + high_order.num_nodes(); }
  void add_cell(CellType t, const PetscInt* v, int tag) {
    cell_types.push_back(t);
    cell_vertices.insert(cell_vertices.end(), v, v + num_vertices_of(t));
    cell_offsets.push_back(static_cast<PetscInt>(cell_vertices.size()));
    cell_tags.push_back(tag);
  }

 private:
  static int num_vertices_of(CellType t) { return neomesh::num_vertices(t); }
};

InputMesh input_from_data(const MeshData& data);

// For the readers: numbers the file's nodes marked used (`vertex[n] >= 0`) in file order, into
// `vertex`, and sets mesh.coords from their 3D coordinates `xyz` (3 per node). A 2D mesh
// (mesh.dim) gets coordinates in its plane, and mesh.plane unless that is z = 0
// (plane_embedding.hpp); one whose vertices do not lie in one plane is a surface mesh
// (mesh.surface) and keeps the 3D coordinates.
void number_used_vertices(std::vector<PetscInt>& vertex, std::span<const double> xyz,
                          const std::string& file, InputMesh& mesh);

// For the readers, after number_used_vertices: numbers the file's nodes marked (`node[n] >= 0`)
// in file order as mesh.high_order's nodes, with their coordinates `xyz` (3 per node); throws
// Error naming `file` and the node (1-based) if one is also a vertex (`vertex[n] >= 0`).
void number_high_order_nodes(std::vector<PetscInt>& node, const std::vector<PetscInt>& vertex,
                             std::span<const double> xyz, const std::string& file, InputMesh& mesh);

// The vertices' coordinates in 3D space, 3 per vertex: a 2D mesh's put back in its plane.
std::vector<double> coordinates_in_space(const InputMesh& mesh);

// A curved mesh's points, as files list them: its vertices, then its high-order nodes. Cell
// `c`'s points in Gmsh order (facts(type).nodes of them) go into `points`; returns how many.
int curved_cell_points(const InputMesh& mesh, PetscInt c, PetscInt* points);
// Their coordinates, coord_dim() values per point: a 2D mesh's in its plane; and in space (3 per
// point, as coordinates_in_space() and the nodes' as read) for the writers.
std::vector<double> points_in_space(const InputMesh& mesh);
std::vector<double> curved_point_coordinates(const InputMesh& mesh);
// The high-order nodes on the sides of a curved mesh's cells, found by the corners of their edge
// (or hexahedron27 face), so that the group facets, which InputMesh keeps by their corners, are
// written at second order: a line3, triangle6, quadrilateral8 or quadrilateral9.
class CurvedFacets {
 public:
  explicit CurvedFacets(const InputMesh& mesh);
  // Facet `k` of mesh.facets as points (as curved_cell_points numbers them): its corners as
  // listed, the nodes of its edges (0,1), (1,2), ... (n−1,0), then of its face, the order of
  // Gmsh, VTK, Exodus II, CGNS and Medit alike; how many. Just its corners when the mesh is
  // straight or the facet no side of a cell.
  int points(PetscInt k, PetscInt* out) const;

 private:
  const InputMesh& mesh_;
  NodesByCorners nodes_;
};

// The nodes moved to `x`, dim values per node (a 2D mesh's in `plane`, null for z = 0), in space.
void set_high_order_coordinates(HighOrderNodes& nodes, int dim, const PlaneEmbedding* plane,
                                std::span<const double> x);
// The inverse of curved_point_coordinates: the vertices and high-order nodes moved to `x`.
void set_curved_point_coordinates(InputMesh& mesh, std::span<const double> x);
// For the readers, after number_used_vertices: throws Error naming `file` unless the high-order
// nodes of a 2D mesh lie in the plane of its vertices (a curved surface mesh is not read).
void check_high_order_nodes(const InputMesh& mesh, const std::string& file);

// How messages name cell `c`: "cell 12 (0-based; element 40 of the file)", or "cell 12
// (0-based)" without element numbers. Users find the element number in Gmsh.
std::string describe_cell(const InputMesh& mesh, PetscInt c);

}  // namespace neomesh
