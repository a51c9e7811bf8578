#include "mesh/plane_embedding.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "core/error.hpp"

namespace neomesh {

namespace {

using Vector3 = Eigen::Vector3d;

Vector3 point(std::span<const double> xyz, std::size_t i) {
  return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
}

// The axis along which every point has the same coordinate, or -1.
int constant_axis(std::span<const double> xyz) {
  for (int k : {2, 0, 1}) {
    bool constant = true;
    for (std::size_t i = 3 + k; i < xyz.size() && constant; i += 3) constant = xyz[i] == xyz[k];
    if (constant) return k;
  }
  return -1;
}

}  // namespace

std::optional<PlaneEmbedding> PlaneEmbedding::fit(std::span<const double> xyz,
                                                  std::vector<double>& uv,
                                                  const std::string& file) {
  const std::size_t n = xyz.size() / 3;
  uv.resize(2 * n);
  PlaneEmbedding plane;
  if (n == 0) return plane;
  for (std::size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i]))
      fail("{}: vertex {} (0-based) has a non-finite coordinate ({})", file, i / 3, xyz[i]);

  // A plane normal to an axis: the other two coordinates are the plane's, unchanged.
  if (const int k = constant_axis(xyz); k >= 0) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    for (std::size_t p = 0; p < n; ++p) uv[2 * p] = xyz[3 * p + i], uv[2 * p + 1] = xyz[3 * p + j];
    plane.xy_ = k == 2 && xyz[2] == 0.0;
    plane.origin_ = {0, 0, 0};
    plane.origin_[k] = xyz[k];
    plane.a_ = plane.b_ = plane.normal_ = {0, 0, 0};
    plane.a_[i] = plane.b_[j] = plane.normal_[k] = 1;
    return plane;
  }

  // Otherwise the least-squares plane: through the centroid, normal to the direction in which
  // the points spread least.
  Vector3 centre = Vector3::Zero(), lo = point(xyz, 0), hi = lo;
  for (std::size_t p = 0; p < n; ++p) {
    centre += point(xyz, p);
    lo = lo.cwiseMin(point(xyz, p));
    hi = hi.cwiseMax(point(xyz, p));
  }
  centre /= static_cast<double>(n);
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (std::size_t p = 0; p < n; ++p) {
    const Vector3 d = point(xyz, p) - centre;
    spread += d * d.transpose();
  }
  Vector3 normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spread).eigenvectors().col(0);
  int major = 0;  // the normal points along +its largest component: z-ish planes keep x, y
  normal.cwiseAbs().maxCoeff(&major);
  if (normal[major] < 0) normal = -normal;
  const double size = (hi - lo).norm();
  double off = 0;
  for (std::size_t p = 0; p < n; ++p)
    off = std::max(off, std::abs(normal.dot(point(xyz, p) - centre)));
  if (!(off <= kPlanarTolerance * size)) return std::nullopt;

  int minor = 0;  // a: the axis least along the normal, made tangent
  normal.cwiseAbs().minCoeff(&minor);
  Vector3 a = Vector3::Unit(minor) - normal[minor] * normal;
  a.normalize();
  const Vector3 b = normal.cross(a);
  for (std::size_t p = 0; p < n; ++p) {
    const Vector3 d = point(xyz, p) - centre;
    uv[2 * p] = d.dot(a);
    uv[2 * p + 1] = d.dot(b);
  }
  plane.xy_ = false;
  for (int k = 0; k < 3; ++k) {
    plane.origin_[k] = centre[k];
    plane.a_[k] = a[k];
    plane.b_[k] = b[k];
    plane.normal_[k] = normal[k];
  }
  plane.input_xyz_.assign(xyz.begin(), xyz.end());
  plane.input_uv_ = uv;
  return plane;
}

std::vector<double> PlaneEmbedding::to_space(std::span<const double> uv) const {
  const std::size_t n = uv.size() / 2;
  std::vector<double> xyz(3 * n);
  const bool has_input = input_uv_.size() == uv.size();
  const int k = normal_[0] == 1 ? 0 : normal_[1] == 1 ? 1 : normal_[2] == 1 ? 2 : -1;
  for (std::size_t p = 0; p < n; ++p) {
    const double u = uv[2 * p], v = uv[2 * p + 1];
    double* x = xyz.data() + 3 * p;
    if (has_input && input_uv_[2 * p] == u && input_uv_[2 * p + 1] == v) {
      std::copy_n(input_xyz_.data() + 3 * p, 3, x);
    } else if (k >= 0) {  // exact: the constant and the two coordinates as they are
      x[k] = origin_[k];
      x[(k + 1) % 3] = u;
      x[(k + 2) % 3] = v;
    } else {
      for (int d = 0; d < 3; ++d) x[d] = origin_[d] + u * a_[d] + v * b_[d];
    }
  }
  return xyz;
}

std::array<double, 2> PlaneEmbedding::to_plane(const double* xyz) const {
  for (int k = 0; k < 3; ++k)
    if (normal_[k] == 1) return {xyz[(k + 1) % 3], xyz[(k + 2) % 3]};
  std::array<double, 2> uv{0, 0};
  for (int d = 0; d < 3; ++d) {
    uv[0] += (xyz[d] - origin_[d]) * a_[d];
    uv[1] += (xyz[d] - origin_[d]) * b_[d];
  }
  return uv;
}

double PlaneEmbedding::distance(const double* xyz) const {
  double off = 0;
  for (int d = 0; d < 3; ++d) off += (xyz[d] - origin_[d]) * normal_[d];
  return std::abs(off);
}

std::string PlaneEmbedding::describe() const {
  for (int k = 0; k < 3; ++k)
    if (normal_[k] == 1) return fmt::format("{} = {:g}", "xyz"[k], origin_[k]);
  return fmt::format("through ({:g}, {:g}, {:g}) with normal ({:.3g}, {:.3g}, {:.3g})", origin_[0],
                     origin_[1], origin_[2], normal_[0], normal_[1], normal_[2]);
}

}  // namespace neomesh
