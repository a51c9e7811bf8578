#include "api/option_table.hpp"

#include <cmath>

#include <fmt/format.h>

#include <neomesh/error.hpp>

namespace neomesh {

namespace {

// The ranges, in the words of the messages "<path> must be <text> (got <value>)".
constexpr Range kPositive{"positive", [](double x) { return x > 0; }};
constexpr Range kNonNegative{"0 or more", [](double x) { return x >= 0; }};
constexpr Range kAtLeastOne{"at least 1", [](double x) { return x >= 1; }};
constexpr Range kOpenUnit{"in (0, 1)", [](double x) { return x > 0 && x < 1; }};
constexpr Range kUpToOne{"in (0, 1]", [](double x) { return x > 0 && x <= 1; }};

constexpr std::string_view kEnergyGroup = "Energy (thesis §4)";
constexpr std::string_view kMethodGroup = "Quasi-Newton method (thesis §5.1)";
constexpr std::string_view kLinearGroup = "Linear solvers (PETSc prefixes -hess_ and -riesz_)";
constexpr std::string_view kBoundaryGroup = "Boundary (docs/boundary.md)";

// `table`'s entries as options of `Task`, whose member `part` holds them; the report shows
// them in its object `object`.
template <typename Task, typename Part>
void append(OptionTable<Task>& to, Part Task::*part, const OptionTable<Part>& table,
            std::string_view object) {
  for (const OptionSpec<Part>& spec : table) {
    OptionSpec<Task> lifted{.path = spec.path,
                            .flag = spec.flag,
                            .help = spec.help,
                            .group = spec.group,
                            .field = Preset{},
                            .range = spec.range,
                            .negated = spec.negated,
                            .shown_default = spec.shown_default,
                            .report_key = spec.report_key,
                            .reported = {},
                            .report_object = object};
    lifted.field = std::visit(
        [part](const auto& access) -> FieldRef<Task> {
          using A = std::decay_t<decltype(access)>;
          if constexpr (std::is_same_v<A, Preset>) {
            return Preset{};
          } else {
            using T = std::remove_reference_t<std::invoke_result_t<A, Part&>>;
            return Access<Task, T>([part, access](Task& t) -> T& { return access(t.*part); });
          }
        },
        spec.field);
    if (spec.reported)
      lifted.reported = [part, reported = spec.reported](const Task& t) {
        return reported(t.*part);
      };
    to.push_back(std::move(lifted));
  }
}

// --thesis, an option of both tasks.
template <typename Task>
OptionSpec<Task> thesis_flag() {
  return {.path = "thesis",
          .flag = "--thesis",
          .help =
              "the thesis' conventions: uniform desired volumes, fixed boundary vertices, no "
              "practical stopping criterion (iterate to the defect tolerance), Riesz solve to "
              "1e-8, 3 Gauss points per direction, antigradient steps where the angle test "
              "fails; options given explicitly win over it; default: off",
          .group = kMethodGroup,
          .field = Preset{}};
}

// Throws OptionError for `path` unless `value` is finite and in `range`. inf and nan are
// refused so that they never reach the method (an infinite λ would make every cell look
// inverted).
template <typename T>
void require(std::string_view path, T value, const Range& range) {
  const std::string field(path);
  if (!std::isfinite(static_cast<double>(value)))
    throw OptionError(field,
                      fmt::format("must be a finite number, {} (got {})", range.text, value));
  if (!range.ok(static_cast<double>(value)))
    throw OptionError(field, fmt::format("must be {} (got {})", range.text, value));
}

}  // namespace

const OptionTable<EnergyOptions>& energy_option_table() {
  using O = EnergyOptions;
  static const OptionTable<O> table = {
      {.path = "energy.lambda",
       .flag = "--lambda",
       .help = "λ > 0: weight of (log det G)², resists volume change",
       .group = kEnergyGroup,
       .field = member(&O::lambda),
       .range = kPositive},
      {.path = "energy.mu",
       .flag = "--mu",
       .help = "μ > 0: weight of the shape terms",
       .group = kEnergyGroup,
       .field = member(&O::mu),
       .range = kPositive},
      {.path = "energy.kappa",
       .flag = "--kappa",
       .help = "κ > 0: penalty on cells grown beyond e^(μ/λ+1) × their desired volume",
       .group = kEnergyGroup,
       .field = member(&O::kappa),
       .range = {"positive (or -1 for kappa = lambda)",
                 [](double x) { return x == -1.0 || x > 0; }},
       .shown_default = "lambda",
       .reported = [](const O& o) { return o.effective_kappa(); }},
      {.path = "energy.gauss_points",
       .flag = "--gauss",
       .help = "Gauss points per direction on quadrilaterals/hexahedra/wedges/pyramids (1-5)",
       .group = kEnergyGroup,
       .field = member(&O::gauss_points),
       .range = {"between 1 and 5", [](double x) { return x >= 1 && x <= 5; }}},
  };
  return table;
}

const OptionTable<BoundaryOptions>& boundary_option_table() {
  using O = BoundaryOptions;
  static const OptionTable<O> table = {
      {.path = "boundary.mode",
       .flag = "--boundary",
       .help = "fixed (boundary vertices stay put, the thesis) or slide (they move along the "
               "input's boundary, curved or flat; corners stay put, ridge vertices slide along "
               "their ridge)",
       .group = kBoundaryGroup,
       .field = member(&O::mode)},
      {.path = "boundary.shapes",
       .flag = "--shape",
       .help = "with --boundary slide: boundary part PART (physical group or FEAT3 mesh part) "
               "lies exactly on a shape: PART=circle:cx,cy,r | line:px,py,nx,ny | "
               "sphere:cx,cy,cz,r | plane:px,py,pz,nx,ny,nz | cylinder:px,py,pz,ax,ay,az,r | "
               "levelset:EXPR (repeatable; default: FEAT3 charts, flat faces, else the input's "
               "own facets)",
       .group = kBoundaryGroup,
       .field = member(&O::shapes)},
      {.path = "boundary.feature_angle",
       .flag = "--feature-angle",
       .help = "with --boundary slide: the boundary has a corner (2D) or ridge (3D) where it "
               "turns by more than this many degrees; corners stay put, ridge vertices slide "
               "along the ridge",
       .group = kBoundaryGroup,
       .field = member(&O::feature_angle),
       .range = {"in (0, 180) degrees", [](double x) { return x > 0 && x < 180; }}},
      {.path = "boundary.surface_geometry",
       .flag = "--surface-geometry",
       .help = "what a surface mesh's vertices slide on: cells (the input's flat cells) or phong "
               "(a curved Phong tessellation through their vertices, flat where it could fold); "
               "a volume mesh's boundary vertices slide on its flat facets either way",
       .group = kBoundaryGroup,
       .field = member(&O::surface_geometry)},
  };
  return table;
}

// The member `m` of SolverOptions::advanced.
template <typename T>
FieldRef<SolverOptions> advanced(T SolverOptions::Advanced::*m) {
  return Access<SolverOptions, T>([m](SolverOptions& s) -> T& { return s.advanced.*m; });
}

const OptionTable<SolverOptions>& solver_option_table() {
  using O = SolverOptions;
  static const OptionTable<O> table = {
      {.path = "solver.advanced.alpha0",
       .flag = "--alpha0",
       .help = "initial α in H(α) = B1 + α B2 + B3, in (0, 1]; auto: 1, or 0.3 where vertices "
               "slide on a curved or oblique boundary",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::alpha0),
       .range = kUpToOne},
      {.path = "solver.advanced.eta",
       .flag = "--eta",
       .help = "angle test: accept the quasi-Newton direction if η_k ≥ η, η in (0, 1)",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::eta),
       .range = kOpenUnit},
      {.path = "solver.advanced.rejected_direction",
       .flag = "--rejected-direction",
       .help = "when the quasi-Newton direction fails the angle test: blend (turn it towards the "
               "antigradient just enough to pass) or antigradient (the thesis)",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::rejected_direction)},
      {.path = "solver.advanced.kmin",
       .flag = "--kmin",
       .help = "initial antigradient steps before quasi-Newton steps",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::kmin),
       .range = kNonNegative},
      {.path = "solver.max_iterations",
       .flag = "--max-iter",
       .help = "maximum number of iterations",
       .group = kMethodGroup,
       .field = member(&O::max_iterations),
       .range = kAtLeastOne},
      {.path = "solver.time_limit",
       .flag = "--time-limit",
       .help = "end the run after this many seconds with the best mesh so far (0: no limit)",
       .group = kMethodGroup,
       .field = member(&O::time_limit),
       .range = {"0 (none) or more seconds", kNonNegative.ok}},
      {.path = "solver.defect_atol",
       .flag = "--tol",
       .help = "stop when the Newton defect ‖g‖ is below this",
       .group = kMethodGroup,
       .field = member(&O::defect_atol),
       .range = kNonNegative},
      {.path = "solver.defect_rtol",
       .flag = "--rtol",
       .help = "stop when the Newton defect fell by this factor from its start",
       .group = kMethodGroup,
       .field = member(&O::defect_rtol),
       .range = kNonNegative},
      {.path = "solver.practical",
       .flag = "--no-practical",
       .help = "iterate to the defect tolerance even after the mesh stopped changing (default: "
               "stop on the practical criterion too)",
       .group = kMethodGroup,
       .field = member(&O::practical),
       .negated = true},
      {.path = "solver.energy_rtol",
       .flag = "--energy-rtol",
       .help = "practical criterion: relative energy decrease per iteration below this ...",
       .group = kMethodGroup,
       .field = member(&O::energy_rtol),
       .range = kNonNegative},
      {.path = "solver.move_rtol",
       .flag = "--move-rtol",
       .help = "... and no vertex moved more than this times its local cell size",
       .group = kMethodGroup,
       .field = member(&O::move_rtol),
       .range = kNonNegative},
      {.path = "solver.newton_move_rtol",
       .flag = "--newton-move-rtol",
       .help = "practical criterion: or a full Newton step (alpha 1, sigma 1) moved no vertex "
               "more than this times its local cell size (0: off)",
       .group = kMethodGroup,
       .field = member(&O::newton_move_rtol),
       .range = kNonNegative},
      {.path = "solver.settle_rtol",
       .flag = "--settle-rtol",
       .help = "practical criterion: or the Newton defect did not halve over the last "
               "--settle-window iterations and they lowered F by less than this times its fall "
               "since the start (0: off); auto: 0.01 for surface meshes, off for others",
       .group = kMethodGroup,
       .field = member(&O::settle_rtol),
       .range = kNonNegative},
      {.path = "solver.settle_window",
       .flag = "--settle-window",
       .help = "... the iterations --settle-rtol looks back over",
       .group = kMethodGroup,
       .field = member(&O::settle_window),
       .range = kAtLeastOne},
      {.path = "solver.advanced.armijo_beta",
       .help = "sufficient decrease of the Armijo line search (thesis (2.5.4))",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::armijo_beta),
       .range = kOpenUnit},
      {.path = "solver.advanced.max_halvings",
       .help = "halvings of the line search's step before it gives up",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::max_halvings),
       .range = kAtLeastOne},
      {.path = "solver.advanced.max_trial_move",
       .flag = "--max-trial-move",
       .help = "line search along the antigradient: the first trial step moves no vertex more "
               "than this times its local cell size (the halving sequence from 1 is kept; 0: "
               "start at 1)",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::max_trial_move),
       .range = kNonNegative},
      {.path = "solver.advanced.initial_previous_defect",
       .flag = "--alpha-start-defect",
       .help = "defect assumed before the first iteration for the α update (thesis: 10)",
       .group = kMethodGroup,
       .field = advanced(&O::Advanced::initial_previous_defect),
       .range = kPositive},
      {.path = "solver.linear_solver",
       .flag = "--linear-solver",
       .help = "amg (CG + hypre BoomerAMG), jacobi (the thesis' PCG) or direct (Cholesky, MUMPS)",
       .group = kLinearGroup,
       .field = member(&O::linear_solver)},
      {.path = "solver.advanced.riesz",
       .flag = "--riesz",
       .help = "Laplacian of the Riesz representative: optimal (over the optimal cells, the "
               "thesis') or current (stiffness of the current mesh)",
       .group = kLinearGroup,
       .field = advanced(&O::Advanced::riesz),
       .report_key = "riesz_laplacian"},
      {.path = "solver.hessian_rtol",
       .flag = "--hess-rtol",
       .help = "relative tolerance of the loose quasi-Newton solve",
       .group = kLinearGroup,
       .field = member(&O::hessian_rtol),
       .range = kOpenUnit},
      {.path = "solver.advanced.hessian_defect_factor",
       .help = "the quasi-Newton solve stops at a residual of this times the defect (thesis §5.2)",
       .group = kLinearGroup,
       .field = advanced(&O::Advanced::hessian_defect_factor),
       .range = kPositive},
      {.path = "solver.advanced.hessian_forcing_max",
       .flag = "--hess-forcing-max",
       .help = "far from the minimum the quasi-Newton solve may stop at a residual of up to "
               "this times the defect, the closer the tighter (0: the thesis' solve throughout)",
       .group = kLinearGroup,
       .field = advanced(&O::Advanced::hessian_forcing_max),
       .range = {"in [0, 1)", [](double x) { return x >= 0 && x < 1; }}},
      {.path = "solver.advanced.hessian_pc",
       .flag = "--hess-pc",
       .help = "amg: precondition the quasi-Newton solve with the Riesz solve's AMG hierarchy "
               "of the Laplacian (laplacian: more CG iterations, cheaper ones, no hierarchy "
               "of H(alpha) built or stored) or with a hierarchy of H(alpha) (hessian)",
       .group = kLinearGroup,
       .field = advanced(&O::Advanced::hessian_pc)},
      {.path = "solver.advanced.hessian_pc_reuse",
       .flag = "--hess-pc-reuse",
       .help = "--hess-pc hessian: keep the AMG hierarchy of H(alpha) while the solve needs at "
               "most this many times the iterations it needed when built (0: rebuild every "
               "iteration)",
       .group = kLinearGroup,
       .field = advanced(&O::Advanced::hessian_pc_reuse),
       .range = kNonNegative},
      {.path = "solver.riesz_rtol",
       .flag = "--riesz-rtol",
       .help = "relative tolerance of the Riesz solve",
       .group = kLinearGroup,
       .field = member(&O::riesz_rtol),
       .range = kOpenUnit},
      {.path = "solver.advanced.lazy_riesz",
       .flag = "--riesz-every-step",
       .help = "solve the Riesz system every iteration (default: in quasi-Newton steps only when "
               "the angle test, estimated with one AMG V-cycle, needs s)",
       .group = kLinearGroup,
       .field = advanced(&O::Advanced::lazy_riesz),
       .negated = true},
  };
  return table;
}

const OptionTable<SizeFieldOptions>& size_field_option_table() {
  using O = SizeFieldOptions;
  static const OptionTable<O> table = {
      {.path = "field.power",
       .flag = "--power",
       .help = "p in v = floor + d^p",
       .group = kSizeFieldGroup,
       .field = member(&O::power),
       .range = kPositive},
      {.path = "field.floor",
       .flag = "--floor",
       .help = "floor in v = floor + d^p",
       .group = kSizeFieldGroup,
       .field = member(&O::floor),
       .range = kNonNegative},
      {.path = "field.max_ratio",
       .flag = "--max-ratio",
       .help = "largest over smallest desired volume; smaller ones are raised (0: no bound; "
               "default 32, with --fit 16)",
       .group = kSizeFieldGroup,
       .field = member(&O::max_ratio),
       .range = {"above 1, or 0 for no bound", [](double x) { return x == 0 || x > 1; }}},
      {.path = "field.smoothing_passes",
       .flag = "--smooth-sizes",
       .help = "passes of averaging log(desired volume) over neighbouring cells",
       .group = kSizeFieldGroup,
       .field = member(&O::smoothing_passes),
       .range = kNonNegative},
  };
  return table;
}

const OptionTable<PicardOptions>& picard_option_table() {
  using O = PicardOptions;
  static const OptionTable<O> table = {
      {.path = "picard.min_updates",
       .flag = "--min-updates",
       .help = "updates of the desired volumes before the run may stop",
       .group = kPicardGroup,
       .field = member(&O::min_updates),
       .range = kNonNegative},
      {.path = "picard.update_every",
       .flag = "--update-every",
       .help = "update the desired volumes at least every this many iterations",
       .group = kPicardGroup,
       .field = member(&O::update_every),
       .range = kAtLeastOne},
      {.path = "picard.update_move",
       .flag = "--update-move",
       .help = "update once a quasi-Newton step moved no vertex more than this times its "
               "local cell size",
       .group = kPicardGroup,
       .field = member(&O::update_move),
       .range = kNonNegative},
      {.path = "picard.update_step_norm",
       .flag = "--update-step",
       .help = "update once the step's Euclidean norm σ‖δ‖ is below this (0: off)",
       .group = kPicardGroup,
       .field = member(&O::update_step_norm),
       .range = kNonNegative},
      {.path = "picard.relaxation",
       .flag = "--relaxation",
       .help = "ω in v ← (1−ω) v_old + ω v(centroids), in (0, 1]",
       .group = kPicardGroup,
       .field = member(&O::relaxation),
       .range = kUpToOne},
  };
  return table;
}

const OptionTable<SmoothOptions>& smooth_own_option_table() {
  using O = SmoothOptions;
  static const OptionTable<O> table = {
      {.path = "quality_guard",
       .flag = "--no-guard",
       .help = "keep the energy's optimum even where a cell ends up worse than the input's worst "
               "cell or with a corner nearly flat (default: off, i.e. flat corners are lifted "
               "and such cells' vertices are pulled back)",
       .field = member(&O::quality_guard),
       .negated = true,
       .report_object = "smooth_options"},
      {.path = "repair_worst_cells",
       .flag = "--no-repair",
       .help = "keep the optimum's worst cells instead of repairing them (default: off, i.e. "
               "after the optimum the vertices of the worst cells, boundary ones sliding, move one "
               "at a time to where the worst cell around them is best: a max-min search, so "
               "meshes equal up to round-off may come out visibly different; not with "
               "--no-guard)",
       .field = member(&O::repair_worst_cells),
       .negated = true,
       .report_object = "smooth_options"},
      {.path = "untangle",
       .flag = "--no-untangle",
       .help = "refuse a mesh with inverted cells instead of untangling it first (default: off, "
               "i.e. inverted cells are untangled, then the mesh is smoothed)",
       .field = member(&O::untangle),
       .negated = true,
       .report_object = "smooth_options"},
      {.path = "sizes",
       .flag = "--sizes",
       .help = "desired cell volumes: smoothed (input volumes averaged over neighbours: keeps "
               "the grading), input (each cell's own volume) or uniform (all equal, the thesis)",
       .field = member(&O::sizes),
       .report_object = "smooth_options"},
      {.path = "targets",
       .flag = "--targets",
       .help = "the cell each cell is pulled towards: smoothed (the input's own cell where its "
               "neighbourhood is stretched on purpose, as boundary layers and graded meshes "
               "are; the ideal cell where the stretching is noise), ideal (square, cube, "
               "equilateral simplex, ... of the desired volume: the thesis) or input (the input "
               "cell: only untangle and repair the worst cells)",
       .field = member(&O::targets),
       .report_object = "smooth_options"},
  };
  return table;
}

const OptionTable<AdaptOptions>& adapt_own_option_table() {
  using O = AdaptOptions;
  static const OptionTable<O> table = {
      {.path = "quality_guard",
       .flag = "--no-guard",
       .help = "keep the adaptation's optimum even where a cell ends up with a scaled Jacobian "
               "below 0.2 and the input's worst, or with a corner nearly flat (default: off, i.e. "
               "flat corners are lifted and such cells' vertices are pulled back; not with --fit "
               "or a metric)",
       .field = member(&O::quality_guard),
       .negated = true,
       .report_object = "adapt_options"},
      {.path = "untangle",
       .flag = "--no-untangle",
       .help = "refuse a mesh with inverted cells instead of untangling it first (default: off, "
               "i.e. inverted cells are untangled towards the size field's volumes, then the "
               "mesh is adapted)",
       .field = member(&O::untangle),
       .negated = true,
       .report_object = "adapt_options"},
      {.path = "warm_updates",
       .flag = "--step-updates",
       .help = "Picard updates before a time step after the first may stop (the first step "
               "uses --min-updates)",
       .group = kTimeGroup,
       .field = member(&O::warm_updates),
       .range = kNonNegative,
       .report_object = "adapt_options"},
  };
  return table;
}

const OptionTable<SmoothOptions>& smooth_option_table() {
  using O = SmoothOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t = smooth_own_option_table();
    append(t, &O::energy, energy_option_table(), "energy_options");
    append(t, &O::solver, solver_option_table(), "solver_options");
    append(t, &O::boundary, boundary_option_table(), "boundary_options");
    t.push_back(thesis_flag<O>());
    return t;
  }();
  return table;
}

const OptionTable<AdaptOptions>& adapt_option_table() {
  using O = AdaptOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t = adapt_own_option_table();
    append(t, &O::field, size_field_option_table(), "field_options");
    append(t, &O::picard, picard_option_table(), "picard");
    append(t, &O::energy, energy_option_table(), "energy_options");
    append(t, &O::solver, solver_option_table(), "solver_options");
    append(t, &O::boundary, boundary_option_table(), "boundary_options");
    t.push_back(thesis_flag<O>());
    return t;
  }();
  return table;
}

template <>
const OptionTable<SmoothOptions>& task_option_table<SmoothOptions>() {
  return smooth_option_table();
}
template <>
const OptionTable<AdaptOptions>& task_option_table<AdaptOptions>() {
  return adapt_option_table();
}

template <typename S>
void check_ranges(const OptionTable<S>& table, const S& options) {
  for (const OptionSpec<S>& spec : table) {
    if (spec.range.text.empty()) continue;
    std::visit(
        [&](const auto& access) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(access)>, Preset>) {
            const auto& value = get(access, options);
            using T = std::decay_t<decltype(value)>;
            if constexpr (std::is_same_v<T, std::optional<double>>) {
              if (value) require(spec.path, *value, spec.range);
            } else if constexpr (std::is_same_v<T, double> || std::is_same_v<T, int>) {
              require(spec.path, value, spec.range);
            }
          }
        },
        spec.field);
  }
}
template void check_ranges(const OptionTable<EnergyOptions>&, const EnergyOptions&);
template void check_ranges(const OptionTable<BoundaryOptions>&, const BoundaryOptions&);
template void check_ranges(const OptionTable<SolverOptions>&, const SolverOptions&);
template void check_ranges(const OptionTable<SizeFieldOptions>&, const SizeFieldOptions&);
template void check_ranges(const OptionTable<PicardOptions>&, const PicardOptions&);
template void check_ranges(const OptionTable<SmoothOptions>&, const SmoothOptions&);
template void check_ranges(const OptionTable<AdaptOptions>&, const AdaptOptions&);

template <typename T>
std::string to_text(const T& value, std::string_view unset) {
  if constexpr (std::is_same_v<T, double>) {
    return fmt::format("{:g}", value);
  } else if constexpr (std::is_same_v<T, int>) {
    return fmt::format("{}", value);
  } else if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    return value ? to_text(*value) : std::string(unset);
  } else if constexpr (std::is_same_v<T, Shapes>) {
    if (value.empty()) return "none";
    std::string text;
    for (const auto& [part, shape] : value)
      text += fmt::format("{}{}={}", text.empty() ? "" : " ", part, shape);
    return text;
  } else {
    return std::string(name(value));
  }
}
template std::string to_text(const double&, std::string_view);
template std::string to_text(const int&, std::string_view);
template std::string to_text(const bool&, std::string_view);
template std::string to_text(const std::optional<double>&, std::string_view);
template std::string to_text(const Shapes&, std::string_view);
template std::string to_text(const BoundaryMode&, std::string_view);
template std::string to_text(const SurfaceGeometry&, std::string_view);
template std::string to_text(const LinearSolverKind&, std::string_view);
template std::string to_text(const RieszLaplacian&, std::string_view);
template std::string to_text(const HessianPreconditioner&, std::string_view);
template std::string to_text(const RejectedDirection&, std::string_view);
template std::string to_text(const SizeMode&, std::string_view);
template std::string to_text(const TargetMode&, std::string_view);

std::string respell_option_message(const std::string& message, const OptionNames& names) {
  const std::size_t end = message.find_first_of(" :");
  if (end == std::string::npos) return message;
  const auto it = names.find(message.substr(0, end));
  return it != names.end() ? it->second + message.substr(end) : message;
}

}  // namespace neomesh
