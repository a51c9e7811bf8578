// Finite-difference checks of a Functional's derivatives, shared by the Functional's tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "energy/functional.hpp"

namespace neomesh::testing {

constexpr double kFdTolerance = 1e-6;  // relative error allowed against central differences

inline double entry(Vec v, PetscInt i) {
  VecReadView view(v);
  return view[i];
}

inline void set_entry(Vec v, PetscInt i, double value) {
  VecWriteView view(v);
  view[i] = value;
}

inline double norm(Vec v) {
  PetscReal n = 0.0;
  NM_PETSC(VecNorm(v, NORM_2, &n));
  return n;
}

// Expects the gradient at x to match central differences of the value at the free dofs (and to
// be zero at the others), to kFdTolerance relative to its norm.
inline void expect_gradient_matches_differences(const Functional& f, Vec x,
                                                const std::function<bool(PetscInt)>& free) {
  const DofMap& dofs = f.dofs();
  OwnedVec gradient = dofs.create_global_vector(), fd = dofs.create_global_vector();
  ASSERT_TRUE(std::isfinite(f.value_and_gradient(x, gradient)));
  const double step = 1e-7;
  for (PetscInt i = 0; i < dofs.num_global_dofs(); ++i) {
    if (!free(i)) {
      EXPECT_EQ(entry(gradient, i), 0.0);
      continue;
    }
    const double saved = entry(x, i);
    set_entry(x, i, saved + step);
    const double plus = f.value(x);
    set_entry(x, i, saved - step);
    const double minus = f.value(x);
    set_entry(x, i, saved);
    set_entry(fd, i, (plus - minus) / (2 * step));
  }
  NM_PETSC(VecAXPY(fd, -1.0, gradient));
  EXPECT_LT(norm(fd), kFdTolerance * norm(gradient));
}

// Expects H(1) at x to match central differences of the gradient (the identity's columns at the
// fixed dofs), to kFdTolerance in the Frobenius norm, and to be exactly symmetric.
inline void expect_hessian_matches_differences(const Functional& f, Vec x,
                                               const std::function<bool(PetscInt)>& free) {
  const DofMap& dofs = f.dofs();
  OwnedMat H = f.create_matrix();
  f.assemble_hessian(x, 1.0, H);
  OwnedVec unit = dofs.create_global_vector(), column = dofs.create_global_vector();
  OwnedVec plus = dofs.create_global_vector(), minus = dofs.create_global_vector();
  const double step = 1e-7;
  double error = 0.0, size = 0.0;  // Frobenius norms over all columns
  for (PetscInt j = 0; j < dofs.num_global_dofs(); ++j) {
    set_entry(unit, j, 1.0);
    NM_PETSC(MatMult(H, unit, column));
    set_entry(unit, j, 0.0);
    if (free(j)) {
      const double saved = entry(x, j);
      set_entry(x, j, saved + step);
      f.value_and_gradient(x, plus);
      set_entry(x, j, saved - step);
      f.value_and_gradient(x, minus);
      set_entry(x, j, saved);
      NM_PETSC(VecAXPY(plus, -1.0, minus));
      NM_PETSC(VecScale(plus, 1.0 / (2 * step)));  // central difference of the gradient
    } else {
      NM_PETSC(VecZeroEntries(plus));  // a fixed dof's column is the identity's
      set_entry(plus, j, 1.0);
    }
    size += std::pow(norm(column), 2);
    NM_PETSC(VecAXPY(plus, -1.0, column));
    error += std::pow(norm(plus), 2);
  }
  EXPECT_LT(std::sqrt(error), kFdTolerance * std::sqrt(size));
  PetscBool symmetric = PETSC_FALSE;
  NM_PETSC(MatIsSymmetric(H, 0.0, &symmetric));
  EXPECT_TRUE(symmetric);
}

}  // namespace neomesh::testing
