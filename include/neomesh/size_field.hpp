// A size field for adaptation (thesis §6, docs/method.md §5): the desired *relative* volume of
// a cell from the position of its centroid, v_K = floor + d(c_K)^p, where d is the distance to
// a target surface (circle/sphere, plane, the surface of an axis-aligned box, or |φ| of a
// level-set expression φ(x, y, z, t)), or per-cell values given directly. A level set may move
// in time (set_time).
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <neomesh/options.hpp>

namespace neomesh {

class SizeField {
 public:
  // Distance to the circle (2 centre coordinates) or sphere (3) of radius `radius` > 0:
  // d = | |x − centre| − radius |.
  static SizeField sphere(std::vector<double> centre, double radius);
  // Distance to the line/plane through `point` with normal `normal` (2 or 3 coordinates).
  static SizeField plane(std::vector<double> point, std::vector<double> normal);
  // Distance to the surface of the axis-aligned box [lower, upper] (inside and outside).
  static SizeField box(std::vector<double> lower, std::vector<double> upper);
  // d = |φ(x, y, z, t)| for a signed-distance expression φ (muparser syntax; z = 0 in 2D; t is
  // the time set by set_time, 0 until then).
  static SizeField level_set(const std::string& expression);
  // Relative volumes per cell, indexed by the cell's number in the input mesh.
  static SizeField cell_values(std::vector<double> values);
  // One value per line, in the input mesh's cell order.
  static SizeField read_cell_values(const std::filesystem::path& file);

  // The time t of a level-set expression (a geometry that moves); other fields ignore it.
  void set_time(double t);

  // A one-line description for the run's summary ("distance to the sphere ...").
  const std::string& description() const { return description_; }

 private:
  friend struct SizeFieldAccess;  // src/adapt/size_field.cpp evaluates the field on a mesh
  using Distance = std::function<double(std::span<const double> point)>;
  SizeField(std::string description, int dim, Distance distance);

  std::string description_;
  int dim_ = 0;  // dimension the field needs, 0 for any
  Distance distance_;
  std::vector<double> cell_values_;       // for cell_values(); empty otherwise
  std::function<void(double)> set_time_;  // for level_set(); empty otherwise
};

}  // namespace neomesh
