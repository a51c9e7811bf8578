// Options of the optimization method shared by `smooth` and `adapt`: the energy (λ, μ, κ,
// quadrature), the boundary (fixed or sliding vertices), the quasi-Newton method (α₀, η, k_min,
// tolerances) and the linear solvers. The command line writes them into the library's option
// structs (include/neomesh/options.hpp); what it cannot say as a number is a name resolved here.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <neomesh/error.hpp>
#include <neomesh/options.hpp>

namespace neomesh::app {

struct MethodOptions {
  EnergyOptions energy;
  SolverOptions solver;
  std::string linear_solver{name(SolverOptions().linear_solver)};
  std::string rejected_direction{name(SolverOptions().rejected_direction)};
  std::string riesz{name(SolverOptions().riesz)};
  std::string hess_pc{name(SolverOptions().hessian_pc)};
  // Unset: SolverOptions' defaults, the thesis' with --thesis.
  std::optional<double> riesz_rtol, hessian_forcing_max, max_trial_move;
  std::string boundary{name(BoundaryOptions().mode)};
  std::vector<std::string> shapes;  // --shape PART=SPEC
  double feature_angle = BoundaryOptions().feature_angle;
  bool no_practical = false;
  bool riesz_every_step = false;
  bool thesis = false;
};

void add_method_options(CLI::App& cmd, MethodOptions& options);

// A library error about an option begins with the option's field path ("solver.eta must be
// ...", "boundary.shapes: ..."): the message with the command line's spelling instead
// ("--eta must be ...", "--shape: ...").
std::string cli_message(const std::string& message);

// `options` (SmoothOptions or AdaptOptions) with the method options of the command line: the
// names resolved, the thesis preset applied with --thesis, the ranges checked (OptionError).
void resolve(const MethodOptions& method, EnergyOptions& energy, SolverOptions& solver,
             BoundaryOptions& boundary);
template <typename Options>
Options resolve(const MethodOptions& method, Options options) {
  resolve(method, options.energy, options.solver, options.boundary);
  if (method.thesis) options = Options::thesis(options);
  if (method.riesz_rtol) options.solver.riesz_rtol = *method.riesz_rtol;
  if (method.hessian_forcing_max) options.solver.hessian_forcing_max = *method.hessian_forcing_max;
  if (method.max_trial_move) options.solver.max_trial_move = *method.max_trial_move;
  if (method.solver.alpha0) options.solver.alpha0 = method.solver.alpha0;  // over --thesis' 0.3
  options.validate();
  return options;
}

}  // namespace neomesh::app
