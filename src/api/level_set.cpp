#include <neomesh/level_set.hpp>

#include "api/fitting.hpp"
#include "core/error.hpp"
#include "targets/size_field.hpp"

namespace neomesh {

namespace {

// Numbers written so that muparser reads back the same double.
std::string exact(double v) {
  return fmt::format("({:.17g})", v);
}

}  // namespace

LevelSet::LevelSet(std::string expression) : expression_(std::move(expression)) {
  LevelSetFunction(expression_, 3, true);  // parses it: errors now, not in the first fit
}

LevelSet LevelSet::sphere(const std::vector<double>& centre, double radius) {
  check_sphere(centre, radius);
  std::string sum;
  for (std::size_t j = 0; j < centre.size(); ++j)
    sum += fmt::format("{}({}-{})^2", j ? "+" : "", "xyz"[j], exact(centre[j]));
  return LevelSet(fmt::format("sqrt({})-{}", sum, exact(radius)));
}

LevelSet LevelSet::plane(const std::vector<double>& point, const std::vector<double>& normal) {
  check_plane(point, normal);
  std::string sum;
  for (std::size_t j = 0; j < point.size(); ++j)
    sum += fmt::format("{}(({}-{})*{})", j ? "+" : "", "xyz"[j], exact(point[j]), exact(normal[j]));
  return LevelSet(sum);
}

LevelSet LevelSet::expression(const std::string& phi) {
  return LevelSet(phi);
}

LevelSetFunction level_set_function(const LevelSet& phi, int dim) {
  LevelSetFunction function(phi.expression(), dim, true);
  function.set_time(phi.time());
  return function;
}

}  // namespace neomesh
