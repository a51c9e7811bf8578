// A level set φ for fitting the mesh to an interface (Optimizer::adapt with a LevelSet,
// docs/adaptivity.md): φ < 0 on one side, φ > 0 on the other, the interface is φ = 0. A chain
// of mesh edges (2D) or surface of mesh faces (3D) is pulled onto that zero set. φ may move in
// time (set_time), like a SizeField's level set.
#pragma once

#include <string>
#include <vector>

namespace neomesh {

class LevelSet {
 public:
  // φ = |x − centre| − radius: a circle (2 centre coordinates) or sphere (3), radius > 0.
  static LevelSet sphere(const std::vector<double>& centre, double radius);
  // φ = (x − point)·normal: a line (2D) or plane (3D); the normal must not be zero.
  static LevelSet plane(const std::vector<double>& point, const std::vector<double>& normal);
  // φ(x, y, z, t) in muparser syntax, best a signed distance (z = 0 in 2D; t as set_time sets
  // it). Throws Error if it does not parse or uses other variables.
  static LevelSet expression(const std::string& phi);

  void set_time(double t) { time_ = t; }
  double time() const { return time_; }
  // The expression of φ (muparser), also for sphere() and plane().
  const std::string& expression() const { return expression_; }

 private:
  explicit LevelSet(std::string expression);
  std::string expression_;
  double time_ = 0.0;
};

}  // namespace neomesh
