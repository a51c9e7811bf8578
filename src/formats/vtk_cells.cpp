#include "formats/vtk_cells.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "mesh/cell_order.hpp"
#include "mesh/curved_type.hpp"

namespace neomesh {

namespace {

constexpr VtkType kVtkTypes[] = {{0, -1, 1, 0, std::nullopt, "empty cell"},
                                 {1, 0, 1, 1, std::nullopt, "vertex"},
                                 {kPolyVertex, 0, 1, -1, std::nullopt, "poly-vertex"},
                                 {3, 1, 1, 2, std::nullopt, "line"},
                                 {kPolyLine, 1, 1, -1, std::nullopt, "poly-line"},
                                 {5, 2, 1, 3, CellType::Triangle, "triangle"},
                                 {kStrip, 2, 1, -1, std::nullopt, "triangle strip"},
                                 {kPolygon, 2, 1, -1, std::nullopt, "polygon"},
                                 {kPixel, 2, 1, 4, CellType::Quadrilateral, "pixel"},
                                 {9, 2, 1, 4, CellType::Quadrilateral, "quadrilateral"},
                                 {10, 3, 1, 4, CellType::Tetrahedron, "tetrahedron"},
                                 {kVoxel, 3, 1, 8, CellType::Hexahedron, "voxel"},
                                 {12, 3, 1, 8, CellType::Hexahedron, "hexahedron"},
                                 {13, 3, 1, 6, CellType::Wedge, "wedge"},
                                 {14, 3, 1, 5, CellType::Pyramid, "pyramid"},
                                 {15, 3, 1, 10, std::nullopt, "pentagonal prism"},
                                 {16, 3, 1, 12, std::nullopt, "hexagonal prism"},
                                 {21, 1, 2, 3, std::nullopt, "quadratic edge"},
                                 {22, 2, 2, 6, std::nullopt, "quadratic triangle"},
                                 {23, 2, 2, 8, std::nullopt, "quadratic quadrilateral"},
                                 {24, 3, 2, 10, std::nullopt, "quadratic tetrahedron"},
                                 {25, 3, 2, 20, std::nullopt, "quadratic hexahedron"},
                                 {26, 3, 2, 15, std::nullopt, "quadratic wedge"},
                                 {27, 3, 2, 13, std::nullopt, "quadratic pyramid"},
                                 {28, 2, 2, 9, std::nullopt, "biquadratic quadrilateral"},
                                 {29, 3, 2, 27, std::nullopt, "triquadratic hexahedron"},
                                 {30, 2, 2, 6, std::nullopt, "quadratic-linear quadrilateral"},
                                 {31, 3, 2, 12, std::nullopt, "quadratic-linear wedge"},
                                 {32, 3, 2, 18, std::nullopt, "biquadratic-quadratic wedge"},
                                 {33, 3, 2, 24, std::nullopt, "biquadratic-quadratic hexahedron"},
                                 {34, 2, 2, 7, std::nullopt, "biquadratic triangle"},
                                 {35, 1, 3, 4, std::nullopt, "cubic line"},
                                 {36, 2, 2, -1, std::nullopt, "quadratic polygon"},
                                 {42, 3, 1, -1, std::nullopt, "polyhedron"},
                                 {68, 1, 2, -1, std::nullopt, "Lagrange curve"},
                                 {69, 2, 2, -1, std::nullopt, "Lagrange triangle"},
                                 {70, 2, 2, -1, std::nullopt, "Lagrange quadrilateral"},
                                 {71, 3, 2, -1, std::nullopt, "Lagrange tetrahedron"},
                                 {72, 3, 2, -1, std::nullopt, "Lagrange hexahedron"},
                                 {73, 3, 2, -1, std::nullopt, "Lagrange wedge"},
                                 {74, 3, 2, -1, std::nullopt, "Lagrange pyramid"},
                                 {75, 1, 2, -1, std::nullopt, "Bezier curve"},
                                 {76, 2, 2, -1, std::nullopt, "Bezier triangle"},
                                 {77, 2, 2, -1, std::nullopt, "Bezier quadrilateral"},
                                 {78, 3, 2, -1, std::nullopt, "Bezier tetrahedron"},
                                 {79, 3, 2, -1, std::nullopt, "Bezier hexahedron"},
                                 {80, 3, 2, -1, std::nullopt, "Bezier wedge"},
                                 {81, 3, 2, -1, std::nullopt, "Bezier pyramid"}};

}  // namespace

const VtkType* vtk_type(long long vtk) {
  for (const VtkType& t : kVtkTypes)
    if (t.vtk == vtk) return &t;
  return nullptr;
}

namespace {

// A cell of the file as neomesh's cell type, or nothing for a lower-dimensional element.
std::optional<CellType> cell_type(const VtkType& t, std::int64_t vertices) {
  if (t.vtk != kPolygon) return t.cell;
  return vertices == 3 ? CellType::Triangle : CellType::Quadrilateral;
}

// A second-order cell of the file as a curved type: a quadratic cell, or a Lagrange cell of
// order 2 (known by its number of points); none for others.
std::optional<CurvedType> curved_type(const VtkType& t, std::int64_t points) {
  for (CurvedType type : kCurvedTypes) {
    const CurvedFacts& f = facts(type);
    if (t.vtk == f.vtk || (t.vtk == f.vtk_lagrange && points == f.nodes)) return type;
  }
  return std::nullopt;
}

// The number of corners of an element of the file that can be a facet (first order, or second
// order with its corners first), or 0.
int facet_corners(const VtkType& t, std::int64_t points) {
  if (t.order == 1) {
    if (t.vertices > 0) return t.vertices;
    return t.vtk == kPolygon && (points == 3 || points == 4) ? static_cast<int>(points) : 0;
  }
  if (t.vtk == 21 || (t.vtk == 68 && points == 3)) return 2;  // quadratic edge
  if (const auto type = curved_type(t, points); type && dimension(facts(*type).linear) == 2)
    return num_vertices(facts(*type).linear);
  return 0;
}

// The dimension of the cells of the highest dimension, which are the cells; throws Error unless
// they are 2D or 3D cells neomesh reads, all of first or all of second order.
int cell_dimension(const VtkCells& c, const std::string& file) {
  if (c.types.empty()) fail("{}: has no cells", file);
  int dim = -1;
  for (int type : c.types) dim = std::max(dim, vtk_type(type)->dim);
  if (dim < 2)
    fail(
        "{}: has no 2D or 3D cells (only {}D elements); neomesh needs triangles, "
        "quadrilaterals, tetrahedra, hexahedra, wedges or pyramids",
        file, std::max(dim, 0));
  std::optional<std::size_t> first_order, second_order;  // a cell of each
  for (std::size_t i = 0; i < c.types.size(); ++i) {
    const VtkType& t = *vtk_type(c.types[i]);
    if (t.dim != dim) continue;
    const std::int64_t vertices = c.offsets[i + 1] - c.offsets[i];
    (t.order > 1 ? second_order : first_order) = i;
    if (first_order && second_order)
      fail(
          "{}: mixes first-order cells (cell {}) and second-order ones (cell {}); neomesh reads "
          "meshes of one order",
          file, *first_order, *second_order);
    if (t.order > 1) {
      if (!curved_type(t, vertices))
        fail(
            "{}: cell {} (0-based) is a {} of {} points; of the second-order cells neomesh reads "
            "triangles (6 points), quadrilaterals (8, 9), tetrahedra (10), hexahedra (20, 27) "
            "and wedges (15, 18)",
            file, i, t.name, vertices);
      continue;
    }
    if (t.vtk == kPolygon && (vertices < 3 || vertices > 4))
      fail("{}: cell {} (0-based) is a polygon of {} vertices; neomesh reads polygons of 3 or 4",
           file, i, vertices);
    if (!cell_type(t, vertices))
      fail(
          "{}: cell {} (0-based) is a {}; neomesh supports triangles, quadrilaterals, "
          "tetrahedra, hexahedra, wedges and pyramids",
          file, i, t.name);
  }
  return dim;
}

// The number of corners of cell `i` of the file (all its points for a first-order cell).
int num_corners(const VtkCells& c, std::size_t i) {
  const VtkType& t = *vtk_type(c.types[i]);
  const std::int64_t n = c.offsets[i + 1] - c.offsets[i];
  if (t.order == 1) return static_cast<int>(n);
  return num_vertices(facts(*curved_type(t, n)).linear);
}

// Cell `i`'s points after its corners into mesh.high_order, in Gmsh order.
void add_high_order_nodes(const VtkCells& c, std::size_t i, const std::vector<PetscInt>& node,
                          InputMesh& mesh) {
  const std::int64_t* points = c.points.data() + c.offsets[i];
  const int n = static_cast<int>(c.offsets[i + 1] - c.offsets[i]);
  const CurvedType type = *curved_type(*vtk_type(c.types[i]), n);
  const int corners = num_vertices(facts(type).linear);
  const bool lagrange = c.types[i] == facts(type).vtk_lagrange;
  const bool old = c.old_lagrange_hexahedra && lagrange && type == CurvedType::Hexahedron27;
  PetscInt gmsh[kMaxCurvedNodes];
  for (int k = corners; k < n; ++k)
    gmsh[vtk_order(type, lagrange)[old ? old_lagrange_hexahedron_position(k) : k]] =
        node[points[k]];
  mesh.high_order.add(type, gmsh + corners);
}

void add_cells(const VtkCells& c, const std::string& file, const std::vector<PetscInt>& vertex,
               const std::vector<PetscInt>& node, InputMesh& mesh) {
  const bool skipped = std::any_of(c.types.begin(), c.types.end(),
                                   [&](int type) { return vtk_type(type)->dim != mesh.dim; });
  for (std::size_t i = 0; i < c.types.size(); ++i) {
    const VtkType& t = *vtk_type(c.types[i]);
    if (t.dim != mesh.dim) continue;
    const std::int64_t* points = c.points.data() + c.offsets[i];
    const int all = static_cast<int>(c.offsets[i + 1] - c.offsets[i]);
    const int n = num_corners(c, i);
    const CellType type = t.order == 1 ? *cell_type(t, n) : facts(*curved_type(t, all)).linear;
    const bool tensor = t.vtk == kPixel || t.vtk == kVoxel;
    PetscInt canonical[8];
    for (int k = 0; k < all; ++k)
      if (std::find(points, points + k, points[k]) != points + k)
        fail("{}: cell {} (0-based) has a repeated vertex", file, i);
    // A second-order cell's corners as its node order says (a Lagrange wedge's are Gmsh's).
    const auto corner = [&](int k) -> int {
      if (t.order == 1) return tensor ? k : vtk_from_canonical(type)[k];
      const CurvedType curved = *curved_type(t, all);
      return gmsh_from_canonical(type)[vtk_order(curved, t.vtk == facts(curved).vtk_lagrange)[k]];
    };
    for (int k = 0; k < n; ++k) canonical[corner(k)] = vertex[points[k]];
    const int tag = c.tags.empty() ? 0 : std::max(c.tags[i], 0);
    mesh.add_cell(type, canonical, tag);
    if (t.order > 1) add_high_order_nodes(c, i, node, mesh);
    // Cells are numbered without the file's lower-dimensional ones: messages give both.
    if (skipped) mesh.element_tag.push_back(static_cast<std::int64_t>(i));
  }
}

// The facets (elements of dimension mesh.dim - 1) with a positive tag.
void add_tagged_elements(const VtkCells& c, const std::string& file,
                         const std::vector<PetscInt>& vertex, InputMesh& mesh) {
  if (c.tags.empty()) return;
  for (std::size_t i = 0; i < c.types.size(); ++i) {
    const VtkType& t = *vtk_type(c.types[i]);
    const int n = t.dim == mesh.dim - 1 ? facet_corners(t, c.offsets[i + 1] - c.offsets[i]) : 0;
    if (c.tags[i] <= 0 || n == 0) continue;
    PetscInt v[4];
    for (int k = 0; k < n; ++k) {
      const std::int64_t p = c.points[c.offsets[i] + (t.vtk == kPixel && k >= 2 ? 5 - k : k)];
      if (vertex[p] < 0)
        fail("{}: element {} (0-based) of group {} is not on the mesh (point {} is on no cell)",
             file, i, c.tags[i], p);
      v[k] = vertex[p];
    }
    mesh.facets.add(v, n, c.tags[i]);
  }
}

}  // namespace

bool group_name_array(const std::vector<double>& values, PhysicalGroup& group) {
  if (values.size() != 2) return false;
  const double tag = values[0], dim = values[1];
  if (!(tag >= 1 && tag < 2147483647.0 && tag == std::floor(tag))) return false;
  if (!(dim >= 0 && dim <= 3 && dim == std::floor(dim))) return false;
  group.tag = static_cast<int>(tag);
  group.dim = static_cast<int>(dim);
  return true;
}

InputMesh input_from_vtk_cells(const VtkCells& c, const std::string& file) {
  InputMesh mesh;
  mesh.dim = cell_dimension(c, file);
  // Vertices are the cells' corners; the other points of second-order cells are their nodes.
  std::vector<PetscInt> vertex(c.xyz.size() / 3, -1), node(c.xyz.size() / 3, -1);
  std::vector<std::int64_t> kept_cells, kept_points;
  for (std::size_t i = 0; i < c.types.size(); ++i)
    if (vtk_type(c.types[i])->dim == mesh.dim) {
      kept_cells.push_back(static_cast<std::int64_t>(i));
      const std::int64_t corners_end = c.offsets[i] + num_corners(c, i);
      for (std::int64_t k = c.offsets[i]; k < c.offsets[i + 1]; ++k)
        (k < corners_end ? vertex : node)[c.points[k]] = 0;
    }
  for (std::size_t p = 0; p < vertex.size(); ++p) {
    if (vertex[p] >= 0) kept_points.push_back(static_cast<std::int64_t>(p));
    if (vertex[p] >= 0 && node[p] >= 0)
      fail(
          "{}: point {} (0-based) is a corner of one cell and a mid-edge, face or centre node of "
          "another",
          file, p);
  }
  number_used_vertices(vertex, c.xyz, file, mesh);
  for (std::size_t p = 0; p < node.size(); ++p)
    if (node[p] >= 0) {
      node[p] = mesh.high_order.num_nodes();
      mesh.high_order.xyz.insert(mesh.high_order.xyz.end(), c.xyz.begin() + 3 * p,
                                 c.xyz.begin() + 3 * p + 3);
    }
  add_cells(c, file, vertex, node, mesh);
  check_high_order_nodes(mesh, file);
  add_tagged_elements(c, file, vertex, mesh);
  // (A curved mesh's point data would need its nodes' values too: it is not carried.)
  if (!mesh.curved()) mesh.point_data = select_data(c.point_data, vertex.size(), kept_points);
  mesh.cell_data = select_data(c.cell_data, c.types.size(), kept_cells);
  std::set<std::pair<int, int>> groups;  // (dim, tag)
  for (int tag : mesh.cell_tags)
    if (tag > 0) groups.emplace(mesh.dim, tag);
  for (int tag : mesh.facets.tags) groups.emplace(mesh.dim - 1, tag);
  std::map<std::pair<int, int>, std::string> names;  // the last name of each group
  for (const PhysicalGroup& g : c.names) names[{g.dim, g.tag}] = g.name;
  for (const auto& [dim, tag] : groups) {
    const auto it = names.find({dim, tag});
    mesh.groups.push_back({dim, tag, it == names.end() ? "" : it->second});
  }
  return mesh;
}

}  // namespace neomesh
