#include "boundary/boundary.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "boundary/discrete_geometry.hpp"
#include "boundary/features.hpp"
#include "boundary/shape.hpp"
#include "core/error.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"
#include "mesh/boundary_surface.hpp"

namespace neomesh {
namespace {

// Per vertex of box(type, n) on [-1,1]^d: how many of its coordinates are ±1, i.e. how many
// box faces it lies on (0 inside, 1 on a face, 2 on an edge, d at a corner).
int box_faces(const MeshView& view, PetscInt v) {
  int faces = 0;
  for (int j = 0; j < view.dim; ++j) faces += std::abs(view.coords[v * view.dim + j]) == 1.0;
  return faces;
}

void expect_box_mask(CellType type, int n) {
  const MeshData data = box(type, n);
  const MeshView view = serial_view(data);
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  const Boundary sliding(view, dofs, BoundaryOptions(BoundaryMode::Slide));
  const std::vector<std::uint8_t> slide = sliding.fixed_dofs().flags;
  const std::vector<std::uint8_t> fixed =
      Boundary(view, dofs, BoundaryOptions(BoundaryMode::Fixed)).fixed_dofs().flags;
  // A box's faces and edges are axis-aligned: every coordinate either stays exactly or moves
  // freely, so nothing needs projecting.
  EXPECT_TRUE(sliding.sliding_vertices().vertices.empty());
  const int d = view.dim;
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const bool corner = box_faces(view, v) == d;
    for (int j = 0; j < d; ++j) {
      // Sliding fixes exactly the coordinates that are ±1: the vertex stays on its faces.
      const bool on_plane = std::abs(view.coords[v * d + j]) == 1.0;
      EXPECT_EQ(slide[v * d + j], on_plane) << "vertex " << v << " component " << j;
      EXPECT_EQ(fixed[v * d + j], box_faces(view, v) > 0) << "vertex " << v;
      if (corner) {
        EXPECT_EQ(slide[v * d + j], 1);
      }
    }
  }
}

TEST(Boundary, QuadAndTriangleBoxesSlideAlongTheirSides) {
  expect_box_mask(CellType::Quadrilateral, 4);
  expect_box_mask(CellType::Triangle, 3);
}

TEST(Boundary, HexAndTetBoxesSlideInFacesAndAlongEdges) {
  expect_box_mask(CellType::Hexahedron, 3);
  expect_box_mask(CellType::Tetrahedron, 2);
}

TEST(BoundaryFeatures, BoxHasCornersRidgesAndFaces) {
  const MeshView view = serial_view(box(CellType::Hexahedron, 3));
  const BoundaryFeatures f = find_features(*view.boundary, 40.0);
  EXPECT_EQ(f.count(VertexFeature::Corner), 8);
  EXPECT_EQ(f.count(VertexFeature::Ridge), 12 * 2);
  EXPECT_EQ(f.count(VertexFeature::Surface), 6 * 4);
  EXPECT_EQ(f.num_patches, 6);
  EXPECT_EQ(f.ridge_edges.size(), 12u);
  const MeshView square = serial_view(box(CellType::Triangle, 4));
  const BoundaryFeatures g = find_features(*square.boundary, 40.0);
  EXPECT_EQ(g.count(VertexFeature::Corner), 4);
  EXPECT_EQ(g.num_patches, 4);
}

// The disc's circle is one closed patch without corners: every boundary vertex slides on the
// input's polygon, in its tangent space.
TEST(Boundary, CircleSlidesWithoutCorners) {
  const MeshView view = serial_view(circle_quad(2));
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  const Boundary b(view, dofs, BoundaryOptions(BoundaryMode::Slide));
  EXPECT_EQ(b.summary().corners, 0);
  EXPECT_EQ(b.summary().patches, 1);
  PetscInt on_boundary = 0;
  for (PetscInt v = 0; v < view.num_vertices; ++v) on_boundary += view.on_boundary[v];
  EXPECT_EQ(static_cast<PetscInt>(b.sliding_vertices().vertices.size()), on_boundary);
  for (std::uint8_t f : b.fixed_dofs().flags) EXPECT_EQ(f, 0);
}

// Corners where two parts meet stay put even where the boundary is straight.
TEST(BoundaryFeatures, PartBordersAreCorners) {
  const MeshView view = serial_view(ring(CellType::Hexahedron, 16, 2, 1.0));
  const BoundaryFeatures f = find_features(*view.boundary, 40.0);
  // Inner and outer cylinders, bottom and top: four patches; four ridge circles, no corners.
  EXPECT_EQ(f.num_patches, 4);
  EXPECT_EQ(f.ridge_edges.size(), 4u);
  EXPECT_EQ(f.count(VertexFeature::Corner), 0);
  EXPECT_EQ(f.count(VertexFeature::Ridge), 4 * 16);
}

TEST(Shape, ParsesEveryKindAndRefusesBadSpecs) {
  const Point p(2.0, 0.0, 0.0);
  EXPECT_NEAR((parse_shape("circle:0,0,0.5", 2)->closest_point(p) - Point(0.5, 0, 0)).norm(), 0,
              1e-15);
  EXPECT_NEAR(parse_shape("sphere:0,0,1,2", 3)->closest_point({0, 0, 5})[2], 3.0, 1e-15);
  EXPECT_NEAR(parse_shape("plane:0,0,1,0,0,2", 3)->closest_point({3, 4, 5})[2], 1.0, 1e-15);
  EXPECT_NEAR(parse_shape("line:0,1,0,1", 2)->closest_point({3, 4, 0})[1], 1.0, 1e-15);
  EXPECT_NEAR(parse_shape("cylinder:0,0,0,0,0,1,1", 3)->closest_point({3, 0, 7})[0], 1.0, 1e-15);
  const auto level = parse_shape("levelset:x^2+y^2-0.25", 2);
  EXPECT_NEAR(level->closest_point({0.6, 0.0, 0})[0], 0.5, 1e-12);
  EXPECT_NEAR(level->normal({0.5, 0.0, 0})[0], 1.0, 1e-8);
  for (const char* bad :
       {"circle", "circle:0,0", "circle:0,0,-1", "circle:0,0,x", "circle:0,,1", "sphere:0,0,1",
        "blob:1", "levelset:", "levelset:x+", "plane:0,0,0,0,0,0"})
    EXPECT_THROW(parse_shape(bad, 2), Error) << bad;
  EXPECT_THROW(parse_shape("circle:0,0,1", 3), Error);
}

TEST(Shape, IntersectionOfTwoSurfacesIsTheirRidge) {
  const auto cylinder = make_cylinder({0, 0, 0}, {0, 0, 1}, 1.0);
  const auto plane = make_plane({0, 0, 0.5}, {0, 0, 1});
  const auto ridge = make_intersection(*cylinder, *plane);
  const Point q = ridge->closest_point({1.2, 0.3, 0.7});
  EXPECT_NEAR(std::hypot(q[0], q[1]), 1.0, 1e-14);
  EXPECT_NEAR(q[2], 0.5, 1e-14);
  EXPECT_NEAR(std::abs(ridge->tangent(q).dot(Point(-q[1], q[0], 0))), 1.0, 1e-12);
}

// The simplex nearest to p (the lowest index among equally near ones), searched one by one.
SimplexSet::Hit brute_force_closest(const std::vector<Point>& points,
                                    const std::vector<std::array<int, 3>>& simplices, int corners,
                                    const Point& p) {
  SimplexSet::Hit best;
  best.distance = 1e300;
  for (std::size_t t = 0; t < simplices.size(); ++t) {
    SimplexSet::Hit h = SimplexSet(points, {simplices[t]}, corners).closest(p);
    h.simplex = static_cast<int>(t);
    if (h.distance < best.distance) best = h;
  }
  return best;
}

// The grid search finds what a search through every triangle finds, for points far from the
// surface and (where the search ends after the first ring) near it.
TEST(DiscreteGeometry, GridSearchAgreesWithBruteForce) {
  std::vector<Point> points;
  std::vector<std::array<int, 3>> triangles;
  const int n = 12;  // a wavy sheet over [0,1]², two triangles per square
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      points.emplace_back(double(i) / n, double(j) / n, 0.1 * std::sin(6.0 * i / n) * j / n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      triangles.push_back({a, a + 1, a + n + 2});
      triangles.push_back({a, a + n + 2, a + n + 1});
    }
  const SimplexSet set(points, triangles, 3);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-0.3, 1.3), near(-1e-3, 1e-3);
  for (int k = 0; k < 400; ++k) {
    Point p(u(random), u(random), 0.4 * u(random));
    if (k % 2) {  // a point of the sheet, moved a little
      const auto& t = triangles[random() % triangles.size()];
      p = (points[t[0]] + points[t[1]] + points[t[2]]) / 3 + (points[t[1]] - points[t[0]]) / 3 +
          Point(near(random), near(random), near(random));
    }
    const SimplexSet::Hit expected = brute_force_closest(points, triangles, 3, p);
    const SimplexSet::Hit found = set.closest(p);
    EXPECT_EQ(found.distance, expected.distance) << k;
    EXPECT_EQ(found.simplex, expected.simplex) << k;
  }
}

// The same in 2D, where every point and simplex lies in one layer of grid cells.
TEST(DiscreteGeometry, GridSearchAgreesWithBruteForceOnAPolyline) {
  std::vector<Point> points;
  std::vector<std::array<int, 3>> segments;
  const int n = 40;  // a wavy closed curve
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n, r = 1 + 0.2 * std::sin(5 * t);
    points.emplace_back(r * std::cos(t), r * std::sin(t), 0.0);
    segments.push_back({i, (i + 1) % n, 0});
  }
  const SimplexSet set(points, segments, 2);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5), near(-1e-3, 1e-3);
  for (int k = 0; k < 400; ++k) {
    Point p(u(random), u(random), 0.0);
    if (k % 2) p = points[random() % n] + Point(near(random), near(random), 0.0);
    const SimplexSet::Hit expected = brute_force_closest(points, segments, 2, p);
    const SimplexSet::Hit found = set.closest(p);
    EXPECT_EQ(found.distance, expected.distance) << k;
    EXPECT_EQ(found.simplex, expected.simplex) << k;
  }
}

TEST(Boundary, ShapeMustNameAPartAndPassThroughItsVertices) {
  const MeshView view = serial_view(ring(CellType::Quadrilateral, 24, 3, 3.0));
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  BoundaryOptions options(BoundaryMode::Slide);
  options.shapes = {{"inner", "circle:0,0,0.5"}, {"outer", "circle:0,0,1"}};
  EXPECT_NO_THROW(Boundary(view, dofs, options));
  options.shapes = {{"hole", "circle:0,0,0.5"}};
  try {
    Boundary b(view, dofs, options);
    ADD_FAILURE() << "unknown part accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no boundary part named 'hole'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("inner, outer"), std::string::npos) << e.what();
  }
  options.shapes = {{"inner", "circle:0,0,0.49"}};
  try {
    Boundary b(view, dofs, options);
    ADD_FAILURE() << "a shape off the vertices accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is 0.01 from it"), std::string::npos) << e.what();
  }
}

// Projection puts a vertex that left its circle back onto it; a vertex of the ring's
// polygon (no shape given) onto the polygon.
TEST(Boundary, ProjectsSlidingVerticesBackOntoTheirGeometry) {
  const MeshView view = serial_view(ring(CellType::Triangle, 16, 2, 1.0));
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  BoundaryOptions options(BoundaryMode::Slide);
  options.shapes = {{"outer", "circle:0,0,1"}};
  const Boundary b(view, dofs, options);
  OwnedVec x = dofs.create_global_vector();
  {
    VecWriteView w(x);
    for (PetscInt i = 0; i < w.size(); ++i) w[i] = 1.05 * view.coords[i];
  }
  b.project(x);
  VecReadView r(x);
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const double radius = std::hypot(r[2 * v], r[2 * v + 1]);
    const double start = std::hypot(view.coords[2 * v], view.coords[2 * v + 1]);
    if (start > 0.99) {
      EXPECT_NEAR(radius, 1.0, 1e-15);
    } else if (start < 0.51) {  // the inner polygon's vertices (radius 0.5) are its corners
      EXPECT_NEAR(radius, 0.5, 1e-15);
    }
  }
  EXPECT_NEAR(b.max_distance_from_input(x), 0.0, 1e-15);
}

}  // namespace
}  // namespace neomesh
