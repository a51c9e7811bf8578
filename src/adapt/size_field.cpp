#include "adapt/size_field.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>

#include <muParser.h>

#include "core/error.hpp"
#include "solver/desired_volumes.hpp"

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

  explicit Expression(const std::string& text) {
    try {
      parser.DefineVar("x", &x);
      parser.DefineVar("y", &y);
      parser.DefineVar("z", &z);
      parser.DefineVar("t", &t);
      parser.SetExpr(text);
      parser.Eval();  // muparser parses on the first evaluation
    } catch (const mu::Parser::exception_type& e) {
      fail("cannot parse the level-set expression '{}': {}", text, e.GetMsg());
    }
  }

  double operator()(std::span<const double> p) {
    x = p[0];
    y = p[1];
    z = p.size() > 2 ? p[2] : 0.0;
    try {
      return parser.Eval();
    } catch (const mu::Parser::exception_type& e) {
      fail("cannot evaluate the level-set expression '{}' at ({}): {}", parser.GetExpr(),
           coordinates(p), e.GetMsg());
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

SizeField::SizeField(std::string description, int dim, Distance distance)
    : description_(std::move(description)), dim_(dim), distance_(std::move(distance)) {}

SizeField SizeField::sphere(std::vector<double> centre, double radius) {
  check_sphere(centre, radius);
  const int dim = static_cast<int>(centre.size());
  return {fmt::format("distance to the {} around ({}) with radius {}",
                      dim == 2 ? "circle" : "sphere", coordinates(centre), radius),
          dim, [centre, radius](std::span<const double> p) {
            double r2 = 0.0;
            for (std::size_t j = 0; j < centre.size(); ++j) r2 += std::pow(p[j] - centre[j], 2);
            return std::abs(std::sqrt(r2) - radius);
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
        return std::abs(s);
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
            // Outside: Euclidean distance to the box; inside: distance to the nearest face.
            double outside = 0.0, inside = std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j < lower.size(); ++j) {
              const double below = lower[j] - p[j], above = p[j] - upper[j];
              const double out = std::max({below, above, 0.0});
              outside += out * out;
              inside = std::min(inside, std::max(std::min(-below, -above), 0.0));
            }
            return outside > 0.0 ? std::sqrt(outside) : inside;
          }};
}

SizeField SizeField::level_set(const std::string& expression) {
  auto phi = std::make_shared<Expression>(expression);
  SizeField field(fmt::format("|{}|", expression), 0,
                  [phi](std::span<const double> p) { return std::abs((*phi)(p)); });
  field.set_time_ = [phi](double t) { phi->t = t; };
  return field;
}

void SizeField::set_time(double t) {
  if (set_time_) set_time_(t);
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
    const int nv = num_vertices(block.type);
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
  static const SizeField::Distance& distance(const SizeField& f) { return f.distance_; }
  static const std::vector<double>& cell_values(const SizeField& f) { return f.cell_values_; }
};

std::vector<double> relative_volumes(const SizeField& field, const MeshView& view,
                                     std::span<const double> coords,
                                     const SizeFieldOptions& options, MPI_Comm comm) {
  const std::string& description = SizeFieldAccess::description(field);
  const int field_dim = SizeFieldAccess::dim(field);
  const auto& distance = SizeFieldAccess::distance(field);
  const std::vector<double>& values = SizeFieldAccess::cell_values(field);
  if (field_dim != 0 && field_dim != view.dim)
    fail("the size field ({}) is {}D but the mesh is {}D", description, field_dim, view.dim);
  const int d = view.dim;
  const std::vector<double> centroids = cell_centroids(view, coords);
  std::vector<double> v(view.num_cells);
  if (!values.empty()) {
    long long cells = view.num_cells, total = 0;
    MPI_Allreduce(&cells, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
    if (static_cast<long long>(values.size()) != total)
      fail("the size field has {} values but the mesh has {} cells", values.size(), total);
    for (PetscInt c = 0; c < view.num_cells; ++c) v[c] = values[view.global_cell[c]];
  } else {
    for (PetscInt c = 0; c < view.num_cells; ++c)
      v[c] =
          options.floor + std::pow(distance(std::span(centroids).subspan(c * d, d)), options.power);
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

std::vector<double> desired_volumes(const SizeField& field, const SizeFieldOptions& options,
                                    const MeshView& view, const DofMap& dofs,
                                    std::span<const double> coords, double total) {
  std::vector<double> v = relative_volumes(field, view, coords, options, dofs.comm());
  if (const double ratio = options.ratio(); ratio > 0) {
    const double largest = v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
    const double smallest = global_max(largest, dofs.comm()) / ratio;
    for (double& x : v) x = std::max(x, smallest);
  }
  if (options.smoothing_passes > 0) {
    // Averaging log v (a geometric mean) keeps small volumes small; an arithmetic mean would
    // let one large neighbour swamp them.
    for (double& x : v) x = std::log(x);
    for (int pass = 0; pass < options.smoothing_passes; ++pass)
      v = average_over_neighbours(view, dofs, v);
    for (double& x : v) x = std::exp(x);
  }
  normalize_volumes(v, total, dofs.comm());
  return v;
}

}  // namespace neomesh
