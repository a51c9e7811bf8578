// Central finite differences for derivative tests: every analytic derivative in neomesh is
// checked against these. `x` is any fixed-size Eigen matrix, differentiated entry by entry in
// its storage order.
#pragma once

#include <Eigen/Dense>

namespace neomesh::testing {

// The relative error an analytic derivative may have against central differences with a step
// of 1e-6 times the problem's length scale.
inline constexpr double kFdTolerance = 1e-6;

// ∂f/∂x_k ≈ (f(x + h e_k) − f(x − h e_k)) / 2h, shaped like x.
template <typename Point, typename Function>
Point fd_gradient(Function&& f, Point x, double step) {
  Point g;
  for (int k = 0; k < x.size(); ++k) {
    const double saved = x.data()[k];
    x.data()[k] = saved + step;
    const double plus = f(x);
    x.data()[k] = saved - step;
    const double minus = f(x);
    x.data()[k] = saved;
    g.data()[k] = (plus - minus) / (2 * step);
  }
  return g;
}

// Column k ≈ (g(x + h e_k) − g(x − h e_k)) / 2h for a gradient g shaped like x.
template <typename Point, typename Gradient>
Eigen::Matrix<double, Point::SizeAtCompileTime, Point::SizeAtCompileTime> fd_jacobian(
    Gradient&& gradient, Point x, double step) {
  Eigen::Matrix<double, Point::SizeAtCompileTime, Point::SizeAtCompileTime> J;
  for (int k = 0; k < x.size(); ++k) {
    const double saved = x.data()[k];
    x.data()[k] = saved + step;
    const Point plus = gradient(x);
    x.data()[k] = saved - step;
    const Point minus = gradient(x);
    x.data()[k] = saved;
    J.col(k) = (plus - minus).reshaped() / (2 * step);
  }
  return J;
}

// ‖analytic − fd‖ / ‖analytic‖ (Frobenius): how far an analytic derivative is from its
// finite-difference approximation (or from any reference of the same shape).
template <typename A, typename B>
double relative_error(const A& analytic, const B& fd) {
  return (analytic - fd).norm() / analytic.norm();
}

}  // namespace neomesh::testing
