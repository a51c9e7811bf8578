#include "solver/curved_repair.hpp"

#include <gtest/gtest.h>

#include "geometry/curved_cell.hpp"

namespace neomesh {
namespace {

// The repair's budget counts Bézier coefficients: as many per cell as the expansion has.
TEST(CurvedRepair, ABezierSizeIsTheNumberOfCoefficientsOfTheCellsDeterminant) {
  for (CurvedType type : kCurvedTypes) {
    SCOPED_TRACE(std::string(name(type)));
    visit_curved_type(type, [&]<CurvedType Type>(CurvedTag<Type>) {
      typename CurvedTraits<Type>::Nodes x;
      for (int i = 0; i < CurvedTraits<Type>::nodes; ++i) x.col(i) = reference_node<Type>(i);
      EXPECT_EQ(jacobian_bezier_size(type),
                static_cast<int>(jacobian_bezier_coefficients<Type>(x).size()));
    });
  }
}

}  // namespace
}  // namespace neomesh
