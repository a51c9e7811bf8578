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
  std::string linear_solver = "amg";
  std::string riesz = "optimal";
  std::string hess_pc = "laplacian";
  std::optional<double> riesz_rtol;  // unset: SolverOptions' default, the thesis' with --thesis
  std::string boundary = "fixed";
  std::vector<std::string> shapes;  // --shape PART=SPEC
  double feature_angle = BoundaryOptions().feature_angle;
  bool no_practical = false;
  bool thesis = false;
};

void add_method_options(CLI::App& cmd, MethodOptions& options);

// The command line's spelling of a library option field ("energy.gauss_points" → "--gauss").
std::string option_name(const std::string& field);
// Runs `validate` and rethrows an OptionError as an Error naming the command-line option.
template <typename Validate>
void validate_options(Validate&& validate) {
  try {
    validate();
  } catch (const OptionError& e) {
    throw Error(option_name(e.field()) + " " + e.requirement());
  }
}

// `options` (SmoothOptions or AdaptOptions) with the method options of the command line: the
// names resolved, the thesis preset applied with --thesis, the ranges checked. Throws Error
// with a one-line message naming the option.
void resolve(const MethodOptions& method, EnergyOptions& energy, SolverOptions& solver,
             BoundaryOptions& boundary);
template <typename Options>
Options resolve(const MethodOptions& method, Options options) {
  resolve(method, options.energy, options.solver, options.boundary);
  if (method.thesis) options = Options::thesis(options);
  if (method.riesz_rtol) options.solver.riesz_rtol = *method.riesz_rtol;
  validate_options([&] { options.validate(); });
  return options;
}

}  // namespace neomesh::app
