#include "geometry/quality.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "generate/generate.hpp"
#include "generate/serial_view.hpp"

namespace neomesh {

namespace {

// The quality of a single cell with the given vertices (canonical order).
CellQuality one_cell(CellType type, std::vector<double> coords) {
  MeshData mesh;
  mesh.dim = dimension(type);
  mesh.cell_type = type;
  mesh.coords = std::move(coords);
  for (int i = 0; i < num_vertices(type); ++i) mesh.cells.push_back(i);
  const MeshView view = serial_view(mesh);
  return cell_quality(view, view.coords);
}

QualitySummary summary_of(const MeshData& mesh) {
  const MeshView view = serial_view(mesh);
  return summarize(cell_quality(view, view.coords), MPI_COMM_WORLD);
}

}  // namespace

TEST(CellQuality, UnitSquareIsIdeal) {
  const CellQuality q = one_cell(CellType::Quadrilateral, {0, 0, 1, 0, 0, 1, 1, 1});
  EXPECT_DOUBLE_EQ(q.volume[0], 1.0);
  EXPECT_DOUBLE_EQ(q.min_corner_det[0], 1.0);
  EXPECT_DOUBLE_EQ(q.min_gauss_det[0], 1.0);
  EXPECT_DOUBLE_EQ(q.scaled_jacobian[0], 1.0);
  EXPECT_DOUBLE_EQ(q.min_angle[0], 90.0);
  EXPECT_DOUBLE_EQ(q.max_angle[0], 90.0);
  EXPECT_DOUBLE_EQ(q.edge_ratio[0], 1.0);
  EXPECT_DOUBLE_EQ(q.inverse_mean_ratio[0], 1.0);
}

// The inverse mean ratio measures shape only: any size, the same; stretching by 2 gives
// |diag(2, 1)|² / (2 det) = 5/4 at every corner; a mirrored cell has none (+∞).
TEST(CellQuality, InverseMeanRatioIsShapeOnly) {
  EXPECT_NEAR(one_cell(CellType::Quadrilateral, {0, 0, 3, 0, 0, 3, 3, 3}).inverse_mean_ratio[0],
              1.0, 1e-15);
  EXPECT_NEAR(one_cell(CellType::Quadrilateral, {0, 0, 2, 0, 0, 1, 2, 1}).inverse_mean_ratio[0],
              1.25, 1e-15);
  EXPECT_TRUE(std::isinf(
      one_cell(CellType::Quadrilateral, {1, 0, 0, 0, 1, 1, 0, 1}).inverse_mean_ratio[0]));
  // A right isosceles triangle: (a² + b² + c²) / (4√3 area) = 2/√3 = 1.15470, the mean IMR
  // Mesquite reaches on triangles split from squares.
  EXPECT_NEAR(one_cell(CellType::Triangle, {0, 0, 1, 0, 0, 1}).inverse_mean_ratio[0],
              2 / std::sqrt(3.0), 1e-15);
}

namespace {

// The optimal wedge and pyramid of edge 1: face angles of 60° and 90°, equal edges.
void expect_optimal(const CellQuality& q, double volume) {
  EXPECT_NEAR(q.volume[0], volume, 1e-15);
  EXPECT_NEAR(q.scaled_jacobian[0], 1.0, 1e-15);
  EXPECT_NEAR(q.min_angle[0], 60.0, 1e-12);
  EXPECT_NEAR(q.max_angle[0], 90.0, 1e-12);
  EXPECT_NEAR(q.edge_ratio[0], 1.0, 1e-15);
  EXPECT_NEAR(q.inverse_mean_ratio[0], 1.0, 1e-14);
}

}  // namespace

TEST(CellQuality, RightPrismOnEquilateralTriangleIsIdeal) {
  const double h = std::sqrt(3.0) / 2;
  expect_optimal(
      one_cell(CellType::Wedge, {0, 0, 0, 1, 0, 0, 0.5, h, 0, 0, 0, 1, 1, 0, 1, 0.5, h, 1}), h / 2);
  // The unit reference wedge (right triangle, height 1) has det J = 1 everywhere.
  const CellQuality unit =
      one_cell(CellType::Wedge, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1});
  EXPECT_NEAR(unit.min_corner_det[0], 1.0, 1e-15);
  EXPECT_NEAR(unit.min_gauss_det[0], 1.0, 1e-14);
}

TEST(CellQuality, SquarePyramidWithEquilateralSidesIsIdeal) {
  const double apex = 1 / std::sqrt(2.0);
  expect_optimal(one_cell(CellType::Pyramid, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.5, 0.5, apex}),
                 apex / 3);
  // Apex above a base corner at height 1: the unit reference pyramid, det J = 1 wherever the
  // rule looks; pushed below the base it is inverted.
  const CellQuality unit =
      one_cell(CellType::Pyramid, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1});
  EXPECT_NEAR(unit.min_gauss_det[0], 1.0, 1e-13);
  const CellQuality below =
      one_cell(CellType::Pyramid, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.5, 0.5, -0.2});
  EXPECT_LT(below.scaled_jacobian[0], 0.0);
  EXPECT_LT(below.min_gauss_det[0], 0.0);
}

TEST(CellQuality, EquilateralTriangleIsIdeal) {
  const double h = std::sqrt(3.0) / 2;
  const CellQuality q = one_cell(CellType::Triangle, {0, 0, 1, 0, 0.5, h});
  EXPECT_DOUBLE_EQ(q.volume[0], h / 2);
  EXPECT_DOUBLE_EQ(q.min_corner_det[0], h);
  EXPECT_NEAR(q.scaled_jacobian[0], 1.0, 1e-15);
  EXPECT_NEAR(q.min_angle[0], 60.0, 1e-12);
  EXPECT_NEAR(q.max_angle[0], 60.0, 1e-12);
  EXPECT_NEAR(q.edge_ratio[0], 1.0, 1e-15);
  EXPECT_NEAR(q.inverse_mean_ratio[0], 1.0, 1e-15);
}

TEST(CellQuality, RightTriangleHasAnglesOf45And90) {
  const CellQuality q = one_cell(CellType::Triangle, {0, 0, 1, 0, 0, 1});
  EXPECT_NEAR(q.min_angle[0], 45.0, 1e-12);
  EXPECT_NEAR(q.max_angle[0], 90.0, 1e-12);
  // Smallest sin of a corner angle: sin 45° = 1/√2, relative to sin 60°.
  EXPECT_NEAR(q.scaled_jacobian[0], (1 / std::sqrt(2.0)) / (std::sqrt(3.0) / 2), 1e-15);
  EXPECT_NEAR(q.edge_ratio[0], std::sqrt(2.0), 1e-15);
}

TEST(CellQuality, ShearedQuadHasAnglesOf45And135) {
  // Parallelogram with the top edge shifted by 1: area 1, sides 1 and √2.
  const CellQuality q = one_cell(CellType::Quadrilateral, {0, 0, 1, 0, 1, 1, 2, 1});
  EXPECT_NEAR(q.volume[0], 1.0, 1e-15);
  EXPECT_NEAR(q.min_corner_det[0], 1.0, 1e-15);
  EXPECT_NEAR(q.min_gauss_det[0], 1.0, 1e-15);
  EXPECT_NEAR(q.scaled_jacobian[0], 1 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(q.min_angle[0], 45.0, 1e-12);
  EXPECT_NEAR(q.max_angle[0], 135.0, 1e-12);
  EXPECT_NEAR(q.edge_ratio[0], std::sqrt(2.0), 1e-15);
}

TEST(CellQuality, TrapezoidHasBilinearVolumeAndGaussDeterminants) {
  // Bottom edge 2, top edge 1, height 1: area 1.5; det J (unit reference) = 2 - ξ₁ along η.
  const CellQuality q = one_cell(CellType::Quadrilateral, {0, 0, 2, 0, 0.5, 1, 1.5, 1});
  EXPECT_NEAR(q.volume[0], 1.5, 1e-15);
  EXPECT_NEAR(q.min_corner_det[0], 1.0, 1e-15);
  // Lowest Gauss point η = (1 + √(3/5))/2 of [0,1]: det = 2 - η.
  EXPECT_NEAR(q.min_gauss_det[0], 2.0 - (1 + std::sqrt(0.6)) / 2, 1e-14);
}

TEST(CellQuality, MirroredQuadIsInverted) {
  const CellQuality q = one_cell(CellType::Quadrilateral, {0, 0, -1, 0, 0, 1, -1, 1});
  EXPECT_DOUBLE_EQ(q.volume[0], -1.0);
  EXPECT_DOUBLE_EQ(q.min_corner_det[0], -1.0);
  EXPECT_DOUBLE_EQ(q.scaled_jacobian[0], -1.0);
  MeshData mesh;
  mesh.coords = {0, 0, -1, 0, 0, 1, -1, 1};
  mesh.cells = {0, 1, 2, 3};
  EXPECT_EQ(summary_of(mesh).inverted, 1);
}

TEST(CellQuality, ReflexCornerOfANonConvexQuad) {
  // Vertex 3 pushed inside the triangle of the others: its corner is reflex.
  const CellQuality q = one_cell(CellType::Quadrilateral, {0, 0, 1, 0, 0, 1, 0.3, 0.3});
  EXPECT_LT(q.min_corner_det[0], 0.0);
  EXPECT_GT(q.max_angle[0], 180.0);
  EXPECT_LT(q.scaled_jacobian[0], 0.0);
}

TEST(CellQuality, RegularTetrahedronIsIdeal) {
  const double s = std::sqrt(3.0), t = std::sqrt(6.0);
  const CellQuality q =
      one_cell(CellType::Tetrahedron, {0, 0, 0, 1, 0, 0, 0.5, s / 2, 0, 0.5, s / 6, t / 3});
  EXPECT_NEAR(q.volume[0], std::sqrt(2.0) / 12, 1e-15);
  EXPECT_NEAR(q.scaled_jacobian[0], 1.0, 1e-14);
  EXPECT_NEAR(q.min_angle[0], std::acos(1.0 / 3) * 180 / M_PI, 1e-10);
  EXPECT_NEAR(q.max_angle[0], std::acos(1.0 / 3) * 180 / M_PI, 1e-10);
  EXPECT_NEAR(q.edge_ratio[0], 1.0, 1e-14);
  EXPECT_NEAR(q.inverse_mean_ratio[0], 1.0, 1e-14);
}

TEST(CellQuality, UnitCubeIsIdeal) {
  std::vector<double> x;
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d) x.push_back((i >> d) & 1);
  const CellQuality q = one_cell(CellType::Hexahedron, x);
  EXPECT_DOUBLE_EQ(q.volume[0], 1.0);
  EXPECT_DOUBLE_EQ(q.min_corner_det[0], 1.0);
  EXPECT_DOUBLE_EQ(q.min_gauss_det[0], 1.0);
  EXPECT_DOUBLE_EQ(q.scaled_jacobian[0], 1.0);
  EXPECT_DOUBLE_EQ(q.min_angle[0], 90.0);
  EXPECT_DOUBLE_EQ(q.max_angle[0], 90.0);
  EXPECT_DOUBLE_EQ(q.edge_ratio[0], 1.0);
  EXPECT_DOUBLE_EQ(q.inverse_mean_ratio[0], 1.0);
}

TEST(QualitySummary, SquareMidpointLevel3) {
  const QualitySummary s = summary_of(square_midpoint(16));
  EXPECT_EQ(s.cells, 256);
  EXPECT_EQ(s.cells_by_type[static_cast<int>(CellType::Quadrilateral)], 256);
  EXPECT_EQ(s.inverted, 0);
  EXPECT_EQ(s.degenerate, 0);
  EXPECT_NEAR(s.volume.mean, 1.0 / 256, 1e-15);
  EXPECT_LT(s.scaled_jacobian.min, 1.0);
}

TEST(QualitySummary, BoxVolumesAddUpAndCollapsedCellsAreDegenerate) {
  for (CellType type : {CellType::Triangle, CellType::Tetrahedron, CellType::Hexahedron}) {
    const MeshView view = serial_view(box(type, 2));
    const CellQuality q = cell_quality(view, view.coords);
    double total = 0.0;
    for (double v : q.volume) total += v;
    EXPECT_NEAR(total, std::pow(2.0, dimension(type)), 1e-13) << name(type);
  }
  MeshData mesh = box(CellType::Quadrilateral, 2);
  mesh.coords[2 * 4] = mesh.coords[2 * 1];  // centre onto the bottom midpoint
  mesh.coords[2 * 4 + 1] = mesh.coords[2 * 1 + 1];
  const QualitySummary s = summary_of(mesh);
  EXPECT_EQ(s.degenerate, 2);  // the two cells below the centre have a zero-length edge
  EXPECT_EQ(s.inverted, 2);
}

// The one-metric passes give cell_quality's values, and a corner with a zero-length edge has
// scaled Jacobian 0 (not the other corners' minimum), so that "scaled Jacobian > 0" means valid.
TEST(CellQuality, OneMetricPassesAgreeWithTheFullOne) {
  for (CellType type :
       {CellType::Triangle, CellType::Quadrilateral, CellType::Tetrahedron, CellType::Hexahedron}) {
    MeshData mesh = box(type, 2);
    const int d = dimension(type);
    // Every vertex moved (generic cells, to compare bits), then vertex 1 onto vertex 0: cells
    // with an edge 0.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    for (double& c : mesh.coords) c += u(rng);
    mesh.coords[d * 1] = mesh.coords[0];
    for (int k = 1; k < d; ++k) mesh.coords[d * 1 + k] = mesh.coords[k];
    const MeshView view = serial_view(mesh);
    const CellQuality q = cell_quality(view, view.coords);
    EXPECT_EQ(cell_volumes(view, view.coords), q.volume) << name(type);
    EXPECT_EQ(cell_scaled_jacobians(view, view.coords), q.scaled_jacobian) << name(type);
    // The full pass takes each corner once for all its metrics (quadrilaterals, hexahedra).
    EXPECT_EQ(cell_edge_ratios(view, view.coords), q.edge_ratio) << name(type);
    EXPECT_EQ(cell_inverse_mean_ratios(view, view.coords), q.inverse_mean_ratio) << name(type);
    int collapsed = 0;
    for (std::size_t c = 0; c < q.size(); ++c) {
      if (q.edge_ratio[c] < INFINITY) continue;
      ++collapsed;
      EXPECT_LE(q.scaled_jacobian[c], 0.0) << name(type) << " cell " << c;
    }
    EXPECT_GT(collapsed, 0) << name(type);
  }
}

namespace {

// The cells of the 2D tests above (each 2 values per vertex) and a few random ones.
std::vector<std::pair<CellType, std::vector<double>>> planar_cells() {
  const double h = std::sqrt(3.0) / 2;
  std::vector<std::pair<CellType, std::vector<double>>> cells = {
      {CellType::Triangle, {0, 0, 1, 0, 0.5, h}},
      {CellType::Triangle, {0, 0, 1, 0, 0, 1}},
      {CellType::Triangle, {0, 0, 0, 1, 1, 0}},  // clockwise: inverted
      {CellType::Quadrilateral, {0, 0, 1, 0, 1, 1, 2, 1}},
      {CellType::Quadrilateral, {0, 0, 2, 0, 0.5, 1, 1.5, 1}},
      {CellType::Quadrilateral, {0, 0, -1, 0, 0, 1, -1, 1}},     // mirrored
      {CellType::Quadrilateral, {0, 0, 1, 0, 0, 1, 0.3, 0.3}}};  // reflex corner
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (CellType type : {CellType::Triangle, CellType::Quadrilateral})
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<double> x = type == CellType::Triangle
                                  ? std::vector<double>{0, 0, 1, 0, 0.5, h}
                                  : std::vector<double>{0, 0, 1, 0, 0, 1, 1, 1};
      for (double& v : x) v = 2.0 * (v + u(rng)) - 0.7;
      cells.emplace_back(type, std::move(x));
    }
  return cells;
}

// The 2D cell `xy` placed in space, rotated by R: 3 values per vertex.
std::vector<double> into_space(const std::vector<double>& xy, const Eigen::Matrix3d& R) {
  std::vector<double> x;
  for (std::size_t i = 0; i < xy.size(); i += 2) {
    const Eigen::Vector3d p = R * Eigen::Vector3d(xy[i], xy[i + 1], 0.0) + Eigen::Vector3d(1, 2, 3);
    x.insert(x.end(), p.data(), p.data() + 3);
  }
  return x;
}

// a and b agree to 1e-14 relative to their size (to 1e-14 where they are below 1), or are the
// same infinity.
void expect_close(double a, double b, const char* what) {
  if (std::isinf(a) || std::isinf(b)) {
    EXPECT_EQ(a, b) << what;
  } else {
    EXPECT_NEAR(a, b, 1e-14 * std::max(1.0, std::abs(b))) << what;
  }
}

}  // namespace

namespace {

// The cells of box(type, 2) scaled by 2 with every coordinate moved by up to ±amplitude, each
// as its vertices' coordinates (canonical order).
std::vector<std::vector<double>> jittered_cells(CellType type, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-amplitude, amplitude);
  MeshData mesh = box(type, 2);
  for (double& x : mesh.coords) x = 2.0 * x + jitter(rng);
  const int d = mesh.dim, n = num_vertices(type);
  std::vector<std::vector<double>> cells(static_cast<std::size_t>(mesh.num_cells()));
  for (std::int64_t c = 0; c < mesh.num_cells(); ++c)
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) cells[c].push_back(mesh.coords[d * mesh.cells[n * c + i] + a]);
  return cells;
}

constexpr CellType kEveryType[] = {CellType::Triangle,    CellType::Quadrilateral,
                                   CellType::Tetrahedron, CellType::Hexahedron,
                                   CellType::Wedge,       CellType::Pyramid};

}  // namespace

// Above its bar, cell_scaled_jacobian_above gives the scaled Jacobian bit for bit; at or
// below it, some value at most the bar: on jittered cells of every type, with bars below, at and
// above each cell's value, and on planar cells turned into space for the surface variant.
TEST(CellQuality, ScaledJacobianAboveABarIsTheScaledJacobian) {
  const double inf = std::numeric_limits<double>::infinity();
  auto check = [](double sj, double above, double bar, const std::string& what) {
    if (sj > bar)
      EXPECT_EQ(above, sj) << what << " bar " << bar;
    else
      EXPECT_LE(above, bar) << what << " bar " << bar << " scaled Jacobian " << sj;
  };
  int below = 0;
  for (CellType type : kEveryType)
    for (const std::vector<double>& x : jittered_cells(type, 0.45, 7)) {  // some inverted
      const double sj = cell_scaled_jacobian(type, x.data());
      for (double bar : {-inf, -0.5, sj - 0.1, std::nextafter(sj, -inf), sj, 0.0, sj + 0.1, 0.9}) {
        check(sj, cell_scaled_jacobian_above(type, x.data(), bar), bar, std::string(name(type)));
        below += !(sj > bar);
      }
    }
  for (const auto& [type, xy] : planar_cells()) {
    const std::vector<double> x = into_space(xy, Eigen::Matrix3d::Identity());
    const double up[3] = {0.0, 0.0, 1.0};
    const double sj = surface_cell_scaled_jacobian(type, x.data(), up);
    for (double bar : {-0.5, sj - 0.1, sj, sj + 0.1})
      check(sj, surface_cell_scaled_jacobian_above(type, x.data(), up, bar), bar,
            "surface " + std::string(name(type)));
  }
  EXPECT_GT(below, 100);  // the early exits were taken
}

// The corners a vertex moves and the others split the scaled Jacobian: the minimum of the two
// parts is the whole bit for bit, and moving the vertex leaves the other corners' part as it is.
TEST(CellQuality, ScaledJacobianSplitsIntoTheCornersAVertexMovesAndTheOthers) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const double inf = std::numeric_limits<double>::infinity();
  int fixed_parts = 0;
  for (CellType type : kEveryType) {
    const int d = dimension(type), n = num_vertices(type);
    for (const std::vector<double>& x : jittered_cells(type, 0.3, 11)) {
      const double whole = cell_scaled_jacobian(type, x.data());
      for (int k = 0; k < n; ++k) {
        const std::uint32_t moved = scaled_jacobian_corners_at(type, k);
        const double others = cell_scaled_jacobian_above(type, x.data(), -inf, ~moved);
        EXPECT_EQ(std::min(others, cell_scaled_jacobian_above(type, x.data(), -inf, moved)), whole)
            << name(type) << " vertex " << k;
        std::vector<double> y = x;
        for (int a = 0; a < d; ++a) y[d * k + a] += jitter(rng);
        EXPECT_EQ(cell_scaled_jacobian_above(type, y.data(), -inf, ~moved), others)
            << name(type) << " vertex " << k;
        fixed_parts += others < inf;
      }
    }
  }
  EXPECT_GT(fixed_parts, 100);  // Q1 cells, wedges and pyramids have corners a vertex leaves be
}

// The corners' values one by one: their minimum over any set of corners is the value over
// those corners bit for bit (all of them: the cell's), in the plane, in space and for surface
// cells, inverted corners included; what the worst-cell repair keeps per cell.
TEST(CellQuality, ScaledJacobianCornersGiveTheValueOverAnyCorners) {
  const double inf = std::numeric_limits<double>::infinity();
  auto least = [inf](const double* values, int n, std::uint32_t corners) {
    double v = inf;
    for (int k = 0; k < n; ++k)
      if ((corners >> k) & 1) v = std::min(v, values[k]);
    return v;
  };
  int inverted = 0;
  for (CellType type : kEveryType)
    for (const std::vector<double>& x : jittered_cells(type, 0.7, 7)) {
      double values[kMaxScaledJacobianCorners];
      const int n = cell_scaled_jacobian_corners(type, x.data(), values);
      ASSERT_LE(n, kMaxScaledJacobianCorners);
      EXPECT_EQ(n, facts(type).shape == CellShape::Simplex ? dimension(type) + 1
                                                           : facts(type).num_corners);
      EXPECT_EQ(least(values, n, kAllCorners), cell_scaled_jacobian(type, x.data())) << name(type);
      for (std::uint32_t corners = 0; corners < (1u << n); corners += 3)
        EXPECT_EQ(least(values, n, corners),
                  cell_scaled_jacobian_above(type, x.data(), -inf, corners))
            << name(type) << " corners " << corners;
      inverted += least(values, n, kAllCorners) <= 0.0;
    }
  EXPECT_GT(inverted, 0);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const auto& [type, xy] : planar_cells()) {
    const std::vector<double> x = into_space(xy, turn);
    const Eigen::Vector3d up = turn * Eigen::Vector3d(0, 0, 1);
    double values[kMaxScaledJacobianCorners];
    const int n = surface_cell_scaled_jacobian_corners(type, x.data(), up.data(), values);
    EXPECT_EQ(least(values, n, kAllCorners),
              surface_cell_scaled_jacobian(type, x.data(), up.data()))
        << "surface " << name(type);
    for (std::uint32_t corners = 0; corners < (1u << n); ++corners)
      EXPECT_EQ(least(values, n, corners),
                surface_cell_scaled_jacobian_above(type, x.data(), up.data(), -inf, corners))
          << "surface " << name(type) << " corners " << corners;
  }
}

// A cell's edge ratio is the longest over the shortest edge_length between the vertices of its
// facets' edges, bit for bit, in 2D, in 3D and for surface cells in space: what the worst-cell
// repair relies on when it updates a cell's edge ratio from the edges at the vertex it moves.
TEST(CellQuality, EdgeRatioIsTheLongestOverTheShortestEdgeLength) {
  auto from_lengths = [](CellType type, const std::vector<double>& x, int d) {
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (int f = 0; f < facts(type).num_facets; ++f) {
      const FacetVertices& facet = facts(type).facets[f];
      for (int i = 0; i < facet.size; ++i) {
        const int a = facet.vertices[i], b = facet.vertices[(i + 1) % facet.size];
        const double length = edge_length(x.data() + d * a, x.data() + d * b, d);
        EXPECT_EQ(length, edge_length(x.data() + d * b, x.data() + d * a, d));
        shortest = std::min(shortest, length);
        longest = std::max(longest, length);
      }
    }
    return longest / shortest;
  };
  int cells = 0;
  for (CellType type : kEveryType)
    for (const std::vector<double>& x : jittered_cells(type, 0.45, 7)) {
      EXPECT_EQ(cell_edge_ratio(type, x.data()), from_lengths(type, x, dimension(type)))
          << name(type);
      ++cells;
    }
  const Eigen::Matrix3d turned =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const auto& [type, xy] : planar_cells()) {
    const std::vector<double> x = into_space(xy, turned);
    EXPECT_EQ(surface_cell_edge_ratio(type, x.data()), from_lengths(type, x, 3)) << name(type);
    ++cells;
  }
  EXPECT_GT(cells, 50);
}

// A triangle or quadrilateral in the xy plane with normal +z, and the same cell turned anywhere
// in space with its normal, measures as the 2D cell: the same area, determinants, scaled
// Jacobian, angles, edge ratio and inverse mean ratio, to rounding.
TEST(SurfaceCellQuality, EqualsThe2DMeasuresInThePlaneAndTurnedInSpace) {
  const Eigen::Matrix3d turned =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  for (const auto& [type, xy] : planar_cells())
    for (const Eigen::Matrix3d& R : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), turned}) {
      const CellQuality flat = one_cell(type, xy);
      const std::vector<double> x = into_space(xy, R);
      const Eigen::Vector3d normal = R.col(2);
      const SurfaceCellMeasures m = surface_cell_measures(type, x.data(), normal.data());
      expect_close(m.area, flat.volume[0], "area");
      expect_close(m.min_corner_det, flat.min_corner_det[0], "min corner det");
      expect_close(m.min_gauss_det, flat.min_gauss_det[0], "min Gauss det");
      expect_close(m.scaled_jacobian, flat.scaled_jacobian[0], "scaled Jacobian");
      expect_close(m.min_angle, flat.min_angle[0], "min angle");
      expect_close(m.max_angle, flat.max_angle[0], "max angle");
      expect_close(m.edge_ratio, flat.edge_ratio[0], "edge ratio");
      expect_close(m.inverse_mean_ratio, flat.inverse_mean_ratio[0], "inverse mean ratio");
      EXPECT_EQ(surface_cell_scaled_jacobian(type, x.data(), normal.data()), m.scaled_jacobian);
      EXPECT_EQ(surface_cell_edge_ratio(type, x.data()), m.edge_ratio);
    }
}

// Seen from the other side — the cell folded against its normal — the determinants change
// sign: a negative scaled Jacobian, a negative area, no inverse mean ratio.
TEST(SurfaceCellQuality, CellFoldedAgainstItsNormalIsInverted) {
  const double h = std::sqrt(3.0) / 2;
  const std::vector<double> triangle = {0, 0, 0, 1, 0, 0, 0.5, h, 0};
  const std::vector<double> square = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const double down[] = {0, 0, -1};
  for (const auto& [type, x] :
       {std::pair{CellType::Triangle, triangle}, std::pair{CellType::Quadrilateral, square}}) {
    const SurfaceCellMeasures m = surface_cell_measures(type, x.data(), down);
    EXPECT_NEAR(m.scaled_jacobian, -1.0, 1e-15) << name(type);
    EXPECT_LT(m.area, 0.0);
    EXPECT_LT(m.min_corner_det, 0.0);
    EXPECT_TRUE(std::isinf(m.inverse_mean_ratio));
  }
}

// A square tilted by θ against the plane normal to n is seen foreshortened: determinants and
// scaled Jacobian times cos θ, the inverse mean ratio over cos θ; lengths and angles are its own.
TEST(SurfaceCellQuality, CellTiltedAgainstItsNormalIsSeenForeshortened) {
  const double theta = 0.3, c = std::cos(theta), s = std::sin(theta);
  const std::vector<double> x = {0, 0, 0, 1, 0, 0, 0, c, s, 1, c, s};  // turned about x
  const double up[] = {0, 0, 1};
  const SurfaceCellMeasures m = surface_cell_measures(CellType::Quadrilateral, x.data(), up);
  EXPECT_NEAR(m.area, c, 1e-15);
  EXPECT_NEAR(m.scaled_jacobian, c, 1e-15);
  EXPECT_NEAR(m.inverse_mean_ratio, 1.0 / c, 1e-15);
  EXPECT_NEAR(m.min_angle, 90.0, 1e-12);
  EXPECT_NEAR(m.max_angle, 90.0, 1e-12);
  EXPECT_NEAR(m.edge_ratio, 1.0, 1e-15);
}

TEST(SurfaceCellQuality, OnlyTrianglesAndQuadrilateralsAreSurfaceCells) {
  const std::vector<double> x(12, 0.0);
  const double up[] = {0, 0, 1};
  EXPECT_THROW(surface_cell_scaled_jacobian(CellType::Tetrahedron, x.data(), up), Error);
  EXPECT_THROW(surface_cell_edge_ratio(CellType::Tetrahedron, x.data()), Error);
}

}  // namespace neomesh
