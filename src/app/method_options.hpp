// Options of the optimization method shared by `smooth` and `adapt`: the energy (λ, μ, κ,
// quadrature), the boundary (fixed or sliding vertices), the quasi-Newton method (α₀, η, k_min,
// tolerances) and the linear solvers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "boundary/boundary.hpp"
#include "energy/functional.hpp"
#include "solver/quasi_newton.hpp"

namespace neomesh::app {

struct MethodOptions {
  EnergyOptions energy;
  QuasiNewtonOptions solver;
  std::string linear_solver = "amg";
  std::string riesz = "optimal";
  std::string hess_pc = "laplacian";
  std::optional<double>
      riesz_rtol;                   // unset: QuasiNewtonOptions' default, the thesis' with --thesis
  std::string boundary = "fixed";   // resolved into boundary_options by finalize()
  std::vector<std::string> shapes;  // --shape PART=SPEC, resolved likewise
  BoundaryOptions boundary_options;
  bool no_practical = false;
  bool thesis = false;
};

void add_method_options(CLI::App& cmd, MethodOptions& options);
// Checks ranges and resolves names; throws Error with a one-line message naming the option.
void finalize(MethodOptions& options);

}  // namespace neomesh::app
