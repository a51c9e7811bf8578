#include "mesh/cell_type.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace neomesh {
namespace {

using Point = std::array<double, 3>;

// A valid cell of each type in canonical order (cell_type.hpp), z = 0 in 2D.
std::vector<Point> reference_cell(CellType t) {
  static const std::vector<Point> cells[kNumCellTypes] = {
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.5, 0.7}}};
  return cells[static_cast<int>(t)];
}

Point minus(const Point& a, const Point& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point& a, const Point& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

bool is_permutation_of_vertices(const std::array<std::uint8_t, 8>& order, int n) {
  std::vector<int> v(order.begin(), order.begin() + n);
  std::sort(v.begin(), v.end());
  for (int i = 0; i < n; ++i)
    if (v[i] != i) return false;
  return true;
}

class CellTypeTable : public ::testing::TestWithParam<CellType> {};

TEST_P(CellTypeTable, OrdersArePermutations) {
  const CellFacts& f = facts(GetParam());
  EXPECT_TRUE(is_permutation_of_vertices(f.gmsh_order, f.vertices));
  EXPECT_TRUE(is_permutation_of_vertices(f.plex_order, f.vertices));
  EXPECT_TRUE(is_permutation_of_vertices(f.mirror, f.vertices));
  EXPECT_EQ(cell_type_index(f.dim, f.vertices), static_cast<int>(GetParam()));
}

// Every corner frame is positive on a valid cell and negative on its mirror image.
TEST_P(CellTypeTable, CornerFramesArePositiveAndMirrorNegatesThem) {
  const CellFacts& f = facts(GetParam());
  const std::vector<Point> x = reference_cell(GetParam());
  auto det = [&](const std::vector<Point>& p, const CornerFrame& frame) {
    Point e[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}};  // 2D: the third column is e_z
    for (int j = 0; j < f.dim; ++j) {
      e[j] = minus(p[frame.ends[j]], p[frame.vertex]);
      if ((frame.flip >> j) & 1) e[j] = minus(Point{0, 0, 0}, e[j]);
    }
    return dot(e[0], cross(e[1], e[2]));
  };
  std::vector<Point> mirrored(x.size());
  for (int i = 0; i < f.vertices; ++i) mirrored[i] = x[f.mirror[i]];
  for (int k = 0; k < f.num_corners; ++k) {
    EXPECT_GT(det(x, f.corners[k]), 0.0) << "corner frame " << k;
    EXPECT_LT(det(mirrored, f.corners[k]), 0.0) << "corner frame " << k;
  }
}

// The facets cover the cell's boundary once, all turning the same way (a closed, oriented
// surface), with normals pointing out of the cell.
TEST_P(CellTypeTable, FacetsAreTheOutwardOrientedBoundary) {
  const CellFacts& f = facts(GetParam());
  if (f.dim != 3) GTEST_SKIP() << "2D facets are edges";
  const std::vector<Point> x = reference_cell(GetParam());
  Point centre{0, 0, 0};
  for (const Point& p : x)
    for (int d = 0; d < 3; ++d) centre[d] += p[d] / f.vertices;
  std::map<std::pair<int, int>, int> directed;
  for (int k = 0; k < f.num_facets; ++k) {
    const FacetVertices& facet = f.facets[k];
    Point normal{0, 0, 0}, middle{0, 0, 0};
    for (int i = 0; i < facet.size; ++i) {
      const int a = facet.vertices[i], b = facet.vertices[(i + 1) % facet.size];
      ++directed[{a, b}];
      const Point c = cross(x[a], x[b]);
      for (int d = 0; d < 3; ++d) {
        normal[d] += c[d];
        middle[d] += x[a][d] / facet.size;
      }
    }
    EXPECT_GT(dot(normal, minus(middle, centre)), 0.0) << "facet " << k;
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryType, CellTypeTable, ::testing::ValuesIn(kAllCellTypes),
                         [](const auto& info) { return std::string(name(info.param)); });

TEST(VisitCellType, CallsTheBodyWithTheTypeAsAConstant) {
  for (CellType t : kAllCellTypes)
    EXPECT_EQ(visit_cell_type(t, []<CellType Type>(CellTag<Type>) { return num_vertices(Type); }),
              num_vertices(t));
}

}  // namespace
}  // namespace neomesh
