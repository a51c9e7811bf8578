#include "targets/background_metric.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "core/error.hpp"
#include "mesh/cell_type.hpp"

namespace neomesh {

namespace {

using Matrix = Eigen::MatrixXd;

// The simplices of a cell, by local (canonical) vertex: quadrilaterals and the pyramid's base
// cut along the diagonal 0–3, hexahedra into six tetrahedra around the diagonal 0–7, wedges
// into three tetrahedra.
std::span<const std::array<std::uint8_t, 4>> simplices_of(CellType type) {
  static constexpr std::array<std::array<std::uint8_t, 4>, 1> triangle{{{0, 1, 2, 0}}},
      tetrahedron{{{0, 1, 2, 3}}};
  static constexpr std::array<std::array<std::uint8_t, 4>, 2> quad{{{0, 1, 3, 0}, {0, 3, 2, 0}}},
      pyramid{{{0, 1, 3, 4}, {0, 3, 2, 4}}};
  static constexpr std::array<std::array<std::uint8_t, 4>, 3> wedge{
      {{0, 1, 2, 3}, {1, 2, 3, 4}, {2, 3, 4, 5}}};
  static constexpr std::array<std::array<std::uint8_t, 4>, 6> hexahedron{
      {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}}};
  switch (type) {
    case CellType::Triangle:
      return triangle;
    case CellType::Quadrilateral:
      return quad;
    case CellType::Tetrahedron:
      return tetrahedron;
    case CellType::Hexahedron:
      return hexahedron;
    case CellType::Wedge:
      return wedge;
    case CellType::Pyramid:
      return pyramid;
  }
  return {};
}

// exp or log of a symmetric matrix through its eigenvalues.
Matrix apply_to_eigenvalues(const Matrix& m, double (*f)(double)) {
  const Eigen::SelfAdjointEigenSolver<Matrix> eigen(m);
  return eigen.eigenvectors() * eigen.eigenvalues().unaryExpr(f).asDiagonal() *
         eigen.eigenvectors().transpose();
}

}  // namespace

void unpack_metric(int dim, std::span<const double> numbers, std::span<double> m,
                   const std::string& where) {
  const std::size_t upper = dim * (dim + 1) / 2, full = dim * dim;
  if (numbers.size() != upper && numbers.size() != full)
    fail("{}: a {}D metric has {} numbers (the upper triangle) or {}, not {}", where, dim, upper,
         full, numbers.size());
  for (int i = 0, k = 0; i < dim; ++i)
    for (int j = numbers.size() == upper ? i : 0; j < dim; ++j, ++k)
      if (numbers.size() == upper)
        m[i + j * dim] = m[j + i * dim] = numbers[k];
      else
        m[i + j * dim] = numbers[i * dim + j];
  const Eigen::Map<const Matrix> M(m.data(), dim, dim);
  const bool finite = M.allFinite();
  if (!finite || (M - M.transpose()).norm() > 1e-12 * M.norm())
    fail("{}: the metric is {}", where, finite ? "not symmetric" : "not finite");
  const Eigen::SelfAdjointEigenSolver<Matrix> eigen(M);
  if (!(eigen.eigenvalues().minCoeff() > 0))
    fail("{}: the metric is not positive definite (eigenvalues {:.4g})", where,
         fmt::join(eigen.eigenvalues(), ", "));
}

void broadcast(BackgroundMesh& mesh, MPI_Comm comm) {
  auto send = [comm](auto& v, MPI_Datatype type) {
    long long n = static_cast<long long>(v.size());
    MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, comm);
    v.resize(n);
    MPI_Bcast(v.data(), static_cast<int>(n), type, 0, comm);
  };
  MPI_Bcast(&mesh.dim, 1, MPI_INT, 0, comm);
  send(mesh.coords, MPI_DOUBLE);
  send(mesh.offsets, MPI_INT64_T);
  send(mesh.vertices, MPI_INT64_T);
  send(mesh.metrics, MPI_DOUBLE);
  std::vector<std::uint8_t> types(mesh.types.size());
  std::transform(mesh.types.begin(), mesh.types.end(), types.begin(),
                 [](CellType t) { return static_cast<std::uint8_t>(t); });
  send(types, MPI_UINT8_T);
  mesh.types.resize(types.size());
  std::transform(types.begin(), types.end(), mesh.types.begin(),
                 [](std::uint8_t t) { return static_cast<CellType>(t); });
}

BackgroundMetric::BackgroundMetric(BackgroundMesh mesh)
    : dim_(mesh.dim), coords_(std::move(mesh.coords)) {
  const int d = dim_, n = d * d;
  const std::int64_t vertices = static_cast<std::int64_t>(coords_.size()) / d;
  logs_.resize(static_cast<std::size_t>(vertices) * n);
  for (std::int64_t v = 0; v < vertices; ++v) {
    const Eigen::Map<const Matrix> m(mesh.metrics.data() + v * n, d, d);
    Eigen::Map<Matrix>(logs_.data() + v * n, d, d) =
        apply_to_eigenvalues(m, [](double x) { return std::log(x); });
  }
  for (std::size_t c = 0; c < mesh.types.size(); ++c)
    for (const auto& s : simplices_of(mesh.types[c]))
      for (int i = 0; i <= d; ++i) simplices_.push_back(mesh.vertices[mesh.offsets[c] + s[i]]);

  // The grid: about one simplex per bucket.
  const std::int64_t count = static_cast<std::int64_t>(simplices_.size()) / (d + 1);
  std::array<double, 3> upper{};
  for (int j = 0; j < d; ++j) {
    lower_[j] = std::numeric_limits<double>::infinity();
    upper[j] = -lower_[j];
    for (std::int64_t v = 0; v < vertices; ++v) {
      lower_[j] = std::min(lower_[j], coords_[v * d + j]);
      upper[j] = std::max(upper[j], coords_[v * d + j]);
    }
    buckets_[j] = std::max(1, static_cast<int>(std::ceil(std::pow(count, 1.0 / d))));
    width_[j] = std::max(upper[j] - lower_[j], 1e-300) / buckets_[j];
  }
  const std::int64_t total = static_cast<std::int64_t>(buckets_[0]) * buckets_[1] * buckets_[2];
  std::vector<std::vector<std::int64_t>> lists(total);
  for (std::int64_t s = 0; s < count; ++s) {
    std::array<int, 3> from{}, to{};
    for (int j = 0; j < d; ++j) {
      double low = std::numeric_limits<double>::infinity(), high = -low;
      for (int i = 0; i <= d; ++i) {
        const double x = coords_[simplices_[s * (d + 1) + i] * d + j];
        low = std::min(low, x);
        high = std::max(high, x);
      }
      from[j] = std::clamp(static_cast<int>((low - lower_[j]) / width_[j]), 0, buckets_[j] - 1);
      to[j] = std::clamp(static_cast<int>((high - lower_[j]) / width_[j]), 0, buckets_[j] - 1);
    }
    for (int k = from[2]; k <= to[2]; ++k)
      for (int j = from[1]; j <= to[1]; ++j)
        for (int i = from[0]; i <= to[0]; ++i)
          lists[(static_cast<std::int64_t>(k) * buckets_[1] + j) * buckets_[0] + i].push_back(s);
  }
  bucket_start_.push_back(0);
  for (const auto& list : lists) {
    bucket_simplices_.insert(bucket_simplices_.end(), list.begin(), list.end());
    bucket_start_.push_back(static_cast<std::int64_t>(bucket_simplices_.size()));
  }
}

double BackgroundMetric::barycentric(std::int64_t s, std::span<const double> p,
                                     std::span<double> lambda) const {
  const int d = dim_;
  const std::int64_t* v = simplices_.data() + s * (d + 1);
  Eigen::Matrix3d edges = Eigen::Matrix3d::Identity();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int j = 0; j < d; ++j) {
    for (int i = 0; i < d; ++i) edges(j, i) = coords_[v[i + 1] * d + j] - coords_[v[0] * d + j];
    rhs[j] = p[j] - coords_[v[0] * d + j];
  }
  const Eigen::Vector3d x = edges.partialPivLu().solve(rhs);
  lambda[0] = 1.0;
  double smallest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < d; ++i) {
    lambda[i + 1] = std::isfinite(x[i]) ? x[i] : -std::numeric_limits<double>::infinity();
    lambda[0] -= lambda[i + 1];
    smallest = std::min(smallest, lambda[i + 1]);
  }
  return std::min(smallest, lambda[0]);
}

std::int64_t BackgroundMetric::locate(std::span<const double> p, std::span<double> lambda) const {
  const int d = dim_;
  std::array<int, 3> at{};
  for (int j = 0; j < d; ++j)
    at[j] = std::clamp(static_cast<int>(std::floor((p[j] - lower_[j]) / width_[j])), 0,
                       buckets_[j] - 1);
  std::array<double, 4> trial{};
  double best_smallest = -std::numeric_limits<double>::infinity();
  std::int64_t best = -1;
  const int most = *std::max_element(buckets_.begin(), buckets_.end());
  // Rings of buckets around the point's: its own holds the point's simplex unless the point is
  // outside the background; then the nearest simplex is in the first ring with any, or the next.
  int rings_after_first = -1;
  for (int r = 0; r <= most && rings_after_first < 1; ++r) {
    for (int k = std::max(0, at[2] - r); k <= std::min(buckets_[2] - 1, at[2] + r); ++k)
      for (int j = std::max(0, at[1] - r); j <= std::min(buckets_[1] - 1, at[1] + r); ++j)
        for (int i = std::max(0, at[0] - r); i <= std::min(buckets_[0] - 1, at[0] + r); ++i) {
          if (std::max({std::abs(i - at[0]), std::abs(j - at[1]), std::abs(k - at[2])}) != r)
            continue;  // an inner ring's bucket, searched already
          const std::int64_t b = (static_cast<std::int64_t>(k) * buckets_[1] + j) * buckets_[0] + i;
          for (std::int64_t q = bucket_start_[b]; q < bucket_start_[b + 1]; ++q) {
            const double smallest = barycentric(bucket_simplices_[q], p, trial);
            if (smallest > best_smallest) {
              best_smallest = smallest;
              best = bucket_simplices_[q];
              std::copy_n(trial.begin(), d + 1, lambda.begin());
            }
            if (smallest >= -1e-12) return best;
          }
        }
    if (best >= 0) ++rings_after_first;
  }
  // Outside: the closest barycentric point of the nearest simplex.
  double sum = 0.0;
  for (int i = 0; i <= d; ++i) sum += lambda[i] = std::max(lambda[i], 0.0);
  for (int i = 0; i <= d; ++i) lambda[i] /= sum;
  return best;
}

void BackgroundMetric::operator()(std::span<const double> point, std::span<double> m) const {
  const int d = dim_, n = d * d;
  std::array<double, 4> lambda{};
  const std::int64_t s = locate(point, lambda);
  Matrix log_m = Matrix::Zero(d, d);
  for (int i = 0; i <= d; ++i)
    log_m +=
        lambda[i] * Eigen::Map<const Matrix>(logs_.data() + simplices_[s * (d + 1) + i] * n, d, d);
  Eigen::Map<Matrix>(m.data(), d, d) =
      apply_to_eigenvalues(log_m, [](double x) { return std::exp(x); });
}

}  // namespace neomesh
