#include "mesh/validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <fmt/format.h>

#include "core/collective_error.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/surface_defects.hpp"

namespace neomesh {

namespace {

// Below this scaled Jacobian a cell counts as degenerate: its volume is rounding noise.
constexpr double kDegenerateJacobian = 1e-12;

double norm(const double* a, int dim) {
  double s = 0;
  for (int d = 0; d < dim; ++d) s += a[d] * a[d];
  return std::sqrt(s);
}

// det[e0, e1(, e2)] / (|e0| |e1| (|e2|)): the sine-like corner quality of edges from a vertex.
double scaled_det(const double (*e)[3], int dim) {
  double det = dim == 2 ? e[0][0] * e[1][1] - e[0][1] * e[1][0]
                        : e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                              e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                              e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  double scale = 1;
  for (int i = 0; i < dim; ++i) scale *= norm(e[i], dim);
  return scale > 0 ? det / scale : 0.0;
}

}  // namespace

namespace {

// The smallest and largest scaled corner Jacobian of a cell (see min_scaled_corner_jacobian),
// over the corner frames of the cell-type table.
std::pair<double, double> scaled_corner_jacobians(CellType type, const double* x) {
  const CellFacts& cell = facts(type);
  const int dim = cell.dim;
  double e[3][3] = {};
  double worst = INFINITY, best = -INFINITY;
  for (int k = 0; k < cell.num_corners; ++k) {
    const CornerFrame& frame = cell.corners[k];
    const double* origin = x + frame.vertex * dim;
    for (int j = 0; j < dim; ++j) {
      const double* end = x + frame.ends[j] * dim;
      const double sign = (frame.flip >> j) & 1 ? -1.0 : 1.0;
      for (int d = 0; d < dim; ++d) e[j][d] = sign * (end[d] - origin[d]);
    }
    const double q = scaled_det(e, dim);
    worst = std::min(worst, q);
    best = std::max(best, q);
  }
  return {worst, best};
}

// The cell's vertex coordinates (canonical order) into x; false if a vertex index is invalid.
bool cell_coordinates(const InputMesh& mesh, PetscInt c, double* x) {
  const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
  const int n = num_vertices(mesh.cell_types[c]);
  const int d = mesh.coord_dim();
  if (dimension(mesh.cell_types[c]) != mesh.dim) return false;
  for (int i = 0; i < n; ++i) {
    if (cell[i] < 0 || cell[i] >= mesh.num_vertices()) return false;
    std::copy_n(mesh.coords.data() + cell[i] * d, d, x + i * d);
  }
  return true;
}

// A surface cell's smallest scaled corner Jacobian seen along its own reference normal (a
// triangle's edge cross product, a quadrilateral's Newell normal, the cross product of its
// diagonals): ≤ 0 for a quadrilateral with a reflex or flat corner and for a cell without area.
// x: 3 coordinates per vertex, canonical order.
double min_scaled_surface_corner_jacobian(CellType type, const double* x) {
  const auto minus = [](const double* a, const double* b) {
    return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  const auto cross = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                 a[0] * b[1] - a[1] * b[0]};
  };
  const auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  const CellFacts& cell = facts(type);
  const std::array<double, 3> n = type == CellType::Triangle
                                      ? cross(minus(x + 3, x), minus(x + 6, x))
                                      : cross(minus(x + 9, x), minus(x + 6, x + 3));
  const double length = std::sqrt(dot(n, n));
  if (!(length > 0)) return 0.0;
  double worst = INFINITY;
  for (int k = 0; k < cell.num_corners; ++k) {
    const CornerFrame& frame = cell.corners[k];
    std::array<double, 3> e[2];
    for (int j = 0; j < 2; ++j) {
      e[j] = minus(x + 3 * frame.ends[j], x + 3 * frame.vertex);
      if ((frame.flip >> j) & 1)
        for (double& v : e[j]) v = -v;
    }
    const double scale = std::sqrt(dot(e[0], e[0]) * dot(e[1], e[1])) * length;
    worst = std::min(worst, scale > 0 ? dot(cross(e[0], e[1]), n) / scale : 0.0);
  }
  return worst;
}

// Mirrors a cell's local order by the table's renumbering (for simplices two vertices
// swapped, for tensor order the reference cell reflected in ξ_0), which negates every corner
// Jacobian.
void mirror(CellType type, PetscInt* cell) {
  PetscInt in[8];
  std::copy_n(cell, num_vertices(type), in);
  for (int i = 0; i < num_vertices(type); ++i) cell[i] = in[facts(type).mirror[i]];
}

// The corners (bit i: Gmsh's corner i) that each node of a curved cell after its corners lies
// between, in Gmsh's order (curved_cell.hpp): its edge, its quadrilateral face or, for the
// centre, all.
constexpr std::uint8_t kTriangleNodes[] = {0x3, 0x6, 0x5};
constexpr std::uint8_t kQuadrilateralNodes[] = {0x3, 0x6, 0xC, 0x9, 0xF};
constexpr std::uint8_t kTetrahedronNodes[] = {0x3, 0x6, 0x5, 0x9, 0xC, 0xA};
constexpr std::uint8_t kHexahedronNodes[] = {0x03, 0x09, 0x11, 0x06, 0x22, 0x0C, 0x44,
                                             0x88, 0x30, 0x90, 0x60, 0xC0, 0x0F, 0x33,
                                             0x99, 0x66, 0xCC, 0xF0, 0xFF};
constexpr const std::uint8_t* node_corners(CellType linear) {
  return linear == CellType::Triangle        ? kTriangleNodes
         : linear == CellType::Quadrilateral ? kQuadrilateralNodes
         : linear == CellType::Tetrahedron   ? kTetrahedronNodes
                                             : kHexahedronNodes;
}

// The vertices a node lies between, sorted (then -1), from the cell's corners in Gmsh's order.
std::array<PetscInt, 8> node_key(std::uint8_t corners, const PetscInt* gmsh) {
  std::array<PetscInt, 8> key;
  key.fill(-1);
  int n = 0;
  for (int i = 0; i < 8; ++i) {  // by insertion (GCC 12 warns wrongly about std::sort here)
    if (!(corners >> i & 1)) continue;
    int j = n++;
    for (; j > 0 && key[j - 1] > gmsh[i]; --j) key[j] = key[j - 1];
    key[j] = gmsh[i];
  }
  return key;
}

// Mirrors cell `c` (mirror()), and a curved cell's other nodes with it: each goes where the
// vertices it lies between are in the mirrored cell.
void mirror_cell(InputMesh& mesh, PetscInt c) {
  const CellType type = mesh.cell_types[c];
  PetscInt* v = mesh.cell_vertices.data() + mesh.cell_offsets[c];
  PetscInt before[8], after[8];  // the corners in Gmsh's order
  for (int i = 0; i < num_vertices(type); ++i) before[i] = v[facts(type).gmsh_order[i]];
  mirror(type, v);
  if (!mesh.curved()) return;
  for (int i = 0; i < num_vertices(type); ++i) after[i] = v[facts(type).gmsh_order[i]];
  PetscInt* nodes = mesh.high_order.nodes.data() + mesh.high_order.offsets[c];
  const int n = static_cast<int>(mesh.high_order.offsets[c + 1] - mesh.high_order.offsets[c]);
  const std::uint8_t* corners = node_corners(type);
  PetscInt old[kMaxCurvedNodes];
  std::copy_n(nodes, n, old);
  for (int p = 0; p < n; ++p)
    for (int q = 0; q < n; ++q)
      if (node_key(corners[p], after) == node_key(corners[q], before)) nodes[p] = old[q];
}

// One facet of a cell: its sorted vertices (then -1), the cell, and which way the cell runs
// around it (the facet's vertex cycle as seen from the cell, relative to the sorted order).
struct FacetSide {
  std::array<PetscInt, 4> key;
  PetscInt cell;
  bool forward;
};

FacetSide facet_side(const PetscInt* v, int n, PetscInt cell) {
  FacetSide side{{-1, -1, -1, -1}, cell, v[0] < v[1]};
  if (n >= 3) {  // the cycle's direction at its smallest vertex
    const int m = static_cast<int>(std::min_element(v, v + n) - v);
    side.forward = v[(m + 1) % n] < v[(m + n - 1) % n];
  }
  for (int i = 0; i < n && i < 4; ++i) {  // insertion sort: n ≤ 4
    int j = i;
    for (; j > 0 && side.key[j - 1] > v[i]; --j) side.key[j] = side.key[j - 1];
    side.key[j] = v[i];
  }
  return side;
}

}  // namespace

double min_scaled_corner_jacobian(CellType type, const double* x) {
  return scaled_corner_jacobians(type, x).first;
}

std::vector<PetscInt> orient_mirrored_cells(InputMesh& mesh) {
  // A surface cell faces the side it is listed towards: no orientation is wrong by itself
  // (find_surface_edge_defect finds neighbours that disagree).
  if (mesh.surface) return {};
  // Cell by cell on every thread (a mirror changes only its own cell); then the list in order.
  std::vector<std::uint8_t> flipped(mesh.num_cells(), 0);
#pragma omp parallel for schedule(static)
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    double x[8 * 3];
    if (!cell_coordinates(mesh, c, x)) continue;  // find_defect names it
    if (scaled_corner_jacobians(mesh.cell_types[c], x).second >= -kDegenerateJacobian) continue;
    mirror_cell(mesh, c);
    flipped[c] = 1;
  }
  std::vector<PetscInt> mirrored;
  for (PetscInt c = 0; c < mesh.num_cells(); ++c)
    if (flipped[c]) mirrored.push_back(c);
  return mirrored;
}

std::string find_fold(const InputMesh& mesh, const std::vector<PetscInt>& mirrored) {
  // A cell's facets (CellFacts::facets, DMPlex's) all run the same way around the cell,
  // and cones of positively oriented cells all have the same orientation: two cells on opposite
  // sides of a facet run around it in opposite directions.
  struct KeyHash {
    std::size_t operator()(const std::array<PetscInt, 4>& k) const {
      std::size_t h = 0;
      for (PetscInt v : k) h = h * 1000003u ^ static_cast<std::size_t>(v);
      return h;
    }
  };
  std::unordered_map<std::array<PetscInt, 4>, std::pair<PetscInt, bool>, KeyHash> first_side;
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellType type = mesh.cell_types[c];
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    for (int f = 0; f < facts(type).num_facets; ++f) {
      const FacetVertices& local = facts(type).facets[f];
      PetscInt v[4] = {};
      for (int j = 0; j < local.size; ++j) v[j] = cell[local.vertices[j]];
      const FacetSide side = facet_side(v, local.size, c);
      const auto [it, inserted] = first_side.try_emplace(side.key, c, side.forward);
      if (inserted || it->second.second != side.forward) continue;
      // Name the cell that was mirrored (it is the one that folds over), else the later one.
      const PetscInt a = it->second.first;
      const bool a_mirrored = std::binary_search(mirrored.begin(), mirrored.end(), a);
      const PetscInt folded = a_mirrored ? a : c, other = a_mirrored ? c : a;
      return fmt::format("{}, a {}, is inverted (it folds over {})", describe_cell(mesh, folded),
                         name(mesh.cell_types[folded]), describe_cell(mesh, other));
    }
  }
  return "";
}

std::string find_defect(const InputMesh& mesh, bool keep_inverted) {
  const PetscInt nv = mesh.num_vertices();
  const int dim = mesh.coord_dim();
  for (PetscInt v = 0; v < nv; ++v)
    for (int d = 0; d < dim; ++d)
      if (!std::isfinite(mesh.coords[v * dim + d]))
        return fmt::format("vertex {} (0-based) has a non-finite coordinate ({})", v,
                           mesh.coords[v * dim + d]);
  for (const VertexSet& set : mesh.vertex_sets)
    for (auto v : set.vertices)
      if (v < 0 || v >= nv)
        return fmt::format("boundary part '{}' refers to vertex {}, but there are {} vertices",
                           set.name, v, nv);
  // Each cell's quality on every thread first (most of the work); the checks below go in order,
  // so that the first defect is the one named.
  std::vector<double> quality(mesh.num_cells(), 0.0);
#pragma omp parallel for schedule(static)
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    double x[8 * 3];
    if (cell_coordinates(mesh, c, x))
      quality[c] = mesh.surface ? min_scaled_surface_corner_jacobian(mesh.cell_types[c], x)
                                : min_scaled_corner_jacobian(mesh.cell_types[c], x);
  }
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellType type = mesh.cell_types[c];
    if (dimension(type) != mesh.dim)
      return fmt::format("{} is a {} in a {}D mesh", describe_cell(mesh, c), name(type), mesh.dim);
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    const int n = num_vertices(type);
    for (int i = 0; i < n; ++i) {
      if (cell[i] < 0 || cell[i] >= nv)
        return fmt::format("{} refers to vertex {}, but there are {} vertices",
                           describe_cell(mesh, c), cell[i], nv);
      for (int j = 0; j < i; ++j)
        if (cell[i] == cell[j])
          return fmt::format("{} has a repeated vertex ({})", describe_cell(mesh, c), cell[i]);
    }
    const double q = quality[c];
    if (q <= kDegenerateJacobian && !keep_inverted)
      return fmt::format("{}, a {}, is {} (scaled det J = {:.3g})", describe_cell(mesh, c),
                         name(type), q < -kDegenerateJacobian ? "inverted" : "degenerate", q);
  }
  return "";
}

void validate(InputMesh& mesh, const std::string& source, MPI_Comm comm, bool keep_inverted) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string defect;
  if (rank == 0) {
    const std::vector<PetscInt> input_order =
        keep_inverted ? mesh.cell_vertices : std::vector<PetscInt>{};
    const std::vector<PetscInt> input_nodes =
        keep_inverted ? mesh.high_order.nodes : std::vector<PetscInt>{};
    const std::vector<PetscInt> mirrored = orient_mirrored_cells(mesh);
    defect = find_defect(mesh, keep_inverted);
    if (defect.empty() && mesh.surface) defect = find_surface_edge_defect(mesh);
    if (defect.empty() && mesh.surface) defect = find_surface_crossing(mesh);
    // A mirrored cell among cells of the other orientation may be a fold rather than a mirror.
    if (defect.empty() && !mirrored.empty()) {
      const std::string fold = find_fold(mesh, mirrored);
      if (!keep_inverted) {
        defect = fold;
      } else if (!fold.empty()) {
        // The folded cells stay inverted, to be counted or untangled; the orientation of the
        // majority is the mesh's (a mirrored mesh with a few folds is mirrored as a whole).
        mesh.cell_vertices = input_order;
        mesh.high_order.nodes = input_nodes;
        if (2 * static_cast<PetscInt>(mirrored.size()) > mesh.num_cells())
          for (PetscInt c = 0; c < mesh.num_cells(); ++c) mirror_cell(mesh, c);
      }
    }
  }
  throw_if_any(comm, defect.empty() ? "" : source + ": " + defect);
}

}  // namespace neomesh
