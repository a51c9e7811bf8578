#include <neomesh/options.hpp>

#include <array>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <neomesh/error.hpp>

#include "api/option_table.hpp"
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
constexpr Choices<SurfaceGeometry, 2> kSurfaceGeometries{
    "surface geometry", {{{SurfaceGeometry::Cells, "cells"}, {SurfaceGeometry::Phong, "phong"}}}};
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
constexpr const auto& choices(SurfaceGeometry) {
  return kSurfaceGeometries;
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
template std::vector<std::string> choice_names<SurfaceGeometry>();
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
std::string_view name(SurfaceGeometry geometry) {
  return name_of(geometry);
}
SurfaceGeometry parse_surface_geometry(std::string_view name) {
  return parse_as<SurfaceGeometry>(name);
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

template <typename E>
E parse_choice(std::string_view name) {
  return parse_as<E>(name);
}
template BoundaryMode parse_choice(std::string_view);
template SurfaceGeometry parse_choice(std::string_view);
template LinearSolverKind parse_choice(std::string_view);
template RieszLaplacian parse_choice(std::string_view);
template HessianPreconditioner parse_choice(std::string_view);
template RejectedDirection parse_choice(std::string_view);
template SizeMode parse_choice(std::string_view);
template TargetMode parse_choice(std::string_view);

// The ranges of the fields are in their tables (src/api/option_table.cpp); what relates two
// fields is here.
void EnergyOptions::validate() const {
  check_ranges(energy_option_table(), *this);
}

void BoundaryOptions::validate() const {
  check_ranges(boundary_option_table(), *this);
  if (!shapes.empty() && mode != BoundaryMode::Slide)
    throw OptionError("boundary.shapes",
                      "need sliding boundary vertices (with fixed ones nothing slides on them)");
  for (const auto& [part, shape] : shapes)
    if (part.empty() || shape.empty())
      throw OptionError("boundary.shapes",
                        fmt::format("need a part name and a shape (got '{}' = '{}')", part, shape));
}

void SolverOptions::validate() const {
  check_ranges(solver_option_table(), *this);
}

void SizeFieldOptions::validate() const {
  check_ranges(size_field_option_table(), *this);
}

void PicardOptions::validate() const {
  check_ranges(picard_option_table(), *this);
}

namespace {

// What smoothing and adaptation share of the thesis' conventions: its quadrature, fixed
// boundary vertices (its H¹₀ setting), iterating to the defect tolerance, the Riesz solve to
// 1e-8, the δ̃ solve to the same tolerance at every step.
void use_thesis_method(EnergyOptions& energy, BoundaryOptions& boundary, SolverOptions& solver) {
  energy.gauss_points = EnergyOptions().gauss_points;
  boundary.mode = BoundaryMode::Fixed;
  boundary.shapes.clear();
  solver.advanced.alpha0 = SolverOptions::Advanced::kThesisAlpha0;
  solver.practical = false;
  solver.riesz_rtol = SolverOptions::kThesisRieszRtol;
  solver.advanced.hessian_forcing_max = 0.0;
  solver.advanced.max_trial_move = 0.0;
  solver.advanced.lazy_riesz = false;
  solver.advanced.rejected_direction = RejectedDirection::Antigradient;
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
  check_ranges(smooth_own_option_table(), *this);
}

AdaptOptions AdaptOptions::thesis(AdaptOptions o) {
  o.field.max_ratio = SizeFieldOptions::thesis().max_ratio;
  o.field.smoothing_passes = SizeFieldOptions::thesis().smoothing_passes;
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
  field.validate();
  picard.validate();
  check_ranges(adapt_own_option_table(), *this);
}

}  // namespace neomesh
