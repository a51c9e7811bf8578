#include "geometry/reference_cell.hpp"

#include "core/error.hpp"

namespace neomesh {

GaussRule1D gauss_legendre(int n) {
  GaussRule1D g;
  g.size = n;
  switch (n) {
    case 1:
      g.points = {0.0};
      g.weights = {2.0};
      break;
    case 2: {
      const double a = 1.0 / std::sqrt(3.0);
      g.points = {-a, a};
      g.weights = {1.0, 1.0};
      break;
    }
    case 3: {
      const double a = std::sqrt(3.0 / 5.0);
      g.points = {-a, 0.0, a};
      g.weights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
      break;
    }
    case 4: {
      const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
      const double b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
      const double wa = (18.0 + std::sqrt(30.0)) / 36.0;
      const double wb = (18.0 - std::sqrt(30.0)) / 36.0;
      g.points = {-b, -a, a, b};
      g.weights = {wb, wa, wa, wb};
      break;
    }
    case 5: {
      const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
      const double b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
      const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
      const double wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
      g.points = {-b, -a, 0.0, a, b};
      g.weights = {wb, wa, 128.0 / 225.0, wa, wb};
      break;
    }
    default:
      fail("Gauss rule with {} points per direction is not available (use 1 to 5)", n);
  }
  return g;
}

}  // namespace neomesh
