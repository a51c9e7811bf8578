#include <neomesh/options.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <neomesh/error.hpp>

#include "core/error.hpp"

namespace neomesh {

namespace {

// Each choice of an option has one name, the command line's and the report's; each enum has
// one table of them, with the noun its errors use.
template <typename E>
struct Choice {
  E value;
  std::string_view name;
};

template <typename E, std::size_t N>
struct Choices {
  std::string_view what;  // "unknown <what> 'x'"
  std::array<Choice<E>, N> list;
};

constexpr Choices<BoundaryMode, 2> kBoundaryModes{
    "boundary mode", {{{BoundaryMode::Fixed, "fixed"}, {BoundaryMode::Slide, "slide"}}}};
constexpr Choices<LinearSolverKind, 3> kLinearSolvers{"linear solver",
                                                      {{{LinearSolverKind::Amg, "amg"},
                                                        {LinearSolverKind::Jacobi, "jacobi"},
                                                        {LinearSolverKind::Direct, "direct"}}}};
constexpr Choices<RieszLaplacian, 2> kRieszLaplacians{
    "Riesz Laplacian",
    {{{RieszLaplacian::OptimalCells, "optimal"}, {RieszLaplacian::CurrentMesh, "current"}}}};
constexpr Choices<HessianPreconditioner, 2> kHessianPreconditioners{
    "quasi-Newton preconditioner",
    {{{HessianPreconditioner::Laplacian, "laplacian"},
      {HessianPreconditioner::Hessian, "hessian"}}}};
constexpr Choices<RejectedDirection, 2> kRejectedDirections{
    "rejected direction",
    {{{RejectedDirection::Blend, "blend"}, {RejectedDirection::Antigradient, "antigradient"}}}};
constexpr Choices<SizeMode, 3> kSizeModes{"size mode",
                                          {{{SizeMode::Smoothed, "smoothed"},
                                            {SizeMode::Input, "input"},
                                            {SizeMode::Uniform, "uniform"}}}};
constexpr Choices<TargetMode, 3> kTargetModes{"target mode",
                                              {{{TargetMode::Smoothed, "smoothed"},
                                                {TargetMode::Ideal, "ideal"},
                                                {TargetMode::Input, "input"}}}};

// The table of an enum, found by overload.
constexpr const auto& choices(BoundaryMode) {
  return kBoundaryModes;
}
constexpr const auto& choices(LinearSolverKind) {
  return kLinearSolvers;
}
constexpr const auto& choices(RieszLaplacian) {
  return kRieszLaplacians;
}
constexpr const auto& choices(HessianPreconditioner) {
  return kHessianPreconditioners;
}
constexpr const auto& choices(RejectedDirection) {
  return kRejectedDirections;
}
constexpr const auto& choices(SizeMode) {
  return kSizeModes;
}
constexpr const auto& choices(TargetMode) {
  return kTargetModes;
}

template <typename E>
std::string_view name_of(E value) {
  for (const Choice<E>& c : choices(value).list)
    if (c.value == value) return c.name;
  return "?";
}

// The choice named `given`, or Error "unknown <what> 'x' (use a, b or c)".
template <typename E>
E parse_as(std::string_view given) {
  const auto& table = choices(E{});
  std::string list;
  for (std::size_t i = 0; i < table.list.size(); ++i) {
    if (table.list[i].name == given) return table.list[i].value;
    list += fmt::format("{}{}",
                        i == 0                       ? ""
                        : i + 1 == table.list.size() ? " or "
                                                     : ", ",
                        table.list[i].name);
  }
  fail("unknown {} '{}' (use {})", table.what, given, list);
}

}  // namespace

template <typename E>
std::vector<std::string> choice_names() {
  std::vector<std::string> names;
  for (const Choice<E>& c : choices(E{}).list) names.emplace_back(c.name);
  return names;
}
template std::vector<std::string> choice_names<BoundaryMode>();
template std::vector<std::string> choice_names<LinearSolverKind>();
template std::vector<std::string> choice_names<RieszLaplacian>();
template std::vector<std::string> choice_names<HessianPreconditioner>();
template std::vector<std::string> choice_names<RejectedDirection>();
template std::vector<std::string> choice_names<SizeMode>();
template std::vector<std::string> choice_names<TargetMode>();

std::string_view name(BoundaryMode mode) {
  return name_of(mode);
}
BoundaryMode parse_boundary_mode(std::string_view name) {
  return parse_as<BoundaryMode>(name);
}
std::string_view name(LinearSolverKind kind) {
  return name_of(kind);
}
LinearSolverKind parse_linear_solver(std::string_view name) {
  return parse_as<LinearSolverKind>(name);
}
std::string_view name(RieszLaplacian kind) {
  return name_of(kind);
}
RieszLaplacian parse_riesz_laplacian(std::string_view name) {
  return parse_as<RieszLaplacian>(name);
}
std::string_view name(HessianPreconditioner kind) {
  return name_of(kind);
}
HessianPreconditioner parse_hessian_preconditioner(std::string_view name) {
  return parse_as<HessianPreconditioner>(name);
}
std::string_view name(RejectedDirection direction) {
  return name_of(direction);
}
RejectedDirection parse_rejected_direction(std::string_view name) {
  return parse_as<RejectedDirection>(name);
}
std::string_view name(SizeMode mode) {
  return name_of(mode);
}
SizeMode parse_size_mode(std::string_view name) {
  return parse_as<SizeMode>(name);
}
std::string_view name(TargetMode mode) {
  return name_of(mode);
}
TargetMode parse_target_mode(std::string_view name) {
  return parse_as<TargetMode>(name);
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
