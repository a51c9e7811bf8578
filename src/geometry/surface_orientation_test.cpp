#include "geometry/surface_orientation.hpp"

#include <gtest/gtest.h>

#include "geometry/surface_frame.hpp"

namespace neomesh {
namespace {

// A (n + 1) × (n + 1) grid of points on the gentle bowl z = 0.02 r² about its middle, in
// triangles facing up (+z), with the points `pushed` (grid i, j) moved by (dx, dy) before the
// bowl is lifted: a cell pushed over its neighbours faces down.
struct Bowl {
  static constexpr int n = 6;
  std::vector<double> coords;
  std::vector<PetscInt> offsets{0}, vertices;

  struct Push {
    int i, j;
    double dx, dy;
  };
  explicit Bowl(std::initializer_list<Push> pushed) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) coords.insert(coords.end(), {double(i), double(j), 0.0});
    for (const Push& p : pushed) {
      coords[3 * index(p.i, p.j)] += p.dx;
      coords[3 * index(p.i, p.j) + 1] += p.dy;
    }
    for (std::size_t v = 0; v < coords.size(); v += 3) {
      const double x = coords[v] - n / 2.0, y = coords[v + 1] - n / 2.0;
      coords[v + 2] = 0.02 * (x * x + y * y);
    }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        add({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
        add({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
      }
  }
  static PetscInt index(int i, int j) { return j * (n + 1) + i; }
  void add(std::initializer_list<PetscInt> cell) {
    vertices.insert(vertices.end(), cell);
    offsets.push_back(static_cast<PetscInt>(vertices.size()));
  }
  // Per cell: 1 if it faces down, which a cell of this bowl does only where it is folded.
  std::vector<std::uint8_t> facing_down() const {
    std::vector<std::uint8_t> down;
    for (std::size_t c = 0; c + 1 < offsets.size(); ++c) {
      const auto x = [&](int k) {
        return Vector<3>(Eigen::Map<const Vector<3>>(&coords[3 * vertices[offsets[c] + k]]));
      };
      down.push_back((x(1) - x(0)).cross(x(2) - x(0))[2] < 0.0);
    }
    return down;
  }
  std::vector<std::uint8_t> folded() const {
    return folded_polygons(offsets, vertices, coords, nullptr);
  }
};

TEST(FoldedPolygons, AnUnfoldedBowlHasNone) {
  const Bowl bowl({});
  EXPECT_EQ(bowl.folded(), std::vector<std::uint8_t>(bowl.offsets.size() - 1, 0));
}

TEST(FoldedPolygons, AVertexPushedOverItsNeighboursFoldsTheCellsThatTurnOver) {
  const Bowl bowl({{3, 3, 1.2, 0.0}});
  const std::vector<std::uint8_t> down = bowl.facing_down();
  EXPECT_EQ(std::count(down.begin(), down.end(), 1), 2);
  EXPECT_EQ(bowl.folded(), down);
}

// Two neighbours pushed together fold four cells, two of them with every vertex among the fold's:
// they are found once the fold's rim is.
TEST(FoldedPolygons, AFoldOfSeveralCellsIsFoundFromItsRimInwards) {
  const Bowl bowl({{3, 3, 1.3, 0.0}, {3, 2, 1.3, 0.0}});
  const std::vector<std::uint8_t> down = bowl.facing_down();
  EXPECT_EQ(std::count(down.begin(), down.end(), 1), 4);
  EXPECT_EQ(bowl.folded(), down);
}

// The two faces of a 10° knife edge, one of a single large cell, the other of many small ones
// along the edge: each cell faces as it lies, though the large cell's normal outweighs the small
// cells' by area at the edge's vertices.
TEST(FoldedPolygons, AKnifeEdgeBetweenCellsOfUnequalSizeIsNoFold) {
  const double half = 5.0 * M_PI / 180.0, c = std::cos(half), s = std::sin(half);
  // The edge from (0,0,0) to (1,0,0) split into 8; the upper face reaches (·, c, s), the lower
  // (·, c, −s). Points: edge 0..8, upper row 9..17, lower far corners 18, 19.
  std::vector<double> coords;
  for (int k = 0; k <= 8; ++k) coords.insert(coords.end(), {k / 8.0, 0.0, 0.0});
  for (int k = 0; k <= 8; ++k) coords.insert(coords.end(), {k / 8.0, 0.02 * c, 0.02 * s});
  coords.insert(coords.end(), {0.0, c, -s, 1.0, c, -s});
  std::vector<PetscInt> offsets{0}, vertices;
  const auto add = [&](std::initializer_list<PetscInt> cell) {
    vertices.insert(vertices.end(), cell);
    offsets.push_back(static_cast<PetscInt>(vertices.size()));
  };
  for (PetscInt k = 0; k < 8; ++k) {  // thin upper strip, facing +z
    add({k, k + 1, k + 10});
    add({k, k + 10, k + 9});
  }
  add({0, 18, 19});  // the lower face, facing −z: its first cell runs along the whole edge
  add({0, 19, 8});
  const std::vector<std::uint8_t> folded = folded_polygons(offsets, vertices, coords, nullptr);
  EXPECT_EQ(folded, std::vector<std::uint8_t>(offsets.size() - 1, 0));
}

// The reference normal of an unfolded cell is its own normal to the bit (outputs of unfolded
// meshes stay as they were); a folded cell's is its reverse.
TEST(SurfaceReferenceNormals, AreTheCellsOwnNormalsReversedWhereFolded) {
  const Bowl bowl({{3, 3, 1.2, 0.0}});
  MeshView view;
  view.dim = 3;
  view.surface = true;
  view.num_vertices = static_cast<PetscInt>(bowl.coords.size() / 3);
  view.num_cells = static_cast<PetscInt>(bowl.offsets.size() - 1);
  view.blocks.push_back({CellType::Triangle, 0, bowl.vertices});
  const std::vector<double> normals = surface_reference_normals(view, bowl.coords, nullptr);
  const std::vector<std::uint8_t> down = bowl.facing_down();
  for (PetscInt c = 0; c < view.num_cells; ++c) {
    Eigen::Matrix<double, 3, 3> x;
    for (int i = 0; i < 3; ++i)
      x.col(i) = Eigen::Map<const Vector<3>>(&bowl.coords[3 * bowl.vertices[3 * c + i]]);
    const Vector<3> own = *surface_cell_normal<CellType::Triangle>(x);
    const Vector<3> reference = Eigen::Map<const Vector<3>>(&normals[3 * c]);
    EXPECT_EQ(reference, down[c] ? Vector<3>(-own) : own) << "cell " << c;
  }
}

}  // namespace
}  // namespace neomesh
