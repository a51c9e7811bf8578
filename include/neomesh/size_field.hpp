// A size field for adaptation (thesis §6, docs/method.md §5): the desired *relative* volume of
// a cell from the position of its centroid, v_K = floor + d(c_K)^p, where d is the distance to
// a target surface (circle/sphere, plane, the surface of an axis-aligned box, or |φ| of a
// level-set expression φ(x, y, z, t)), or per-cell values given directly. A level set may move
// in time (set_time).
//
// An anisotropic field is a metric M(x), a symmetric positive definite dim × dim matrix: a cell
// is as the field wants it where it is the unit cell in M, of size 1/√λ along each eigenvector of
// M with eigenvalue λ (Mmg's and Gmsh's convention). Adaptation then aims each cell at the ideal
// cell stretched by M^(-1/2) at its centroid, of relative volume det(M)^(-1/2) (docs/method.md,
// "Metric fields"); only the ratios of sizes matter, since the number of cells is fixed.
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <neomesh/options.hpp>

namespace neomesh {

class Mesh;

// The metric of SizeField::stretched: cells of size `normal` across the target surface and
// `tangent` along it, within `width` of it; farther away the size across grows by `grading` per
// unit distance until the cells are isotropic of size `tangent`. r-adaptivity moves a fixed
// number of cells, and a gentle grading spends most of them on the transition: Mmg's 0.3 left
// the band's cells as large as isotropic adaptation does; 4 halves the interpolation error of a
// front there (docs/method.md §9, "Metric fields").
struct Stretch {
  double normal = 0.0, tangent = 0.0;  // 0 < normal ≤ tangent
  double width = 0.0;                  // ≥ 0
  double grading = 4.0;                // > 0
};

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
  // A caller's distance function evaluated on all points at once (one call per evaluation of
  // the field, e.g. a numpy function): it gets n points, `dim` values each (the local cells'
  // centroids), and writes their n signed distances d. `dim` 0: a field of any dimension.
  // An exception it throws goes through the optimization to the caller.
  using Distances = std::function<void(std::span<const double> points, std::span<double> d)>;
  static SizeField distances(Distances distances, const std::string& description, int dim = 0);
  // Relative volumes per cell, indexed by the cell's number in the input mesh.
  static SizeField cell_values(std::vector<double> values);
  // One value per line, in the input mesh's cell order.
  static SizeField read_cell_values(const std::filesystem::path& file);
  // The metric whose entries are the expressions m11, m12, m22 (2D) or m11, m12, m13, m22, m23,
  // m33 (3D) in x, y, z, t (muparser syntax; the upper triangle of the symmetric M). Adapting to
  // it throws Error naming the cell where M is not positive definite.
  static SizeField metric(const std::vector<std::string>& entries);

  // The metric `mesh`'s input file gives per vertex in its point-data array `array` (VTK point
  // data, Gmsh $NodeData, Exodus nodal variables): 3 components in 2D (m11 m12 m22) or 6 in 3D
  // (m11 m12 m13 m22 m23 m33), or the dim² of the whole matrix. Between the vertices it is
  // interpolated linearly in log M over the mesh as it is now (adaptation moves the vertices
  // over it; src/targets/background_metric.hpp). Throws Error for a missing array, another number
  // of components or a vertex whose metric is not symmetric positive definite (naming it).
  // Collective; every process holds the whole mesh and its metrics.
  static SizeField vertex_metric(const Mesh& mesh, const std::string& array);
  // The same from a text file of one metric per line, in the mesh's vertex order (the input
  // file's), 3 or 6 numbers (or dim²) per line; Error for a file of another length.
  static SizeField read_vertex_metric(const Mesh& mesh, const std::filesystem::path& file);

  // This distance field (not per-cell values) made anisotropic: the metric of `stretch` about
  // its target surface, the surface's normal taken from the gradient of its signed distance.
  SizeField stretched(const Stretch& stretch) const;
  // A metric field (metric() or stretched()): adaptation aims at target shapes, not only volumes.
  bool anisotropic() const { return static_cast<bool>(metric_); }

  // The time t of a level-set expression (a geometry that moves); other fields ignore it.
  void set_time(double t);

  // A one-line description for the run's summary ("distance to the sphere ...").
  const std::string& description() const { return description_; }

 private:
  friend struct SizeFieldAccess;  // src/targets/size_field.cpp evaluates the field on a mesh
  using Distance = std::function<double(std::span<const double> point)>;
  // M at a point, dim × dim (column-major) into the second argument.
  using Metric = std::function<void(std::span<const double> point, std::span<double> m)>;
  SizeField(std::string description, int dim, Distance signed_distance);

  std::string description_;
  int dim_ = 0;               // dimension the field needs, 0 for any
  Distance signed_distance_;  // negative on one side of the target surface; d = its magnitude
  Metric metric_;             // for an anisotropic field; empty otherwise
  Distances distances_;       // for distances() (signed_distance_ then calls it per point)
  std::vector<double> cell_values_;       // for cell_values(); empty otherwise
  std::function<void(double)> set_time_;  // for level_set(); empty otherwise
};

}  // namespace neomesh
