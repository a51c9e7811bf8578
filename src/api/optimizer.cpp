#include <neomesh/optimizer.hpp>

#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "adapt/picard.hpp"
#include "adapt/volume_ratio.hpp"
#include "api/fitting.hpp"
#include "api/memory_check.hpp"
#include "api/optimizer_impl.hpp"
#include "api/vertex_order.hpp"
#include "boundary/interface.hpp"
#include "core/error.hpp"
#include "geometry/node_mesh.hpp"
#include "geometry/quality.hpp"
#include "solver/linear_solver.hpp"
#include "solver/quality_guard.hpp"
#include "solver/quasi_newton.hpp"
#include "solver/untangle.hpp"
#include "solver/worst_cell_repair.hpp"
#include "solver/worst_cells.hpp"
#include "targets/cell_targets.hpp"
#include "targets/desired_volumes.hpp"
#include "targets/input_targets.hpp"

namespace neomesh {

namespace {

bool same(const EnergyOptions& a, const EnergyOptions& b) {
  return a.lambda == b.lambda && a.mu == b.mu && a.kappa == b.kappa &&
         a.gauss_points == b.gauss_points;
}
bool same(const BoundaryOptions& a, const BoundaryOptions& b) {
  return a.mode == b.mode && a.feature_angle == b.feature_angle && a.shapes == b.shapes;
}

UntanglingSummary summarize(const UntangleResult& u) {
  return {.inverted_before = u.before.count,
          .inverted_after = u.after.count,
          .min_det_before = u.before.min_det,
          .min_det_after = u.after.min_det,
          .history = u.history,
          .rounds = u.rounds,
          .seconds = u.seconds};
}

// The cells that stayed inverted, for the error: "0, 1, 7, ..." (global, input order).
std::string list_cells(const Inversion& inversion) {
  std::string cells;
  for (PetscInt c : inversion.cells) cells += fmt::format("{}{}", cells.empty() ? "" : ", ", c);
  if (inversion.count > static_cast<PetscInt>(inversion.cells.size())) cells += ", ...";
  return cells;
}

// The options of an adaptation followed by a fit: of the adaptation, of the fit, and of the
// fit's last stage. A warm step adapts only until the small cells have moved along with the
// geometry: the fit goes on optimizing, and its start recomputes the desired volumes (one of the
// step's updates). After a cold start the volumes follow the fitted cells once more.
struct FittedAdaptation {
  AdaptOptions adapting, fitting;
  PicardOptions last_stage;
};
FittedAdaptation fitted_adaptation(const AdaptOptions& options, bool warm) {
  FittedAdaptation parts{.adapting = options, .fitting = options, .last_stage = options.picard};
  parts.fitting.field.max_ratio = options.field.ratio(true);
  parts.adapting = parts.fitting;
  if (warm) {
    parts.adapting.warm_updates = std::max(0, options.warm_updates - 1);
    parts.adapting.solver.max_iterations = FitOptions().stage_iterations;
  }
  parts.last_stage.min_updates = warm ? 0 : 1;
  return parts;
}

}  // namespace

// Desired volumes asked for (a volume source, --sizes, of uniform) win over the volumes the
// smoothed targets would keep; and a cell's design without its size (a layer's height across the
// wall) is no design (docs/method.md §9).
TargetMode targets_asked(const SmoothOptions& options) {
  return options.targets == TargetMode::Smoothed && options.sizes == SizeMode::Uniform
             ? TargetMode::Ideal
             : options.targets;
}

Optimizer::Impl::Impl(Mesh& m) : mesh(m) {}

void Optimizer::Impl::start(const EnergyOptions& e, const BoundaryOptions& b,
                            const SolverOptions* solver) {
  x = mesh.plex().coordinates();
  const bool same_problem = functional && same(*energy, e) && same(*boundary_options, b) &&
                            boundary->slides_on_surface_of(view());
  if (!functional) {
    const bool hessian_hierarchy = solver && solver->linear_solver == LinearSolverKind::Amg &&
                                   solver->advanced.hessian_pc == HessianPreconditioner::Hessian;
    check_memory_fits(mesh.comm(), view().dim, view().num_vertices, view().num_cells,
                      hessian_hierarchy, mesh.creation_bytes_, mesh.name());
  }
  if (!same_problem) {
    smoothed.reset();
    double local = 0.0;
    for (double v : cell_volumes()) local += v;
    MPI_Allreduce(&local, &mesh_volume, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
    boundary = std::make_unique<Boundary>(view(), dofs(), b);
    energy = e;
    boundary_options = b;
  }
  if (!same_problem || fitted) constrain({});  // the boundary's sliding vertices alone
  fitted.reset();
  // Onto the charts as FEAT3 does, before the inverted cells are counted (untangle() fixes
  // what the move folds); then sliding vertices onto their geometry.
  boundary->place_on_charts(x);
  boundary->project(x);
}

CellTargets Optimizer::Impl::smoothing_targets(TargetMode mode, SizeMode volume_source) const {
  const TargetRequest request = SmoothingRequest{.mode = mode, .volume_source = volume_source};
  const std::vector<double> volumes = cell_volumes();
  const bool input_cells = needs_jacobians(request);
  const std::vector<double> jacobians =
      input_cells ? functional->cell_jacobians(x) : std::vector<double>{};
  const std::vector<double> edge_ratios = input_cells ? cell_edge_ratios() : std::vector<double>{};
  return build_targets(request, view(), dofs(),
                       {.volumes = volumes, .jacobians = jacobians, .edge_ratios = edge_ratios});
}

TargetsAt Optimizer::Impl::adaptation_targets(const SizeField& field,
                                              const SizeFieldOptions& field_options) const {
  const TargetRequest request = AdaptationRequest{.field = &field, .field_options = field_options};
  std::vector<double> orientations =
      needs_jacobians(request) ? functional->cell_jacobians(x) : std::vector<double>{};
  return [this, request, orientations = std::move(orientations), total = mesh_volume](Vec at) {
    std::vector<double> coords(dofs().num_local_dofs());
    dofs().global_to_local(at, coords);
    return build_targets(request, view(), dofs(),
                         {.coords = coords, .jacobians = orientations, .mesh_volume = total});
  };
}

const Functional& Optimizer::Impl::set_targets(const CellTargets& targets) {
  problem = problem.with_targets(targets.volumes, targets.shapes, targets.weights);
  cell_size = local_cell_size(view(), dofs(), targets.volumes);
  input_share = targets.shapes.empty() ? std::vector<double>{} : targets.input_share;
  return rebuild_functional();
}

const Functional& Optimizer::Impl::constrain(SlidingVertices extra) {
  problem = problem.with_constraints(
      std::make_shared<const Constraints>(view(), dofs(), boundary->fixed_dofs(),
                                          join(boundary->sliding_vertices(), std::move(extra))));
  return rebuild_functional();
}

const Functional& Optimizer::Impl::rebuild_functional() {
  functional = std::make_unique<Functional>(*energy, problem);
  return *functional;
}

std::optional<UntanglingSummary> Optimizer::Impl::untangle(const QuasiNewtonOptions& method,
                                                           const Observer& observer) {
  const PetscInt inverted = functional->inversion(x, 0).count;
  if (inverted == 0) return std::nullopt;
  if (observer.untangling) observer.untangling(inverted);
  const OwnedVec start = copy_of(x);
  UntangleResult u = neomesh::untangle(*functional, x, method, cell_size, {}, observer.iteration);
  // If it stalls, again from the input with the boundary fixed: sliding vertices can fold a
  // boundary cell further (tangled_horse1 stalled after 248 iterations; fixed, it untangles in
  // 30). Then towards equal cell volumes too: the input's, filled in where cells are inverted,
  // can ask for what the boundary cannot give (hole_in_square_tanglap: 8 of 23 cells stayed
  // inverted; towards equal volumes none after 12 iterations). The smoothing that follows has
  // the boundary and the volumes asked for.
  std::shared_ptr<const Constraints> every_boundary_vertex;  // built by the first retry
  const auto retry = [&](const std::vector<double>& volumes) {
    NM_PETSC(VecCopy(start, x));
    if (!every_boundary_vertex)
      every_boundary_vertex =
          std::make_shared<const Constraints>(view(), dofs(), view().on_boundary);
    const Functional pinned(
        *energy, problem.with_constraints(every_boundary_vertex).with_desired_volumes(volumes));
    const UntangleResult again =
        neomesh::untangle(pinned, x, method, cell_size, {}, observer.iteration);
    u.history.insert(u.history.end(), again.history.begin(), again.history.end());
    u.after = again.after;
    u.rounds += again.rounds;
    u.seconds += again.seconds;
  };
  bool boundary_fixed = false, equal_volumes = false;
  if (u.after.count > 0 && boundary_options->mode == BoundaryMode::Slide) {
    retry(problem.desired_volumes());
    boundary_fixed = true;
  }
  if (u.after.count > 0) {
    retry(std::vector<double>(static_cast<std::size_t>(view().num_cells),
                              mesh_volume / static_cast<double>(mesh.num_cells())));
    boundary_fixed = boundary_options->mode == BoundaryMode::Slide;
    equal_volumes = true;
  }
  if (u.after.count > 0 && past_deadline(method.deadline, mesh.comm()))
    fail(
        "{}: the time limit ran out while untangling ({} of {} inverted cells are still "
        "inverted after {} iterations); a longer --time-limit may help",
        mesh.name(), u.after.count, u.before.count, u.history.size());
  if (u.after.count > 0)
    fail(
        "{}: the mesh cannot be untangled with its boundary as it is: {} of {} inverted cells "
        "are still inverted after {} iterations (cells {}; 0-based, in input order)",
        mesh.name(), u.after.count, u.before.count, u.history.size(), list_cells(u.after));
  UntanglingSummary summary = summarize(u);
  summary.boundary_fixed = boundary_fixed;
  summary.equal_volumes = equal_volumes;
  if (observer.untangled) observer.untangled(summary);
  return summary;
}

ProblemSummary Optimizer::Impl::problem_summary(const SolverOptions& solver) const {
  ProblemSummary p;
  p.free_coordinates = functional->free_dofs();
  if (boundary_options->mode == BoundaryMode::Slide) p.boundary = boundary->summary();
  p.alpha0 = solver.initial_alpha(functional->slides());
  const int dim = view().dim;
  p.hessian_solver =
      LinearSolver(mesh.comm(), solver.linear_solver, "hess_", dim, solver.hessian_rtol)
          .description();
  LinearSolver riesz(mesh.comm(), solver.linear_solver, "riesz_", dim, solver.riesz_rtol);
  if (const auto kind = riesz_components(*functional, solver))
    riesz.precondition_per_component(*kind);
  p.riesz_solver = riesz.description();
  return p;
}

QuasiNewtonOptions Optimizer::Impl::method(const SolverOptions& solver) const {
  QuasiNewtonOptions o;
  static_cast<SolverOptions&>(o) = solver;
  o.energy_roundoff = energy_roundoff(*energy, view().dim, mesh_volume);
  if (solver.time_limit > 0) o.deadline = started + solver.time_limit;
  return o;
}

const Optimizer::Impl::InputCells* Optimizer::Impl::current_input_cells() const {
  return input_cells && input_cells->coordinates_version ==
                            std::as_const(mesh).plex().coordinates_version()
             ? &*input_cells
             : nullptr;
}

std::vector<double> Optimizer::Impl::cell_volumes() const {
  if (curved) return curved_cell_volumes(curved->cells, curved->cells.coords);
  if (const InputCells* kept = current_input_cells()) return kept->volumes;
  return neomesh::cell_volumes(view(), view().coords, &dofs());
}

std::vector<double> Optimizer::Impl::cell_edge_ratios() const {
  // A curved cell's: its corners' (the target's shape is its corners' too, cell_jacobians).
  if (curved) return neomesh::cell_edge_ratios(curved->corners, curved->corners.coords);
  if (const InputCells* kept = current_input_cells()) return kept->edge_ratios;
  return neomesh::cell_edge_ratios(view(), view().coords);
}

std::vector<double> Optimizer::Impl::cell_scaled_jacobians() const {
  if (const InputCells* kept = current_input_cells()) return kept->scaled_jacobians;
  return neomesh::cell_scaled_jacobians(view(), view().coords, &dofs());
}

bool Optimizer::Impl::at_mesh_coordinates(Vec y) const {
  const std::vector<double>& mine = std::as_const(mesh).plex().view().coords;
  std::vector<double> local(dofs().num_local_dofs());
  dofs().global_to_local(y, local);
  int same = local.size() == mine.size() &&
             std::memcmp(local.data(), mine.data(), local.size() * sizeof(double)) == 0;
  MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_LAND, mesh.comm());
  return same;
}

void Optimizer::Impl::keep_input_cells() {
  // The quality's volumes, edge ratios and scaled Jacobians are cell_volumes()'s,
  // cell_edge_ratios()'s and cell_scaled_jacobians()'s, from the same functions of the same
  // coordinates (geometry/quality.cpp).
  const CellQuality& quality = std::as_const(mesh).cell_quality();
  input_cells = InputCells{std::as_const(mesh).plex().coordinates_version(), quality.volume,
                           quality.edge_ratio, quality.scaled_jacobian};
}

QualitySummary Optimizer::Impl::input_quality(bool untangle) const {
  const QualitySummary quality = mesh.quality();
  if (!untangle && (quality.inverted > 0 || quality.degenerate > 0))
    fail("{} has {} inverted and {} degenerate cells, and untangling is switched off", mesh.name(),
         quality.inverted, quality.degenerate);
  return quality;
}

void Optimizer::Impl::refuse_surface(const QualitySummary& input) const {
  // A folded cell is inverted, and untangled as a volume mesh's is; a cell without area has no
  // tangent plane to be seen in.
  if (view().surface && input.degenerate > 0)
    fail("{}: a surface mesh with {} degenerate cells (without area): they have no tangent plane",
         mesh.name(), input.degenerate);
}

void Optimizer::Impl::refuse_surface(const SizeField& field) const {
  // A metric is a 3 × 3 matrix in space, a surface cell's target a 2 × 2 one in its tangent
  // plane.
  if (view().surface && field.anisotropic())
    fail(
        "{}: a surface mesh (2D cells in space) is adapted to sizes, not to a metric: give an "
        "isotropic size field",
        mesh.name());
}

void Optimizer::Impl::finish(Result& result) {
  mesh.plex().set_coordinates(x);
  result.quality_after = mesh.quality();
  if (result.quality_after.inverted > 0 || result.quality_after.degenerate > 0)
    fail(
        "the optimized mesh has {} inverted and {} degenerate cells (please report this with the "
        "input mesh)",
        result.quality_after.inverted, result.quality_after.degenerate);
  result.boundary_distance = boundary->max_distance_from_input(x);
  const double volume = result.quality_after.volume.mean * result.quality_after.cells;
  result.volume_change = (volume - mesh_volume) / mesh_volume;
}

Optimizer::Impl::Smoothing Optimizer::Impl::set_up_smoothing(const SmoothOptions& options,
                                                             const Observer& observer,
                                                             Result& result) {
  warm = false;  // the desired volumes are smoothing's now
  // A warm start where the last call smoothed the same problem: its minimum is near, so the
  // Newton regime (α where it ended) from the first step, without antigradient steps (annulus
  // quads, 1 % of the vertices moved: 11 iterations cold, 4 warm, the same optimum).
  const std::optional<SmoothingEnd> last = std::exchange(smoothed, std::nullopt);
  // Targets from the input cells — not from a tangled input, whose cells around the inverted
  // ones are distorted by whatever tangled it: that is no design to keep.
  const bool tangled = result.quality_before.inverted > 0 || result.quality_before.degenerate > 0;
  const bool volumes_asked = targets_asked(options) != options.targets;
  const TargetMode mode = tangled ? TargetMode::Ideal : targets_asked(options);
  // Nor are its sizes where it is folded over itself throughout: the fill-in of the inverted
  // cells' volumes from their neighbours then starts from cells that were squeezed and stretched
  // with them (copy-morph-for-ricoh: desired volumes from 7e-4 to 26 in a ring of equal cells,
  // an optimum with corners nearly flat, 5 + 123 iterations and 76 s; uniform: 4 + 7, 3.8 s).
  const double coverage = tangled ? domain_coverage(cell_volumes(), mesh.comm()) : 1.0;
  const bool folded = coverage > kFoldedCoverage;
  KeptCells kept;
  {  // the problem keeps its own copy of the targets: this one goes before the solve
    const CellTargets targets = smoothing_targets(mode, folded ? SizeMode::Uniform : options.sizes);
    set_targets(targets);
    kept = count_kept(targets.input_share, mesh.comm());
  }
  QuasiNewtonOptions run_method = method(options.solver);
  if (last && !tangled && last->targets == options.targets && last->sizes == options.sizes)
    run_method.warm_alpha = last->alpha;
  result.problem = problem_summary(options.solver);
  if (run_method.warm_alpha && !options.solver.advanced.alpha0)
    result.problem.alpha0 = *run_method.warm_alpha;
  result.problem.targets = {std::string(name(mode)),
                            kept.all,
                            kept.part,
                            kept.none,
                            tangled && options.targets != TargetMode::Ideal,
                            !tangled && volumes_asked,
                            coverage,
                            folded && options.sizes != SizeMode::Uniform};
  if (observer.started) observer.started(result.problem);
  // The guard's promise is about the input (before untangling): a tangled input's worst cell is
  // inverted, so any untangled output keeps it.
  OwnedVec input = copy_of(x);
  // The input as the run starts from it: vertices placed on their charts (FEAT3's
  // unit-axe-tria: the placement alone takes its mean from 0.816 to 0.647).
  // Where the input stayed as read, the quality before's means are these, the same sums bit for
  // bit (geometry/quality.cpp, solver/quality_guard.cpp): a pass over the cells less.
  const bool as_read = at_mesh_coordinates(input);
  const QualitySummary& read = result.quality_before;
  const double input_mean =
      as_read ? read.scaled_jacobian.mean : mean_scaled_jacobian(view(), dofs(), input);
  const double input_imr = !view().surface ? std::numeric_limits<double>::infinity()
                           : as_read       ? read.inverse_mean_ratio.mean
                                           : mean_inverse_mean_ratio(view(), dofs(), input);
  return {.options = options,
          .observer = observer,
          .method = run_method,
          .mode = mode,
          .tangled = tangled,
          .input = std::move(input),
          .input_mean = input_mean,
          .input_imr = input_imr};
}

void Optimizer::Impl::optimize(const Smoothing& s, Result& run) {
  static_cast<SolverRun&>(run) =
      minimize(*functional, x, s.method, cell_size, s.observer.iteration);
  if (!s.tangled && !run.history.empty())
    smoothed = SmoothingEnd{run.history.back().alpha, s.options.targets, s.options.sizes};
  if (!s.options.quality_guard) return;
  lift_corners(s.method, s.observer, run);
  // The repair spends no more of the mean than the promise allows.
  if (s.options.repair_worst_cells)
    repair_worst(run, s.input_mean - QualityGuardResult::kMeanSlack, repair_imr_ceiling(s));
  guard_worst(s.input, run);
  if (!s.tangled) guard_mean(s, run);
}

void Optimizer::Impl::retry_towards_ideal_cells(const Smoothing& s, Result& result) {
  if (s.mode == TargetMode::Ideal || result.reason == StopReason::TimeLimit) return;
  // Where the kept cells ask for a corner the mesh cannot open, or keep a cell flattened across
  // its edges, towards ideal cells from the input too; the better worst cell wins, the
  // design's on a tie.
  const bool flat_kept =
      (result.corner_phase && result.corner_phase->gave_up) || flat_cap(view(), dofs(), x);
  if (!flat_kept) return;
  const OwnedVec kept = copy_of(x);
  NM_PETSC(VecCopy(s.input, x));
  set_targets(smoothing_targets(TargetMode::Ideal, s.options.sizes));
  Result ideal;
  ideal.quality_before = result.quality_before;
  optimize(s, ideal);
  IdealRetrySummary& retry = result.ideal_retry.emplace();
  retry.min_scaled_jacobian_kept = min_scaled_jacobian(view(), dofs(), kept);
  retry.min_scaled_jacobian_ideal = min_scaled_jacobian(view(), dofs(), x);
  retry.iterations = static_cast<int>(ideal.history.size());
  retry.ideal_kept = retry.min_scaled_jacobian_ideal > retry.min_scaled_jacobian_kept;
  result.history.insert(result.history.end(), ideal.history.begin(), ideal.history.end());
  if (retry.ideal_kept) {  // F and the defect of the energy towards ideal cells
    result.initial_energy = ideal.initial_energy;
    result.initial_defect = ideal.initial_defect;
    result.reason = ideal.reason;
    result.final_energy = ideal.final_energy;
    result.final_defect = ideal.final_defect;
    result.worst_cell_repair = ideal.worst_cell_repair;
    result.quality_guard = ideal.quality_guard;
  } else {
    NM_PETSC(VecCopy(kept, x));
    set_targets(smoothing_targets(s.mode, s.options.sizes));
  }
}

void Optimizer::Impl::lift_corners(const QuasiNewtonOptions& method, const Observer& observer,
                                   Result& run) {
  if (run.reason != StopReason::TimeLimit)
    run.corner_phase = lift_flat_corners(*functional, view(), dofs(), x, method, cell_size, run,
                                         observer.iteration);
}

double Optimizer::Impl::repair_imr_ceiling(const Smoothing& s) const {
  if (!view().surface) return std::numeric_limits<double>::infinity();
  // The repair lifts the worst cells at the cost of the others' shapes, which the mean inverse
  // mean ratio reads: spending all the optimum gained raised it above the input's on a capped
  // cylinder (1.0659 -> 1.0691) and quads_on_sphere_529 (1.0187 -> 1.0310).
  const double start = mean_inverse_mean_ratio(view(), dofs(), x);
  return start < s.input_imr ? start + kRepairImrSpend * (s.input_imr - start)
                             : -std::numeric_limits<double>::infinity();
}

void Optimizer::Impl::repair_worst(Result& run, double mean_floor, double imr_ceiling) {
  if (run.reason == StopReason::TimeLimit) return;
  // The floor binds where x's mean is above it; below it, the mean guard returns the input
  // anyway (guard_mean).
  const double min_mean = mean_scaled_jacobian(view(), dofs(), x) >= mean_floor
                              ? mean_floor
                              : -std::numeric_limits<double>::infinity();
  const WorstCellRepair r =
      repair_worst_cells(view(), dofs(), repair_freedom(), x, min_mean, imr_ceiling);
  run.worst_cell_repair = {.min_scaled_jacobian_before = r.min_before,
                           .min_scaled_jacobian_after = r.min_after,
                           .vertices_moved = r.vertices_moved,
                           .sweeps = r.sweeps};
}

void Optimizer::Impl::guard_worst(Vec input, Result& run, double ceiling) {
  // The threshold is the file's worst cell, or where placing vertices on their charts left it
  // (at most the ceiling).
  run.quality_guard = guard_worst_quality(
      view(), dofs(), input, x, [this](Vec y) { functional->project_onto_boundary(y); },
      run.quality_before.inverted > 0
          ? std::optional(ceiling)
          : std::optional(std::min(run.quality_before.scaled_jacobian.min, ceiling)));
  if (run.quality_guard->vertices_moved > 0) run.final_energy = functional->value(x);
}

void Optimizer::Impl::guard_mean(const Smoothing& s, Result& run) {
  QualityGuardResult& guard = *run.quality_guard;
  guard.input_mean = s.input_mean;
  guard.mean_optimum = mean_scaled_jacobian(view(), dofs(), x);
  const double floor = s.input_mean - QualityGuardResult::kMeanSlack;
  bool shapes_worse = false;
  if (view().surface) {
    guard.input_mean_inverse_mean_ratio = s.input_imr;
    guard.mean_inverse_mean_ratio_optimum = mean_inverse_mean_ratio(view(), dofs(), x);
    shapes_worse = *guard.mean_inverse_mean_ratio_optimum > s.input_imr;
  }
  if (guard.mean_optimum >= floor && !shapes_worse) return;
  NM_PETSC(VecCopy(s.input, x));
  mesh.plex().set_coordinates(x);  // what the repair judges the input cells by
  // Within the slack of the input's mean, so above the optimum's.
  if (s.options.repair_worst_cells) repair_worst(run, floor, repair_imr_ceiling(s));
  guard.input_returned = true;
  guard.min_after = min_scaled_jacobian(view(), dofs(), x);
  run.final_energy = functional->value(x);
}

RepairFreedom Optimizer::Impl::repair_freedom() const {
  const int d = view().dim;
  RepairFreedom f{.fixed = boundary->fixed_dofs().flags,
                  .geometry = boundary->sliding_geometry(),
                  .project = [this, d](int g, std::span<double> p) {
                    Point at = Point::Zero();
                    for (int a = 0; a < d; ++a) at[a] = p[a];
                    const Point q = boundary->closest_point(g, at);
                    for (int a = 0; a < d; ++a) p[a] = q[a];
                  }};
  // A cell that keeps (part of) its input cell is the mesh's design: its vertices stay, unless
  // its angles are poor. A kept simplex or wedge keeps its input shape: poor below 0.5. A kept
  // quadrilateral, hexahedron or pyramid aims at a right-angled cell: its design is held where
  // the input and the optimum are near right-angled; a graded block's skewed bricks and the
  // cells the optimum distorted (FEAT3's rotor, in the gap between the screws) are free.
  // Collective (a surface's reference normals are summed over ranks): a rank without cells
  // takes part too.
  // A curved mesh's nodes all move (curved_repair.hpp): its cells' designs are their corners'.
  if (curved) return f;
  int design = !input_share.empty();
  MPI_Allreduce(MPI_IN_PLACE, &design, 1, MPI_INT, MPI_MAX, mesh.comm());
  if (design) {
    const std::vector<double> input_sj = cell_scaled_jacobians();
    std::vector<double> local(dofs().num_local_dofs());
    dofs().global_to_local(x, local);
    const std::vector<double> sj = neomesh::cell_scaled_jacobians(view(), local, &dofs());
    for (const CellBlock& block : view().blocks) {
      const bool right_angled = right_angled_target(block.type);
      for (PetscInt c = block.first_cell; c < block.first_cell + block.size(); ++c) {
        const bool held =
            input_share[c] >= kHeldInputShare &&
            (right_angled ? std::min(input_sj[c], sj[c]) >= kKeptRightAngledMinScaledJacobian
                          : input_sj[c] >= kKeptCellMinScaledJacobian);
        if (held)
          for (int i = 0; i < facts(block.type).vertices; ++i)
            std::fill_n(f.fixed.begin() + d * block.cell(c - block.first_cell)[i], d, 1);
      }
    }
  }
  return f;
}

VolumeRatioStats Optimizer::Impl::volume_ratio() const {
  return volume_ratio_stats(functional->cell_fields(x).volume_ratio, mesh.comm());
}

TargetsAt Optimizer::Impl::set_up_adaptation(const SizeField& field, const AdaptOptions& options,
                                             const Observer& observer, Result& result) {
  smoothed.reset();
  TargetsAt targets = adaptation_targets(field, options.field);
  // The size field's targets at the start: what the observer sees, and what untangling aims at.
  // They replace any a smoothing before may have left.
  set_targets(targets(x));
  result.problem = problem_summary(options.solver);
  if (field.anisotropic()) result.problem.targets.mode = "metric";
  if (observer.started) observer.started(result.problem);
  return targets;
}

void Optimizer::Impl::picard_iteration(const TargetsAt& targets, const AdaptOptions& options,
                                       const Observer& observer, Result& result) {
  PicardOptions picard = options.picard;
  if (warm) picard.min_updates = options.warm_updates;
  const PicardResult run = neomesh::picard(
      view(), x, targets,
      [this](const CellTargets& t) -> const Functional& { return set_targets(t); }, picard,
      method(options.solver), observer);
  warm = true;
  static_cast<SolverRun&>(result) = run.run;
  result.update_iterations = run.update_iterations;
}

void Optimizer::Impl::adapt(const SizeField& field, const AdaptOptions& options,
                            const Observer& observer, Result& result) {
  const TargetsAt targets = set_up_adaptation(field, options, observer, result);
  if (options.untangle) result.untangling = untangle(method(options.solver), observer);
  picard_iteration(targets, options, observer, result);
}

void Optimizer::Impl::fit(const LevelSet& level_set, const SizeField& field,
                          const AdaptOptions& options, const PicardOptions& last_stage,
                          const Observer& observer, Result& result) {
  phi = std::make_unique<LevelSetFunction>(level_set_function(level_set, view().dim));
  const FitHooks hooks{
      .constrain = [this](SlidingVertices extra) -> const Functional& {
        return constrain(std::move(extra));
      },
      .targets = adaptation_targets(field, options.field),
      .set_targets = [this](const CellTargets& t) -> const Functional& { return set_targets(t); }};
  fitted = fit_interface(view(), dofs(), x, *phi, hooks, last_stage, method(options.solver), {},
                         observer);
  const FitResult& f = *fitted;
  // The fit's iterations follow the adaptation's; it starts from new volumes.
  const int before = static_cast<int>(result.history.size());
  result.update_iterations.push_back(before);
  result.history.insert(result.history.end(), f.picard.run.history.begin(),
                        f.picard.run.history.end());
  for (int k : f.picard.update_iterations) result.update_iterations.push_back(k + before);
  result.reason = f.picard.run.reason;
  result.final_energy = f.picard.run.final_energy;
  result.final_defect = f.picard.run.final_defect;
  std::int64_t counts[2] = {f.interface.num_facets(), 0};  // over all processes: facets, vertices
  for (PetscInt u : f.interface.vertices) counts[1] += view().owned[u];
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT64_T, MPI_SUM, mesh.comm());
  result.fit = FitSummary{.level_set = level_set.expression(),
                          .facets = counts[0],
                          .vertices = counts[1],
                          .max_distance = f.max_distance,
                          .stages = f.stages,
                          .undone = f.retries,
                          .cells_moved_across = f.interface.cells_flipped,
                          .iterations = static_cast<int>(f.picard.run.history.size())};
}

namespace {

// Only smoothing optimizes curved meshes.
void refuse_curved(const Mesh& mesh, std::string_view what) {
  if (mesh.curved())
    fail(
        "{}: has second-order (curved) cells, which {} does not take (neomesh smooths, measures "
        "and converts them)",
        mesh.name(), what);
}

}  // namespace

Optimizer::Optimizer(Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
Optimizer::~Optimizer() = default;
Optimizer::Optimizer(Optimizer&&) noexcept = default;
Optimizer& Optimizer::operator=(Optimizer&&) noexcept = default;

// The phases of smoothing, in the order of docs/method.md §8 (the worst cells' phases are
// optimize()'s).
Result Optimizer::smooth(const SmoothOptions& options, const Observer& observer) {
  Impl& r = *impl_;
  if (r.mesh.curved()) return r.smooth_curved(options, observer);
  Result result = r.start(options);
  const Impl::Smoothing s = r.set_up_smoothing(options, observer, result);
  if (options.untangle) result.untangling = r.untangle(s.method, observer);
  r.optimize(s, result);
  r.retry_towards_ideal_cells(s, result);
  r.finish(result);
  result.seconds = MPI_Wtime() - r.started;
  return result;
}

// The phases of adaptation (docs/adaptivity.md).
Result Optimizer::adapt(const SizeField& field, const AdaptOptions& options,
                        const Observer& observer) {
  Impl& r = *impl_;
  refuse_curved(r.mesh, "adapt");
  r.refuse_surface(field);
  Result result = r.start(options);
  const OwnedVec input =
      copy_of(r.x);  // where the adaptation starts (vertices placed on their charts)
  r.adapt(field, options, observer, result);
  if (options.quality_guard) r.lift_corners(r.method(options.solver), observer, result);
  // The guard judges cells against the ideal cell, which a metric field stretches on purpose;
  // a corner left nearly flat is no metric's aim.
  if (options.quality_guard && !field.anisotropic())
    r.guard_worst(input, result, AdaptOptions::kGuardCeiling);
  r.finish(result);
  result.volume_ratio = r.volume_ratio();
  result.seconds = MPI_Wtime() - r.started;
  return result;
}

// The phases of adaptation with a fit (docs/adaptivity.md).
Result Optimizer::adapt(const SizeField& field, const LevelSet& fit_to, const AdaptOptions& options,
                        const Observer& observer) {
  Impl& r = *impl_;
  refuse_curved(r.mesh, "adapt");
  r.refuse_surface(field);
  Result result = r.start(options);
  const FittedAdaptation parts = fitted_adaptation(options, r.warm);
  r.adapt(field, parts.adapting, observer, result);
  if (observer.fitting) observer.fitting(fit_to.expression());
  r.fit(fit_to, field, parts.fitting, parts.last_stage, observer, result);
  r.finish(result);
  result.volume_ratio = r.volume_ratio();
  result.seconds = MPI_Wtime() - r.started;
  return result;
}

Result Optimizer::adapt(const LevelSet& phi, const AdaptOptions& options,
                        const Observer& observer) {
  SizeField field = SizeField::level_set(phi.expression());
  field.set_time(phi.time());
  return adapt(field, phi, options, observer);
}

void Optimizer::forget_warm_start() {
  impl_->warm = false;
  impl_->smoothed.reset();
}

std::vector<Field> Optimizer::cell_fields() const {
  const Impl& r = *impl_;
  // A curved mesh's fields would be of its node mesh's cells: none are written.
  if (r.curved || !r.functional || r.problem.desired_volumes().empty()) return {};
  const CellFields fields = r.functional->cell_fields(r.x);
  std::vector<Field> out = {{"energy", fields.energy},
                            {"det_G_min", fields.min_det},
                            {"Q", fields.volume_ratio},
                            {"desired_volume", r.problem.desired_volumes()}};
  if (!r.input_share.empty()) out.push_back({"target_input_share", r.input_share});
  if (r.fitted)
    out.push_back({"inside", std::vector<double>(r.fitted->interface.inside.begin(),
                                                 r.fitted->interface.inside.end())});
  return out;
}

std::vector<Field> Optimizer::vertex_fields() const {
  const Impl& r = *impl_;
  if (!r.fitted) return {};
  const MeshView& view = r.view();
  std::vector<double> on(view.num_vertices, 0.0), phi(view.num_vertices);
  for (PetscInt u : r.fitted->interface.vertices) on[u] = 1.0;
  for (PetscInt u = 0; u < view.num_vertices; ++u) {
    Point p = Point::Zero();
    for (int j = 0; j < view.dim; ++j) p[j] = view.coords[u * view.dim + j];
    phi[u] = r.phi->value(p);
  }
  return {public_vertex_field(view, "interface", on), public_vertex_field(view, "phi", phi)};
}

std::vector<FacetGroup> Optimizer::facet_groups() const {
  const Impl& r = *impl_;
  if (!r.fitted) return {};
  return {public_facet_group(r.view(), "interface", r.fitted->interface.offsets,
                             r.fitted->interface.facet_vertices)};
}

double Optimizer::evaluate(const SmoothOptions& options) {
  options.validate();
  Impl& r = *impl_;
  refuse_curved(r.mesh, "evaluate");
  r.start(options.energy, options.boundary);
  r.x = r.mesh.plex().coordinates();  // as they are: sliding vertices not projected
  r.warm = false;
  r.smoothed.reset();
  r.set_targets(r.smoothing_targets(targets_asked(options), options.sizes));
  return r.functional->value(r.x);
}

}  // namespace neomesh
