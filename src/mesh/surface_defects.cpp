#include "mesh/surface_defects.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "mesh/cell_type.hpp"

namespace neomesh {

namespace {

// How many cells a message lists before "...".
constexpr std::size_t kCellsListed = 4;
// Below this distance from a triangle's plane, relative to the size of the two triangles
// tested, a point counts as on the plane: an edge crosses the plane only if its ends are
// farther on either side, and a triangle whose vertices are all this near lies in the plane.
constexpr double kPlaneTolerance = 1e-9;
// Barycentric coordinates and 2D orientations (relative to the triangles' squared size) above
// this count as strictly inside: the crossings found are proper ones, not round-off.
constexpr double kInsideTolerance = 1e-12;

using Vec = Eigen::Vector3d;

std::span<const PetscInt> cell_of(const InputMesh& mesh, PetscInt c) {
  return {mesh.cell_vertices.data() + mesh.cell_offsets[c],
          static_cast<std::size_t>(mesh.cell_offsets[c + 1] - mesh.cell_offsets[c])};
}

// The local vertex at position i of the cell's cycle (its edges' first ends, in order).
int cycle_vertex(CellType type, int i) {
  return facts(type).facets[i].vertices[0];
}

// "3, 8 and 11, 0-based; elements 4, 9 and 12 of the file": the first kCellsListed.
std::string describe_cells(const InputMesh& mesh, const std::vector<PetscInt>& cells) {
  const std::size_t n = std::min(cells.size(), kCellsListed);
  const auto list = [&](auto number) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i)
      s += fmt::format("{}{}",
                       i == 0                            ? ""
                       : i + 1 == n && n == cells.size() ? " and "
                                                         : ", ",
                       number(cells[i]));
    return s + (n < cells.size() ? ", ..." : "");
  };
  const std::string numbers = list([](PetscInt c) { return c; });
  if (mesh.element_tag.size() != static_cast<std::size_t>(mesh.num_cells()))
    return fmt::format("{}, 0-based", numbers);
  return fmt::format("{}, 0-based; elements {} of the file", numbers,
                     list([&](PetscInt c) { return mesh.element_tag[c]; }));
}

// ---- Edges -------------------------------------------------------------------------------

// One cell's edge: its ends, smaller first, and whether the cell runs along it from `low`.
struct EdgeSide {
  PetscInt low, high, cell;
  bool forward;
};

std::vector<EdgeSide> edge_sides(const InputMesh& mesh) {
  std::vector<EdgeSide> sides;
  sides.reserve(mesh.cell_vertices.size());
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const auto cell = cell_of(mesh, c);
    const CellType type = mesh.cell_types[c];
    for (int i = 0, n = facts(type).num_facets; i < n; ++i) {
      const PetscInt from = cell[cycle_vertex(type, i)], to = cell[cycle_vertex(type, (i + 1) % n)];
      sides.push_back({std::min(from, to), std::max(from, to), c, from < to});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const EdgeSide& a, const EdgeSide& b) {
    return std::tie(a.low, a.high, a.cell) < std::tie(b.low, b.high, b.cell);
  });
  return sides;
}

}  // namespace

std::string find_surface_edge_defect(const InputMesh& mesh) {
  const std::vector<EdgeSide> sides = edge_sides(mesh);
  std::string misoriented;  // the first, reported if no edge has more than two cells
  for (std::size_t i = 0, j = 0; i < sides.size(); i = j) {
    for (j = i + 1;
         j < sides.size() && sides[j].low == sides[i].low && sides[j].high == sides[i].high; ++j) {
    }
    const EdgeSide& a = sides[i];
    if (j - i > 2) {
      std::vector<PetscInt> cells;
      for (std::size_t k = i; k < j; ++k) cells.push_back(sides[k].cell);
      return fmt::format(
          "the edge between vertices {} and {} (0-based) is shared by {} cells ({}), where an "
          "edge of a surface belongs to one cell or two",
          a.low, a.high, j - i, describe_cells(mesh, cells));
    }
    if (j - i == 2 && a.forward == sides[i + 1].forward && misoriented.empty()) {
      const PetscInt from = a.forward ? a.low : a.high, to = a.forward ? a.high : a.low;
      misoriented = fmt::format(
          "its cells are not oriented alike: {} and {} both run from vertex {} to vertex {} "
          "(0-based) along their common edge, so they face opposite sides",
          describe_cell(mesh, a.cell), describe_cell(mesh, sides[i + 1].cell), from, to);
    }
  }
  return misoriented;
}

namespace {

// ---- Crossings ---------------------------------------------------------------------------

using Triangle = std::array<Vec, 3>;

// Whether the segment pq crosses the plane of `t` (normal n, |n|² = nn) beyond `tolerance`
// on either side, at a point strictly inside `t`.
bool segment_crosses(const Vec& p, const Vec& q, const Triangle& t, const Vec& n, double nn,
                     double tolerance) {
  const double length = std::sqrt(nn);
  const double dp = n.dot(p - t[0]) / length, dq = n.dot(q - t[0]) / length;
  if (!((dp > tolerance && dq < -tolerance) || (dp < -tolerance && dq > tolerance))) return false;
  const double s = dp / (dp - dq);
  const Vec x = p + s * (q - p);
  for (int k = 0; k < 3; ++k)  // barycentric coordinate of the vertex opposite edge k
    if (n.dot((t[(k + 1) % 3] - t[k]).cross(x - t[k])) / nn <= kInsideTolerance) return false;
  return true;
}

// 2D orientation of (a, b, c) in the coordinate plane (i, j).
double orient2d(const Vec& a, const Vec& b, const Vec& c, int i, int j) {
  return (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]);
}

// Two triangles in one plane (normal n) overlap: two edges cross, or a vertex of one lies
// strictly inside the other. `area` is the scale (squared size) orientations are judged by.
bool coplanar_overlap(const Triangle& a, const Triangle& b, const Vec& n, double area) {
  int axis = 0;  // drop the normal's largest component: project onto the other two
  for (int d = 1; d < 3; ++d)
    if (std::abs(n[d]) > std::abs(n[axis])) axis = d;
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  const double tol = kInsideTolerance * area;
  const auto sign = [&](double v) { return v > tol ? 1 : v < -tol ? -1 : 0; };
  for (int e = 0; e < 3; ++e)
    for (int f = 0; f < 3; ++f) {
      const Vec &p = a[e], &q = a[(e + 1) % 3], &r = b[f], &s = b[(f + 1) % 3];
      const int s1 = sign(orient2d(p, q, r, i, j)), s2 = sign(orient2d(p, q, s, i, j));
      const int s3 = sign(orient2d(r, s, p, i, j)), s4 = sign(orient2d(r, s, q, i, j));
      if (s1 * s2 < 0 && s3 * s4 < 0) return true;
    }
  const auto inside = [&](const Triangle& t, const Vec& x) {
    const int o = sign(orient2d(t[0], t[1], t[2], i, j));
    for (int k = 0; k < 3; ++k)
      if (sign(orient2d(t[k], t[(k + 1) % 3], x, i, j)) != o || o == 0) return false;
    return true;
  };
  return inside(a, b[0]) || inside(b, a[0]);
}

// Whether two triangles cross (see find_surface_crossing). `size`: their bounding box's
// largest extent.
bool triangles_cross(const Triangle& a, const Triangle& b, double size) {
  const Vec na = (a[1] - a[0]).cross(a[2] - a[0]);
  const Vec nb = (b[1] - b[0]).cross(b[2] - b[0]);
  const double naa = na.squaredNorm(), nbb = nb.squaredNorm();
  if (!(naa > 0) || !(nbb > 0)) return false;  // no plane: a degenerate cell, reported elsewhere
  const double tolerance = kPlaneTolerance * size;
  bool coplanar = true;
  for (const Vec& p : b)
    coplanar = coplanar && std::abs(na.dot(p - a[0])) <= tolerance * std::sqrt(naa);
  if (coplanar) return coplanar_overlap(a, b, na, size * size);
  for (int e = 0; e < 3; ++e)
    if (segment_crosses(a[e], a[(e + 1) % 3], b, nb, nbb, tolerance) ||
        segment_crosses(b[e], b[(e + 1) % 3], a, na, naa, tolerance))
      return true;
  return false;
}

struct Box {
  Vec low = Vec::Constant(INFINITY), high = Vec::Constant(-INFINITY);
  void add(const Vec& p) { low = low.cwiseMin(p), high = high.cwiseMax(p); }
  bool overlaps(const Box& o) const {
    for (int d = 0; d < 3; ++d)
      if (low[d] > o.high[d] || o.low[d] > high[d]) return false;
    return true;
  }
  double extent() const { return (high - low).maxCoeff(); }
};

// The surface's cells as triangles and boxes, ready for pair tests.
class CrossingTest {
 public:
  explicit CrossingTest(const InputMesh& mesh) : mesh_(mesh), boxes_(mesh.num_cells()) {
    for (PetscInt c = 0; c < mesh.num_cells(); ++c)
      for (PetscInt v : cell_of(mesh, c)) boxes_[c].add(point(v));
  }

  const Box& box(PetscInt c) const { return boxes_[c]; }

  // Whether cells a and b, whose boxes overlap, cross.
  bool cross(PetscInt a, PetscInt b) const {
    const auto va = cell_of(mesh_, a), vb = cell_of(mesh_, b);
    for (PetscInt u : va)
      if (std::find(vb.begin(), vb.end(), u) != vb.end()) return false;
    Box both = boxes_[a];
    both.add(boxes_[b].low), both.add(boxes_[b].high);
    const double size = both.extent();
    std::array<Triangle, 2> ta, tb;
    const int na = triangles(a, ta), nb = triangles(b, tb);
    for (int i = 0; i < na; ++i)
      for (int j = 0; j < nb; ++j)
        if (triangles_cross(ta[i], tb[j], size)) return true;
    return false;
  }

 private:
  Vec point(PetscInt v) const { return Vec(mesh_.coords.data() + 3 * v); }

  // A triangle as itself; a quadrilateral (cycle c0 c1 c2 c3) as c0 c1 c2 and c0 c2 c3. Returns
  // their number.
  int triangles(PetscInt c, std::array<Triangle, 2>& out) const {
    const auto cell = cell_of(mesh_, c);
    const CellType type = mesh_.cell_types[c];
    const auto at = [&](int i) { return point(cell[cycle_vertex(type, i)]); };
    out[0] = {at(0), at(1), at(2)};
    if (type == CellType::Triangle) return 1;
    out[1] = {at(0), at(2), at(3)};
    return 2;
  }

  const InputMesh& mesh_;
  std::vector<Box> boxes_;
};

// A uniform grid over the surface's bounding box, bins about the mean cell's size.
struct Grid {
  Box box;
  double bin = 1;
  std::array<std::int64_t, 3> count{1, 1, 1};

  std::int64_t index(double x, int d) const {
    return std::clamp(static_cast<std::int64_t>((x - box.low[d]) / bin), std::int64_t{0},
                      count[d] - 1);
  }
  std::int64_t linear(const std::array<std::int64_t, 3>& i) const {
    return (i[2] * count[1] + i[1]) * count[0] + i[0];
  }
};

Grid make_grid(const CrossingTest& test, PetscInt num_cells) {
  // Bins per axis are capped so that a bin's index fits in 30 bits (find_surface_crossing packs
  // it with a cell number, below 2³²). Bins 1.5 times the mean cell's size hold a few more pairs
  // each than bins of that size, but give fewer (bin, cell) entries to sort: on
  // Mesquite_geo_10242 3.5 per cell instead of 5.6.
  constexpr std::int64_t kMaxBinsPerAxis = 1 << 10;
  constexpr double kBinsPerMeanCell = 1.5;
  Grid grid;
  double mean = 0;
  for (PetscInt c = 0; c < num_cells; ++c) {
    grid.box.add(test.box(c).low), grid.box.add(test.box(c).high);
    mean += test.box(c).extent() / num_cells;
  }
  grid.bin = std::max(kBinsPerMeanCell * mean, grid.box.extent() / kMaxBinsPerAxis);
  if (!(grid.bin > 0)) return grid;
  for (int d = 0; d < 3; ++d)
    grid.count[d] = std::max<std::int64_t>(
        1, static_cast<std::int64_t>((grid.box.high[d] - grid.box.low[d]) / grid.bin) + 1);
  return grid;
}

}  // namespace

std::string find_surface_crossing(const InputMesh& mesh) {
  constexpr std::uint64_t kCellBits = 0xffffffffu;
  const PetscInt nc = mesh.num_cells();
  if (nc < 2) return "";
  const CrossingTest test(mesh);
  const Grid grid = make_grid(test, nc);
  // Every (bin, cell) with the cell's box over the bin, as bin << 32 | cell, sorted by bin.
  std::vector<std::uint64_t> binned;
  binned.reserve(2 * static_cast<std::size_t>(nc));
  for (PetscInt c = 0; c < nc; ++c) {
    std::array<std::int64_t, 3> lo, hi, i;
    for (int d = 0; d < 3; ++d)
      lo[d] = grid.index(test.box(c).low[d], d), hi[d] = grid.index(test.box(c).high[d], d);
    for (i[2] = lo[2]; i[2] <= hi[2]; ++i[2])
      for (i[1] = lo[1]; i[1] <= hi[1]; ++i[1])
        for (i[0] = lo[0]; i[0] <= hi[0]; ++i[0])
          binned.push_back(static_cast<std::uint64_t>(grid.linear(i)) << 32 |
                           static_cast<std::uint64_t>(c));
  }
  std::sort(binned.begin(), binned.end());
  // Pairs in a bin; a pair whose boxes share several bins is tested in the one holding the low
  // corner of their boxes' overlap.
  PetscInt first = -1, second = -1;
  for (std::size_t i = 0, j = 0; i < binned.size(); i = j) {
    for (j = i + 1; j < binned.size() && binned[j] >> 32 == binned[i] >> 32; ++j) {
    }
    for (std::size_t k = i; k < j; ++k)
      for (std::size_t l = k + 1; l < j; ++l) {
        const auto a = static_cast<PetscInt>(binned[k] & kCellBits);  // a < b
        const auto b = static_cast<PetscInt>(binned[l] & kCellBits);
        if (first >= 0 && std::pair(a, b) >= std::pair(first, second)) continue;
        const Box &ba = test.box(a), &bb = test.box(b);
        if (!ba.overlaps(bb)) continue;
        std::array<std::int64_t, 3> corner;
        for (int d = 0; d < 3; ++d) corner[d] = grid.index(std::max(ba.low[d], bb.low[d]), d);
        if (static_cast<std::uint64_t>(grid.linear(corner)) != binned[i] >> 32 || !test.cross(a, b))
          continue;
        first = a, second = b;
      }
  }
  if (first < 0) return "";
  return fmt::format("the surface crosses itself: {} and {} intersect without sharing a vertex",
                     describe_cell(mesh, first), describe_cell(mesh, second));
}

}  // namespace neomesh
