#include <neomesh/options.hpp>

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <neomesh/error.hpp>

#include "core/error.hpp"

namespace neomesh {

namespace {

// Each choice of an option has one name, the command line's and the report's.
template <typename E>
struct Choice {
  E value;
  std::string_view name;
};

constexpr Choice<BoundaryMode> kBoundaryModes[] = {{BoundaryMode::Fixed, "fixed"},
                                                   {BoundaryMode::Slide, "slide"}};
constexpr Choice<LinearSolverKind> kLinearSolvers[] = {{LinearSolverKind::Amg, "amg"},
                                                       {LinearSolverKind::Jacobi, "jacobi"},
                                                       {LinearSolverKind::Direct, "direct"}};
constexpr Choice<RieszLaplacian> kRieszLaplacians[] = {{RieszLaplacian::OptimalCells, "optimal"},
                                                       {RieszLaplacian::CurrentMesh, "current"}};
constexpr Choice<HessianPreconditioner> kHessianPreconditioners[] = {
    {HessianPreconditioner::Laplacian, "laplacian"}, {HessianPreconditioner::Hessian, "hessian"}};
constexpr Choice<RejectedDirection> kRejectedDirections[] = {
    {RejectedDirection::Blend, "blend"}, {RejectedDirection::Antigradient, "antigradient"}};
constexpr Choice<SizeMode> kSizeModes[] = {
    {SizeMode::Smoothed, "smoothed"}, {SizeMode::Input, "input"}, {SizeMode::Uniform, "uniform"}};
constexpr Choice<TargetMode> kTargetModes[] = {
    {TargetMode::Smoothed, "smoothed"}, {TargetMode::Ideal, "ideal"}, {TargetMode::Input, "input"}};

template <typename E, std::size_t N>
std::string_view name_in(const Choice<E> (&choices)[N], E value) {
  for (const Choice<E>& c : choices)
    if (c.value == value) return c.name;
  return "?";
}

template <typename E, std::size_t N>
std::vector<std::string> names_in(const Choice<E> (&choices)[N]) {
  std::vector<std::string> names;
  for (const Choice<E>& c : choices) names.emplace_back(c.name);
  return names;
}

// The choice named `given`, or Error "unknown <what> 'x' (use a, b or c)".
template <typename E, std::size_t N>
E parse_in(const Choice<E> (&choices)[N], std::string_view what, std::string_view given) {
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (choices[i].name == given) return choices[i].value;
    list += fmt::format("{}{}", i == 0 ? "" : i + 1 == N ? " or " : ", ", choices[i].name);
  }
  fail("unknown {} '{}' (use {})", what, given, list);
}

}  // namespace

std::string_view name(BoundaryMode mode) {
  return name_in(kBoundaryModes, mode);
}
BoundaryMode parse_boundary_mode(std::string_view name) {
  return parse_in(kBoundaryModes, "boundary mode", name);
}
std::string_view name(LinearSolverKind kind) {
  return name_in(kLinearSolvers, kind);
}
LinearSolverKind parse_linear_solver(std::string_view name) {
  return parse_in(kLinearSolvers, "linear solver", name);
}
std::string_view name(RieszLaplacian kind) {
  return name_in(kRieszLaplacians, kind);
}
RieszLaplacian parse_riesz_laplacian(std::string_view name) {
  return parse_in(kRieszLaplacians, "Riesz Laplacian", name);
}
std::string_view name(HessianPreconditioner kind) {
  return name_in(kHessianPreconditioners, kind);
}
HessianPreconditioner parse_hessian_preconditioner(std::string_view name) {
  return parse_in(kHessianPreconditioners, "quasi-Newton preconditioner", name);
}
std::string_view name(RejectedDirection direction) {
  return name_in(kRejectedDirections, direction);
}
RejectedDirection parse_rejected_direction(std::string_view name) {
  return parse_in(kRejectedDirections, "rejected direction", name);
}
std::string_view name(SizeMode mode) {
  return name_in(kSizeModes, mode);
}
SizeMode parse_size_mode(std::string_view name) {
  return parse_in(kSizeModes, "size mode", name);
}
std::string_view name(TargetMode mode) {
  return name_in(kTargetModes, mode);
}
TargetMode parse_target_mode(std::string_view name) {
  return parse_in(kTargetModes, "target mode", name);
}

template <>
std::vector<std::string> choice_names<BoundaryMode>() {
  return names_in(kBoundaryModes);
}
template <>
std::vector<std::string> choice_names<LinearSolverKind>() {
  return names_in(kLinearSolvers);
}
template <>
std::vector<std::string> choice_names<RieszLaplacian>() {
  return names_in(kRieszLaplacians);
}
template <>
std::vector<std::string> choice_names<HessianPreconditioner>() {
  return names_in(kHessianPreconditioners);
}
template <>
std::vector<std::string> choice_names<RejectedDirection>() {
  return names_in(kRejectedDirections);
}
template <>
std::vector<std::string> choice_names<SizeMode>() {
  return names_in(kSizeModes);
}
template <>
std::vector<std::string> choice_names<TargetMode>() {
  return names_in(kTargetModes);
}

namespace {

// Throws OptionError for `field` unless `value` is finite and `ok`: "<field> must be <range>
// (got <value>)". inf and nan are refused so that they never reach the method (an infinite λ
// would make every cell look inverted).
template <typename T>
void require(bool ok, const char* field, T value, const char* range) {
  if (!std::isfinite(static_cast<double>(value)))
    throw OptionError(field, fmt::format("must be a finite number, {} (got {})", range, value));
  if (!ok) throw OptionError(field, fmt::format("must be {} (got {})", range, value));
}

}  // namespace

void EnergyOptions::validate() const {
  require(lambda > 0, "energy.lambda", lambda, "positive");
  require(mu > 0, "energy.mu", mu, "positive");
  require(kappa == -1.0 || kappa > 0, "energy.kappa", kappa, "positive (or -1 for kappa = lambda)");
  require(gauss_points >= 1 && gauss_points <= 5, "energy.gauss_points", gauss_points,
          "between 1 and 5");
}

void BoundaryOptions::validate() const {
  require(feature_angle > 0 && feature_angle < 180, "boundary.feature_angle", feature_angle,
          "in (0, 180) degrees");
  if (!shapes.empty() && mode != BoundaryMode::Slide)
    throw OptionError("boundary.shapes",
                      "need sliding boundary vertices (with fixed ones nothing slides on them)");
  for (const auto& [part, shape] : shapes)
    if (part.empty() || shape.empty())
      throw OptionError("boundary.shapes",
                        fmt::format("need a part name and a shape (got '{}' = '{}')", part, shape));
}

void SolverOptions::validate() const {
  if (alpha0) require(*alpha0 > 0 && *alpha0 <= 1, "solver.alpha0", *alpha0, "in (0, 1]");
  require(eta > 0 && eta < 1, "solver.eta", eta, "in (0, 1)");
  require(kmin >= 0, "solver.kmin", kmin, "0 or more");
  require(max_iterations >= 1, "solver.max_iterations", max_iterations, "at least 1");
  require(time_limit >= 0, "solver.time_limit", time_limit, "0 (none) or more seconds");
  require(defect_atol >= 0, "solver.defect_atol", defect_atol, "0 or more");
  require(defect_rtol >= 0, "solver.defect_rtol", defect_rtol, "0 or more");
  require(energy_rtol >= 0, "solver.energy_rtol", energy_rtol, "0 or more");
  require(move_rtol >= 0, "solver.move_rtol", move_rtol, "0 or more");
  require(newton_move_rtol >= 0, "solver.newton_move_rtol", newton_move_rtol, "0 or more");
  require(armijo_beta > 0 && armijo_beta < 1, "solver.armijo_beta", armijo_beta, "in (0, 1)");
  require(max_halvings >= 1, "solver.max_halvings", max_halvings, "at least 1");
  require(max_trial_move >= 0, "solver.max_trial_move", max_trial_move, "0 or more");
  require(initial_previous_defect > 0, "solver.initial_previous_defect", initial_previous_defect,
          "positive");
  require(hessian_rtol > 0 && hessian_rtol < 1, "solver.hessian_rtol", hessian_rtol, "in (0, 1)");
  require(hessian_defect_factor > 0, "solver.hessian_defect_factor", hessian_defect_factor,
          "positive");
  require(hessian_forcing_max >= 0 && hessian_forcing_max < 1, "solver.hessian_forcing_max",
          hessian_forcing_max, "in [0, 1)");
  require(riesz_rtol > 0 && riesz_rtol < 1, "solver.riesz_rtol", riesz_rtol, "in (0, 1)");
  require(hessian_pc_reuse >= 0, "solver.hessian_pc_reuse", hessian_pc_reuse, "0 or more");
}

void SizeFieldOptions::validate() const {
  require(power > 0, "sizes.power", power, "positive");
  require(floor >= 0, "sizes.floor", floor, "0 or more");
  if (max_ratio)
    require(*max_ratio == 0 || *max_ratio > 1, "sizes.max_ratio", *max_ratio,
            "above 1, or 0 for no bound");
  require(smoothing_passes >= 0, "sizes.smoothing_passes", smoothing_passes, "0 or more");
}

void PicardOptions::validate() const {
  require(min_updates >= 0, "picard.min_updates", min_updates, "0 or more");
  require(update_every >= 1, "picard.update_every", update_every, "at least 1");
  require(update_move >= 0, "picard.update_move", update_move, "0 or more");
  require(update_step_norm >= 0, "picard.update_step_norm", update_step_norm, "0 or more");
  require(relaxation > 0 && relaxation <= 1, "picard.relaxation", relaxation, "in (0, 1]");
}

namespace {

// What smoothing and adaptation share of the thesis' conventions: its quadrature, fixed
// boundary vertices (its H¹₀ setting), iterating to the defect tolerance, the Riesz solve to
// 1e-8, the δ̃ solve to the same tolerance at every step.
void use_thesis_method(EnergyOptions& energy, BoundaryOptions& boundary, SolverOptions& solver) {
  energy.gauss_points = EnergyOptions().gauss_points;
  boundary.mode = BoundaryMode::Fixed;
  boundary.shapes.clear();
  solver.alpha0 = SolverOptions::kThesisAlpha0;
  solver.practical = false;
  solver.riesz_rtol = SolverOptions::kThesisRieszRtol;
  solver.hessian_forcing_max = 0.0;
  solver.max_trial_move = 0.0;
  solver.lazy_riesz = false;
  solver.rejected_direction = RejectedDirection::Antigradient;
}

}  // namespace

SmoothOptions SmoothOptions::thesis(SmoothOptions o) {
  use_thesis_method(o.energy, o.boundary, o.solver);
  o.sizes = SizeMode::Uniform;
  o.targets = TargetMode::Ideal;
  o.quality_guard = false;
  return o;
}

void SmoothOptions::validate() const {
  energy.validate();
  boundary.validate();
  solver.validate();
}

AdaptOptions AdaptOptions::thesis(AdaptOptions o) {
  o.sizes.max_ratio = SizeFieldOptions::thesis().max_ratio;
  o.sizes.smoothing_passes = SizeFieldOptions::thesis().smoothing_passes;
  o.energy.lambda = 1.0;
  o.energy.mu = 10.0;
  use_thesis_method(o.energy, o.boundary, o.solver);
  o.picard = PicardOptions::thesis();
  o.quality_guard = false;
  return o;
}

void AdaptOptions::validate() const {
  energy.validate();
  boundary.validate();
  solver.validate();
  sizes.validate();
  picard.validate();
  require(warm_updates >= 0, "warm_updates", warm_updates, "0 or more");
}

}  // namespace neomesh
