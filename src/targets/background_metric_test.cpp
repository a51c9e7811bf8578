#include "targets/background_metric.hpp"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "core/error.hpp"
#include "generate/generate.hpp"

namespace neomesh {
namespace {

using ::testing::HasSubstr;

// log M linear in x: M = diag(e^(1 + x), e^(2 y)[, e^(−z)]), with an off-diagonal part made by a
// fixed rotation Q: M = Q diag(...) Qᵀ. The log-Euclidean interpolation is exact for it.
Eigen::MatrixXd exact(int d, std::span<const double> x) {
  Eigen::VectorXd logs(d);
  logs[0] = 1 + x[0];
  logs[1] = 2 * x[1];
  if (d == 3) logs[2] = -x[2];
  Eigen::MatrixXd q = Eigen::MatrixXd::Identity(d, d);
  q.topLeftCorner(2, 2) = Eigen::Rotation2Dd(0.3).toRotationMatrix();
  return q * logs.array().exp().matrix().asDiagonal() * q.transpose();
}

BackgroundMesh background(CellType type, int n) {
  const MeshData data = box(type, n);
  BackgroundMesh mesh;
  mesh.dim = data.dim;
  mesh.coords = data.coords;
  const int nv = num_vertices(type);
  for (std::int64_t c = 0; c < data.num_cells(); ++c) {
    mesh.types.push_back(type);
    mesh.offsets.push_back(mesh.offsets.back() + nv);
  }
  mesh.vertices = data.cells;
  const int d = data.dim;
  for (std::int64_t v = 0; v < data.num_vertices(); ++v) {
    const Eigen::MatrixXd m = exact(d, std::span(data.coords).subspan(v * d, d));
    mesh.metrics.insert(mesh.metrics.end(), m.data(), m.data() + d * d);
  }
  return mesh;
}

class BackgroundMetricTest : public ::testing::TestWithParam<CellType> {};

TEST_P(BackgroundMetricTest, InterpolatesALogLinearMetricExactly) {
  const BackgroundMetric metric(background(GetParam(), 3));
  const int d = metric.dim();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> inside(-1.0, 1.0);  // box() is [-1, 1]^d
  for (int k = 0; k < 50; ++k) {
    std::vector<double> p(d);
    for (double& x : p) x = inside(random);
    Eigen::MatrixXd m(d, d);
    metric(p, std::span(m.data(), d * d));
    EXPECT_TRUE(m.isApprox(exact(d, p), 1e-12)) << m << "\nat " << p[0] << ", " << p[1];
  }
}

TEST_P(BackgroundMetricTest, APointOutsideTakesTheNearestSimplexsValue) {
  const BackgroundMetric metric(background(GetParam(), 2));
  const int d = metric.dim();
  std::vector<double> p(d, 0.1);
  p[0] = 1.3;  // beyond the face x = 1
  Eigen::MatrixXd m(d, d);
  metric(p, std::span(m.data(), d * d));
  // On the face x = 1 the exact metric's first logarithm is 2; the others lie between the
  // face's corners' values.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
  std::vector<double> on_face = p;
  on_face[0] = 1.0;
  EXPECT_TRUE(m.isApprox(exact(d, on_face), 0.3)) << m;
}

INSTANTIATE_TEST_SUITE_P(EveryType, BackgroundMetricTest,
                         ::testing::Values(CellType::Triangle, CellType::Quadrilateral,
                                           CellType::Tetrahedron, CellType::Hexahedron,
                                           CellType::Wedge, CellType::Pyramid));

TEST(UnpackMetric, TakesTheUpperTriangleOrTheWholeMatrix) {
  std::array<double, 9> m{};
  unpack_metric(2, std::array{4.0, 1.0, 3.0}, m, "here");
  EXPECT_EQ((std::array<double, 4>{m[0], m[1], m[2], m[3]}), (std::array{4.0, 1.0, 1.0, 3.0}));
  unpack_metric(3, std::array{4.0, 1.0, 0.5, 3.0, 0.2, 2.0}, m, "here");
  EXPECT_EQ(m, (std::array{4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0}));
  unpack_metric(2, std::array{4.0, 1.0, 1.0, 3.0}, m, "here");
  EXPECT_EQ(m[2], 1.0);
}

TEST(UnpackMetric, ABadMetricNamesWhereItIs) {
  std::array<double, 9> m{};
  auto message = [&](int d, std::vector<double> numbers) {
    try {
      unpack_metric(d, numbers, m, "vertex 7 (0.5, 0.5)");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message(2, {1, 2, 1}),
              HasSubstr("vertex 7 (0.5, 0.5): the metric is not positive definite (eigenvalues "
                        "-1, 3)"));
  EXPECT_THAT(message(2, {1, 0.5}), HasSubstr("a 2D metric has 3 numbers (the upper triangle) "
                                              "or 4, not 2"));
  EXPECT_THAT(message(2, {1, 0.5, 0.4, 1}), HasSubstr("the metric is not symmetric"));
  EXPECT_THAT(message(2, {1, NAN, 1}), HasSubstr("the metric is not finite"));
}

}  // namespace
}  // namespace neomesh
