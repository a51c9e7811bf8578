#include "targets/size_field.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>

#include <muParser.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "core/error.hpp"
#include "targets/desired_volumes.hpp"

namespace neomesh {

namespace {

double norm(std::span<const double> v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

void expect_size(const std::vector<double>& v, const char* what, std::size_t low,
                 std::size_t high) {
  if (v.size() < low || v.size() > high)
    fail("the {} needs {} coordinates (got {})", what,
         low == high ? fmt::format("{}", low) : fmt::format("{} or {}", low, high), v.size());
}

std::string coordinates(std::span<const double> v) {
  return fmt::format("{:.4g}", fmt::join(v, ", "));
}

// A muparser expression in x, y, z and the time t. The parser keeps the addresses of the variables,
// so both live together on the heap and are never moved.
struct Expression {
  mu::Parser parser;
  double x = 0.0, y = 0.0, z = 0.0, t = 0.0;
  std::string what;  // "level-set expression", "metric entry m12", ...

  explicit Expression(const std::string& text, std::string what_ = "level-set expression")
      : what(std::move(what_)) {
    try {
      parser.DefineVar("x", &x);
      parser.DefineVar("y", &y);
      parser.DefineVar("z", &z);
      parser.DefineVar("t", &t);
      parser.SetExpr(text);
      parser.Eval();  // muparser parses on the first evaluation
    } catch (const mu::Parser::exception_type& e) {
      fail("cannot parse the {} '{}': {}", what, text, e.GetMsg());
    }
  }

  double operator()(std::span<const double> p) {
    x = p[0];
    y = p[1];
    z = p.size() > 2 ? p[2] : 0.0;
    try {
      return parser.Eval();
    } catch (const mu::Parser::exception_type& e) {
      fail("cannot evaluate the {} '{}' at ({}): {}", what, parser.GetExpr(), coordinates(p),
           e.GetMsg());
    }
  }
};

double global_max(double value, MPI_Comm comm) {
  double out = 0.0;
  MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, comm);
  return out;
}

}  // namespace

void check_sphere(const std::vector<double>& centre, double radius) {
  expect_size(centre, "centre of a circle/sphere", 2, 3);
  if (!(radius > 0 && std::isfinite(radius)))
    fail("the radius of a {} must be positive (got {})", centre.size() == 2 ? "circle" : "sphere",
         radius);
}

void check_plane(const std::vector<double>& point, const std::vector<double>& normal) {
  expect_size(point, "point of a plane", 2, 3);
  expect_size(normal, "normal of a plane", point.size(), point.size());
  if (!(norm(normal) > 0)) fail("the normal of the plane must not be zero");
}

SizeField::SizeField(std::string description, int dim, Distance signed_distance)
    : description_(std::move(description)),
      dim_(dim),
      signed_distance_(std::move(signed_distance)) {}

SizeField SizeField::sphere(std::vector<double> centre, double radius) {
  check_sphere(centre, radius);
  const int dim = static_cast<int>(centre.size());
  return {fmt::format("distance to the {} around ({}) with radius {}",
                      dim == 2 ? "circle" : "sphere", coordinates(centre), radius),
          dim, [centre, radius](std::span<const double> p) {
            double r2 = 0.0;
            for (std::size_t j = 0; j < centre.size(); ++j) r2 += std::pow(p[j] - centre[j], 2);
            return std::sqrt(r2) - radius;
          }};
}

SizeField SizeField::plane(std::vector<double> point, std::vector<double> normal) {
  check_plane(point, normal);
  const double length = norm(normal);
  for (double& n : normal) n /= length;
  return {
      fmt::format("distance to the {} through ({}) with normal ({})",
                  point.size() == 2 ? "line" : "plane", coordinates(point), coordinates(normal)),
      static_cast<int>(point.size()), [point, normal](std::span<const double> p) {
        double s = 0.0;
        for (std::size_t j = 0; j < point.size(); ++j) s += (p[j] - point[j]) * normal[j];
        return s;
      }};
}

SizeField SizeField::box(std::vector<double> lower, std::vector<double> upper) {
  expect_size(lower, "lower corner of a box", 2, 3);
  expect_size(upper, "upper corner of a box", lower.size(), lower.size());
  for (std::size_t j = 0; j < lower.size(); ++j)
    if (!(lower[j] < upper[j]))
      fail("the box's lower corner ({}) must be below its upper corner ({}) in every coordinate",
           coordinates(lower), coordinates(upper));
  return {fmt::format("distance to the surface of the box ({}) – ({})", coordinates(lower),
                      coordinates(upper)),
          static_cast<int>(lower.size()), [lower, upper](std::span<const double> p) {
            // Outside: Euclidean distance to the box; inside: minus the distance to the nearest
            // face.
            double outside = 0.0, inside = std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j < lower.size(); ++j) {
              const double below = lower[j] - p[j], above = p[j] - upper[j];
              const double out = std::max({below, above, 0.0});
              outside += out * out;
              inside = std::min(inside, std::max(std::min(-below, -above), 0.0));
            }
            return outside > 0.0 ? std::sqrt(outside) : -inside;
          }};
}

SizeField SizeField::level_set(const std::string& expression) {
  auto phi = std::make_shared<Expression>(expression);
  SizeField field(fmt::format("|{}|", expression), 0,
                  [phi](std::span<const double> p) { return (*phi)(p); });
  field.set_time_ = [phi](double t) { phi->t = t; };
  return field;
}

SizeField SizeField::metric(const std::vector<std::string>& entries) {
  if (entries.size() != 3 && entries.size() != 6)
    fail(
        "a metric needs 3 entries (2D: m11, m12, m22) or 6 (3D: m11, m12, m13, m22, m23, m33), "
        "got {}",
        entries.size());
  const int dim = entries.size() == 3 ? 2 : 3;
  std::vector<std::shared_ptr<Expression>> m;
  for (int i = 0, k = 0; i < dim; ++i)
    for (int j = i; j < dim; ++j, ++k)
      m.push_back(std::make_shared<Expression>(entries[k],
                                               fmt::format("metric entry m{}{}", i + 1, j + 1)));
  SizeField field(fmt::format("the metric ({})", fmt::join(entries, "; ")), dim, {});
  field.metric_ = [m, dim](std::span<const double> p, std::span<double> out) {
    for (int i = 0, k = 0; i < dim; ++i)
      for (int j = i; j < dim; ++j, ++k) out[i + j * dim] = out[j + i * dim] = (*m[k])(p);
  };
  field.set_time_ = [m](double t) {
    for (const auto& entry : m) entry->t = t;
  };
  return field;
}

SizeField SizeField::stretched(const Stretch& stretch) const {
  if (!signed_distance_)
    fail("only a field of the distance to a surface can be stretched, not {}", description_);
  const Stretch s = stretch;
  if (!(s.normal > 0 && s.normal <= s.tangent && std::isfinite(s.tangent)))
    fail("a stretch needs sizes 0 < normal ≤ tangent (got normal {}, tangent {})", s.normal,
         s.tangent);
  if (!(s.width >= 0 && std::isfinite(s.width)))
    fail("a stretch needs a width ≥ 0 (got {})", s.width);
  if (!(s.grading > 0 && std::isfinite(s.grading)))
    fail("a stretch needs a grading > 0 (got {})", s.grading);
  SizeField field = *this;
  field.description_ = fmt::format("{}, stretched: size {:g} across and {:g} along it within {:g}",
                                   description_, s.normal, s.tangent, s.width);
  field.metric_ = [phi = signed_distance_, s](std::span<const double> p, std::span<double> m) {
    const std::size_t d = p.size();
    // The normal: the gradient of the signed distance by central differences, at a step far
    // below the smallest size asked for.
    const double h = 1e-3 * s.normal;
    std::array<double, 3> at{}, n{};
    std::copy(p.begin(), p.end(), at.begin());
    double length = 0.0;
    for (std::size_t j = 0; j < d; ++j) {
      at[j] = p[j] + h;
      const double forward = phi(std::span(at).first(d));
      at[j] = p[j] - h;
      n[j] = (forward - phi(std::span(at).first(d))) / (2 * h);
      at[j] = p[j];
      length += n[j] * n[j];
    }
    length = std::sqrt(length);
    const double distance = std::abs(phi(p));
    const double across =
        std::min(s.tangent, s.normal + s.grading * std::max(0.0, distance - s.width));
    // M = I / tangent² + (1 / across² − 1 / tangent²) n nᵀ; isotropic where the normal is
    // undefined (the centre of a sphere, a box's medial surface).
    const bool has_normal = length > 0 && std::isfinite(length);
    const double base = has_normal ? 1 / (s.tangent * s.tangent) : 1 / (across * across);
    const double extra = has_normal ? 1 / (across * across) - base : 0.0;
    for (std::size_t i = 0; i < d; ++i)
      for (std::size_t j = 0; j < d; ++j)
        m[i + j * d] =
            (i == j ? base : 0.0) + extra * n[i] * n[j] / (has_normal ? length * length : 1);
  };
  return field;
}

void SizeField::set_time(double t) {
  if (set_time_) set_time_(t);
}

SizeField SizeField::distances(Distances distances, const std::string& description, int dim) {
  if (!distances) fail("the size field's distance function is empty");
  // One point at a time for what needs single points (the normal of stretched()).
  SizeField field(description, dim, [distances](std::span<const double> p) {
    double d = 0.0;
    distances(p, std::span(&d, 1));
    return d;
  });
  field.distances_ = std::move(distances);
  return field;
}

SizeField SizeField::cell_values(std::vector<double> values) {
  SizeField field(fmt::format("{} per-cell values", values.size()), 0, {});
  field.cell_values_ = std::move(values);
  return field;
}

SizeField SizeField::read_cell_values(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) fail("cannot open the size file {}", file.string());
  std::vector<double> values;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;  // blank lines, e.g. a trailing one
    char* end = nullptr;
    const double v = std::strtod(line.c_str() + first, &end);
    if (end == line.c_str() + first ||
        line.find_first_not_of(" \t\r", end - line.c_str()) != std::string::npos)
      fail("{}:{}: expected one number per line, got '{}'", file.string(), number, line);
    values.push_back(v);
  }
  SizeField field = cell_values(std::move(values));
  field.description_ = fmt::format("per-cell values from {}", file.string());
  return field;
}

std::vector<double> cell_centroids(const MeshView& view, std::span<const double> coords) {
  const int d = view.dim;
  std::vector<double> centroids(static_cast<std::size_t>(view.num_cells) * d, 0.0);
  for (const CellBlock& block : view.blocks) {
    const int nv = block.nodes();
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int i = 0; i < nv; ++i)
        for (int j = 0; j < d; ++j)
          centroids[(block.first_cell + c) * d + j] += coords[block.cell(c)[i] * d + j] / nv;
  }
  return centroids;
}

// What relative_volumes() reads of a SizeField, which keeps it private.
struct SizeFieldAccess {
  static const std::string& description(const SizeField& f) { return f.description_; }
  static int dim(const SizeField& f) { return f.dim_; }
  static const SizeField::Distance& signed_distance(const SizeField& f) {
    return f.signed_distance_;
  }
  static const SizeField::Metric& metric(const SizeField& f) { return f.metric_; }
  static const std::vector<double>& cell_values(const SizeField& f) { return f.cell_values_; }
  static const SizeField::Distances& distances(const SizeField& f) { return f.distances_; }
};

namespace {

double determinant(std::span<const double> m, int d) {
  if (d == 2) return m[0] * m[3] - m[1] * m[2];
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[3] * (m[1] * m[8] - m[2] * m[7]) +
         m[6] * (m[1] * m[5] - m[2] * m[4]);
}

void require_dimension_of(const SizeField& field, const MeshView& view) {
  const int field_dim = SizeFieldAccess::dim(field);
  if (field_dim != 0 && field_dim != view.dim)
    fail("the size field ({}) is {}D but the mesh is {}D", SizeFieldAccess::description(field),
         field_dim, view.dim);
}

// M^(-1/2) of an anisotropic field at each centroid (dim² per cell, column-major); throws
// Error naming the first cell where M is not symmetric positive definite.
std::vector<double> metric_inverse_roots(const SizeField& field, const MeshView& view,
                                         std::span<const double> centroids) {
  require_dimension_of(field, view);
  const int d = view.dim;
  const auto& metric = SizeFieldAccess::metric(field);
  std::vector<double> roots(static_cast<std::size_t>(view.num_cells) * d * d);
  Eigen::MatrixXd m(d, d);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(d);
  for (PetscInt c = 0; c < view.num_cells; ++c) {
    const std::span<const double> at = centroids.subspan(c * d, d);
    metric(at, std::span(m.data(), d * d));
    const bool finite = m.allFinite();
    if (finite) eigen.compute(m);
    if (!finite || (m - m.transpose()).norm() > 1e-12 * m.norm() ||
        !(eigen.eigenvalues().minCoeff() > 0))
      fail("the metric is not symmetric positive definite at cell {} (centroid {}): {}; {}",
           view.global_cell[c], coordinates(at),
           finite ? fmt::format("eigenvalues {:.4g}", fmt::join(eigen.eigenvalues(), ", "))
                  : std::string("not finite"),
           SizeFieldAccess::description(field));
    const Eigen::MatrixXd root = eigen.eigenvectors() *
                                 eigen.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() *
                                 eigen.eigenvectors().transpose();
    std::copy_n(root.data(), d * d, roots.begin() + c * d * d);
  }
  return roots;
}

// The volume of each cell's unit cell of M relative to the ideal cell of size 1: det(M^(-1/2)).
std::vector<double> unit_cell_volumes(std::span<const double> roots, int d) {
  std::vector<double> v(roots.size() / (d * d));
  for (std::size_t c = 0; c < v.size(); ++c) v[c] = determinant(roots.subspan(c * d * d, d * d), d);
  return v;
}

}  // namespace

std::vector<double> relative_volumes(const SizeField& field, const MeshView& view,
                                     std::span<const double> coords,
                                     const SizeFieldOptions& field_options, MPI_Comm comm) {
  const std::string& description = SizeFieldAccess::description(field);
  const auto& signed_distance = SizeFieldAccess::signed_distance(field);
  const std::vector<double>& values = SizeFieldAccess::cell_values(field);
  require_dimension_of(field, view);
  const int d = view.dim;
  const std::vector<double> centroids = cell_centroids(view, coords);
  std::vector<double> v(view.num_cells);
  if (field.anisotropic()) {
    v = unit_cell_volumes(metric_inverse_roots(field, view, centroids), d);
  } else if (!values.empty()) {
    long long cells = view.num_cells, total = 0;
    MPI_Allreduce(&cells, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
    if (static_cast<long long>(values.size()) != total)
      fail("the size field has {} values but the mesh has {} cells", values.size(), total);
    for (PetscInt c = 0; c < view.num_cells; ++c) v[c] = values[view.global_cell[c]];
  } else if (const auto& distances = SizeFieldAccess::distances(field)) {
    distances(centroids, v);  // d, then v = floor + |d|^p in place
    for (double& x : v) x = field_options.floor + std::pow(std::abs(x), field_options.power);
  } else {
    for (PetscInt c = 0; c < view.num_cells; ++c)
      v[c] = field_options.floor +
             std::pow(std::abs(signed_distance(std::span(centroids).subspan(c * d, d))),
                      field_options.power);
  }
  for (PetscInt c = 0; c < view.num_cells; ++c) {
    const char* problem = std::isnan(v[c])   ? "NaN"
                          : std::isinf(v[c]) ? "infinite"
                          : v[c] < 0         ? "negative"
                          : v[c] == 0        ? "zero"
                                             : nullptr;
    if (problem)
      fail("size field is {} at cell {} (centroid {}): {}; desired sizes must be positive", problem,
           view.global_cell[c], coordinates(std::span(centroids).subspan(c * d, d)), description);
  }
  return v;
}

namespace {

// Relative volumes made consistent as `field_options` asks and scaled to sum to `total`: desired
// volumes. Collective.
std::vector<double> consistent_volumes(std::vector<double> v, const SizeFieldOptions& field_options,
                                       const MeshView& view, const DofMap& dofs, double total) {
  if (const double ratio = field_options.ratio(); ratio > 0) {
    const double largest = v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
    const double smallest = global_max(largest, dofs.comm()) / ratio;
    for (double& x : v) x = std::max(x, smallest);
  }
  if (field_options.smoothing_passes > 0) {
    // Averaging log v (a geometric mean) keeps small volumes small; an arithmetic mean would
    // let one large neighbour swamp them.
    for (double& x : v) x = std::log(x);
    for (int pass = 0; pass < field_options.smoothing_passes; ++pass)
      v = average_over_neighbours(view, dofs, v);
    for (double& x : v) x = std::exp(x);
  }
  normalize_volumes(v, total, dofs.comm());
  return v;
}

// Each cell's M^(-1/2) (in `shapes`) turned by the rotation R of its Jacobian J = R U.
void orient(std::vector<double>& shapes, std::span<const double> jacobians, int d) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(d, d, Eigen::ComputeFullU | Eigen::ComputeFullV);
  for (std::size_t c = 0; c * d * d < shapes.size(); ++c) {
    const Eigen::Map<const Eigen::MatrixXd> J(jacobians.data() + c * d * d, d, d);
    if (!(J.determinant() > 0)) continue;  // an inverted cell has no orientation: S = M^(-1/2)
    svd.compute(J);
    Eigen::Map<Eigen::MatrixXd> S(shapes.data() + c * d * d, d, d);
    const Eigen::MatrixXd rotation = svd.matrixU() * svd.matrixV().transpose();
    S = S * rotation;
  }
}

}  // namespace

std::vector<double> desired_volumes_from_field(const SizeField& field,
                                               const SizeFieldOptions& field_options,
                                               const MeshView& view, const DofMap& dofs,
                                               std::span<const double> coords, double total) {
  return consistent_volumes(relative_volumes(field, view, coords, field_options, dofs.comm()),
                            field_options, view, dofs, total);
}

std::vector<double> target_shapes(const SizeField& field, const MeshView& view,
                                  std::span<const double> coords,
                                  std::span<const double> jacobians) {
  if (!field.anisotropic()) return {};
  std::vector<double> shapes = metric_inverse_roots(field, view, cell_centroids(view, coords));
  orient(shapes, jacobians, view.dim);
  return shapes;
}

CellTargets field_targets(const SizeField& field, const SizeFieldOptions& field_options,
                          const MeshView& view, const DofMap& dofs, std::span<const double> coords,
                          std::span<const double> jacobians, double total) {
  if (!field.anisotropic())
    return ideal_targets(
        desired_volumes_from_field(field, field_options, view, dofs, coords, total));
  // M is evaluated once per cell for both the volume and the shape.
  std::vector<double> shapes = metric_inverse_roots(field, view, cell_centroids(view, coords));
  CellTargets targets = ideal_targets(
      consistent_volumes(unit_cell_volumes(shapes, view.dim), field_options, view, dofs, total));
  orient(shapes, jacobians, view.dim);
  targets.shapes = std::move(shapes);
  return targets;
}

}  // namespace neomesh
