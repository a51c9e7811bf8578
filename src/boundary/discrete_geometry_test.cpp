// The Phong tessellation of a triangulated surface (PhongSurface): closer to the sphere its points
// lie on than the flat triangles, its normal and shape operator those of its closest points (by
// finite differences), and flat where a coarse triangulation could fold it.
#include "boundary/discrete_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include <Eigen/Geometry>

namespace neomesh {
namespace {

struct Triangulation {
  std::vector<Point> points;
  std::vector<std::array<int, 3>> triangles;
};

// An octahedron's faces, each split into level² triangles, its points moved onto the unit sphere.
Triangulation sphere(int level) {
  const std::array<Point, 6> corner{Point(1, 0, 0),  Point(-1, 0, 0), Point(0, 1, 0),
                                    Point(0, -1, 0), Point(0, 0, 1),  Point(0, 0, -1)};
  const std::array<std::array<int, 3>, 8> face{
      {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}}};
  Triangulation out;
  std::map<std::array<long, 3>, int> index;  // by rounded position: shared edges share points
  auto point = [&](const Point& p) {
    const Point x = p.normalized();
    const std::array<long, 3> key{std::lround(x[0] * 1e9), std::lround(x[1] * 1e9),
                                  std::lround(x[2] * 1e9)};
    const auto [it, added] = index.emplace(key, static_cast<int>(out.points.size()));
    if (added) out.points.push_back(x);
    return it->second;
  };
  for (const auto& f : face) {
    const Point &a = corner[f[0]], &b = corner[f[1]], &c = corner[f[2]];
    auto at = [&](int i, int j) {
      return point(a + (b - a) * i / double(level) + (c - a) * j / double(level));
    };
    for (int i = 0; i < level; ++i)
      for (int j = 0; i + j < level; ++j) {
        out.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 2 <= level)
          out.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  return out;
}

// Points about the unit sphere, off it by up to `off`.
std::vector<Point> probes(double off) {
  std::vector<Point> out;
  for (int k = 0; k < 400; ++k) {
    const double z = -0.99 + 1.98 * (k + 0.5) / 400, phi = 2.39996 * k;
    const double s = std::sqrt(1 - z * z), r = 1 + off * std::sin(7.0 * k);
    out.emplace_back(r * s * std::cos(phi), r * s * std::sin(phi), r * z);
  }
  return out;
}

TEST(PhongSurface, OnASphereIsFarCloserToItThanTheFlatTriangles) {
  const Triangulation t = sphere(6);  // edges turn by about 15°, as a coarse Gmsh sphere's
  const PhongSurface phong(t.points, t.triangles);
  const DiscreteSurface flat(t.points, t.triangles, 3);
  EXPECT_EQ(phong.flat_points(), 0);
  double phong_error = 0, flat_error = 0;
  for (const Point& p : probes(0.05)) {
    phong_error = std::max(phong_error, std::abs(phong.closest_point(p).norm() - 1));
    flat_error = std::max(flat_error, std::abs(flat.closest_point(p).norm() - 1));
  }
  EXPECT_GT(flat_error, 5e-3);
  EXPECT_LT(phong_error, flat_error / 10);
  std::printf("level 6: farthest from the sphere %.3g (Phong) vs %.3g (flat)\n", phong_error,
              flat_error);
}

TEST(PhongSurface, InterpolatesThePointsAndItsClosestPointsStayPut) {
  const Triangulation t = sphere(4);
  const PhongSurface phong(t.points, t.triangles);
  for (const Point& x : t.points) EXPECT_LT((phong.closest_point(x) - x).norm(), 1e-14);
  const std::vector<Point> near = probes(0.1);
  for (const Point& q : near)
    EXPECT_LT((phong.closest_point(phong.closest_point(q)) - phong.closest_point(q)).norm(), 1e-13);
  for (std::size_t k = 0; k < near.size(); k += 20) {
    const Point& p = near[k];
    const Point q = phong.closest_point(p);
    // The closest point, by sampling every triangle's patch.
    double sampled = 1e300;
    for (int s = 0; s < static_cast<int>(t.triangles.size()); ++s)
      for (int i = 0; i <= 30; ++i)
        for (int j = 0; i + j <= 30; ++j)
          sampled = std::min(sampled, (phong.evaluate(s, i / 30.0, j / 30.0).q - p).norm());
    EXPECT_LE((q - p).norm(), sampled + 1e-12) << p.transpose();
  }
}

TEST(PhongSurface, NormalAndShapeOperatorMatchFiniteDifferences) {
  const Triangulation t = sphere(3);
  const PhongSurface phong(t.points, t.triangles);
  const double h = 1e-5;
  for (int s = 0; s < static_cast<int>(t.triangles.size()); s += 5) {
    const PhongSurface::Patch at = phong.evaluate(s, 0.3, 0.25);  // inside: the patch is smooth
    const Point q = at.q, n = phong.normal(q);
    const Matrix3 S = phong.shape_operator(q);
    // The patch's normal is ⟂ its chords through q; normal() is within a few degrees of it.
    const Point patch_normal = at.qu.cross(at.qv).normalized();
    EXPECT_GT(std::abs(n.dot(patch_normal)), std::cos(5 * M_PI / 180));
    const Point a = n.unitOrthogonal(), b = n.cross(a);
    std::vector<Point> dn;  // dn/ds along a, b, (a + 2b)/|a + 2b|
    for (const Point& e : {a, b, Point((a + 2 * b).normalized())}) {
      const Point plus = phong.closest_point(q + h * e), minus = phong.closest_point(q - h * e);
      EXPECT_LT(std::abs(patch_normal.dot(plus - minus)) / (2 * h), 1e-6);
      dn.push_back((phong.normal(plus) - phong.normal(minus)) / (2 * h));
    }
    // S is symmetric, tangent, and uᵀ S v = (u·dn(v) + v·dn(u))/2 for tangent u, v.
    EXPECT_LT((S - S.transpose()).norm(), 1e-12);
    EXPECT_LT((S * n).norm(), 1e-12);
    const Point c = (a + 2 * b).normalized();
    EXPECT_NEAR(a.dot(S * a), a.dot(dn[0]), 1e-5);
    EXPECT_NEAR(b.dot(S * b), b.dot(dn[1]), 1e-5);
    EXPECT_NEAR(c.dot(S * c), c.dot(dn[2]), 1e-5);
    EXPECT_NEAR(a.dot(S * b), 0.5 * (a.dot(dn[1]) + b.dot(dn[0])), 1e-5);
    // A sphere's: about the identity on the tangent plane.
    EXPECT_NEAR(a.dot(S * a) * (n.dot(q) > 0 ? 1 : -1), 1.0, 0.3);
  }
}

TEST(PhongSurface, FlattensWhereARoughSurfaceWouldFoldIt) {
  // A sphere's points moved by up to 1.3 edge lengths (radially and along x): noisy normals.
  // Smooth surfaces keep the area element above 0.7 (a sphere, an ellipsoid squashed 20 times,
  // points moved by 0.2 edge lengths); rough ones fold.
  const int level = 6;
  Triangulation t = sphere(level);
  for (std::size_t k = 0; k < t.points.size(); ++k) {
    t.points[k] *= 1 + 2.0 / level * std::sin(12.9898 * double(k + 1));
    t.points[k].x() += 2.0 / level * std::sin(78.233 * double(k + 1));
  }
  const PhongSurface unguarded(t.points, t.triangles, -1e300);
  const PhongSurface guarded(t.points, t.triangles);
  EXPECT_EQ(unguarded.flat_points(), 0);
  EXPECT_GT(guarded.flat_points(), 0);
  EXPECT_LT(guarded.flat_points(), static_cast<int>(t.points.size()));
  double unguarded_least = 1e300, guarded_least = 1e300;
  for (int s = 0; s < static_cast<int>(t.triangles.size()); ++s) {
    unguarded_least = std::min(unguarded_least, unguarded.area_ratio(s));
    guarded_least = std::min(guarded_least, guarded.area_ratio(s));
  }
  EXPECT_LT(unguarded_least, 0.0);  // folded
  EXPECT_GE(guarded_least, PhongSurface::kMinAreaRatio);
}

}  // namespace
}  // namespace neomesh
