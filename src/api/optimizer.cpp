#include <neomesh/optimizer.hpp>

#include <mpi.h>

#include <utility>

#include "adapt/picard.hpp"
#include "adapt/size_field.hpp"
#include "api/optimizer_impl.hpp"
#include "boundary/interface.hpp"
#include "core/error.hpp"
#include "geometry/quality.hpp"
#include "solver/desired_volumes.hpp"
#include "solver/quality_guard.hpp"
#include "solver/untangle.hpp"

namespace neomesh {

namespace {

bool same(const EnergyOptions& a, const EnergyOptions& b) {
  return a.lambda == b.lambda && a.mu == b.mu && a.kappa == b.kappa &&
         a.gauss_points == b.gauss_points;
}
bool same(const BoundaryOptions& a, const BoundaryOptions& b) {
  return a.mode == b.mode && a.feature_angle == b.feature_angle && a.shapes == b.shapes;
}

}  // namespace

void copy_run(const QuasiNewtonResult& run, Result& result) {
  result.history = run.history;
  result.reason = run.reason;
  result.initial_energy = run.initial_energy;
  result.final_energy = run.final_energy;
  result.initial_defect = run.initial_defect;
  result.final_defect = run.final_defect;
  result.times = run.times;
}

namespace {

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

}  // namespace

Optimizer::Impl::Impl(Mesh& m) : mesh(m) {}

void Optimizer::Impl::start(const EnergyOptions& e, const BoundaryOptions& b) {
  x = mesh.plex().coordinates();
  if (functional && energy && same(*energy, e) && boundary_options && same(*boundary_options, b)) {
    boundary->project(x);
    return;
  }
  double local = 0.0;
  for (double v : cell_volumes()) local += v;
  MPI_Allreduce(&local, &mesh_volume, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
  const std::vector<double> volumes =
      functional ? functional->desired_volumes() : std::vector<double>{};
  boundary = std::make_unique<Boundary>(view(), dofs(), b);
  functional = std::make_unique<Functional>(view(), dofs(), e, boundary->fixed_dofs(),
                                            boundary->sliding_vertices());
  if (!volumes.empty()) functional->set_desired_volumes(volumes);
  boundary->project(x);  // onto given shapes and charts: they pass within 1e-6 h
  energy = e;
  boundary_options = b;
}

void Optimizer::Impl::set_desired_volumes(std::vector<double> volumes) {
  functional->set_desired_volumes(volumes);
  cell_size = local_cell_size(view(), dofs(), volumes);
}

const Functional& Optimizer::Impl::constrain(SlidingVertices extra) {
  const std::vector<double> volumes = functional->desired_volumes();
  functional = std::make_unique<Functional>(view(), dofs(), *energy, boundary->fixed_dofs(),
                                            join(boundary->sliding_vertices(), std::move(extra)));
  if (!volumes.empty()) functional->set_desired_volumes(volumes);
  return *functional;
}

std::optional<UntanglingSummary> Optimizer::Impl::untangle(const QuasiNewtonOptions& method,
                                                           const Observer& observer) {
  const PetscInt inverted = functional->inversion(x, 0).count;
  if (inverted == 0) return std::nullopt;
  if (observer.untangling) observer.untangling(inverted);
  const UntangleResult u =
      neomesh::untangle(*functional, x, method, cell_size, {}, observer.iteration);
  if (u.after.count > 0)
    fail(
        "{}: the mesh cannot be untangled with its boundary as it is: {} of {} inverted cells "
        "are still inverted after {} iterations (cells {}; 0-based, in input order)",
        mesh.name(), u.after.count, u.before.count, u.history.size(), list_cells(u.after));
  const UntanglingSummary summary = summarize(u);
  if (observer.untangled) observer.untangled(summary);
  return summary;
}

ProblemSummary Optimizer::Impl::problem() const {
  double free = 0.0;
  NM_PETSC(VecSum(functional->free_mask(), &free));
  ProblemSummary p;
  p.free_coordinates = static_cast<std::int64_t>(free);
  if (boundary_options->mode == BoundaryMode::Slide) p.boundary = boundary->summary();
  return p;
}

QuasiNewtonOptions Optimizer::Impl::method(const SolverOptions& solver) const {
  QuasiNewtonOptions o{solver};
  o.energy_roundoff = energy_roundoff(*energy, view().dim, mesh_volume);
  return o;
}

std::vector<double> Optimizer::Impl::cell_volumes() const {
  return cell_quality(view(), view().coords).volume;
}

QualitySummary Optimizer::Impl::input_quality(bool untangle) const {
  const QualitySummary quality = mesh.quality();
  if (!untangle && (quality.inverted > 0 || quality.degenerate > 0))
    fail("{} has {} inverted and {} degenerate cells, and untangling is switched off", mesh.name(),
         quality.inverted, quality.degenerate);
  return quality;
}

QualitySummary Optimizer::Impl::finish() {
  mesh.plex().set_coordinates(x);
  const QualitySummary summary = mesh.quality();
  if (summary.inverted > 0 || summary.degenerate > 0)
    fail(
        "the optimized mesh has {} inverted and {} degenerate cells (please report this with the "
        "input mesh)",
        summary.inverted, summary.degenerate);
  return summary;
}

Optimizer::Optimizer(Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
Optimizer::~Optimizer() = default;
Optimizer::Optimizer(Optimizer&&) noexcept = default;
Optimizer& Optimizer::operator=(Optimizer&&) noexcept = default;

Optimizer::Impl& Optimizer::impl() {
  return *impl_;
}

Result Optimizer::smooth(const SmoothOptions& options, const Observer& observer) {
  options.validate();
  Impl& r = *impl_;
  const double start = MPI_Wtime();
  Result result;
  result.quality_before = r.input_quality(options.untangle);
  r.start(options.energy, options.boundary);
  r.warm = false;  // the desired volumes are smoothing's now
  r.set_desired_volumes(desired_volumes(options.sizes, r.view(), r.dofs(), r.cell_volumes()));
  const QuasiNewtonOptions method = r.method(options.solver);
  if (observer.started) observer.started(r.problem());

  // The guard's promise is about the input: a tangled input's worst cell is inverted, so any
  // untangled output keeps it.
  OwnedVec input;
  NM_PETSC(VecDuplicate(r.x, input.out()));
  NM_PETSC(VecCopy(r.x, input));
  if (options.untangle) result.untangling = r.untangle(method, observer);
  const QuasiNewtonResult run =
      minimize(*r.functional, r.x, method, r.cell_size, observer.iteration);
  copy_run(run, result);
  if (options.quality_guard) {
    result.quality_guard = guard_worst_quality(
        r.view(), r.dofs(), input, r.x, [&r](Vec x) { r.functional->project_onto_boundary(x); });
    if (result.quality_guard->vertices_moved > 0) result.final_energy = r.functional->value(r.x);
  }
  result.quality_after = r.finish();
  result.seconds = MPI_Wtime() - start;
  return result;
}

Result Optimizer::adapt(const SizeField& field, const AdaptOptions& options,
                        const Observer& observer) {
  options.validate();
  Impl& r = *impl_;
  const double start = MPI_Wtime();
  Result result;
  result.quality_before = r.input_quality(options.untangle);
  r.start(options.energy, options.boundary);
  const auto target_volumes =
      size_field_volumes(field, options.sizes, r.view(), r.dofs(), r.mesh_volume);
  // The size field's volumes at the start: what the observer sees, and what untangling aims at.
  r.set_desired_volumes(target_volumes(r.x));
  if (observer.started) observer.started(r.problem());
  if (options.untangle) result.untangling = r.untangle(r.method(options.solver), observer);
  PicardOptions picard = options.picard;
  if (r.warm) picard.min_updates = options.warm_updates;
  const PicardResult run = neomesh::picard(
      *r.functional, r.view(), r.x, target_volumes,
      [&r](const std::vector<double>& v) { r.set_desired_volumes(v); }, picard,
      r.method(options.solver), observer);
  r.warm = true;
  copy_run(run.run, result);
  result.update_iterations = run.update_iterations;
  result.quality_after = r.finish();
  result.seconds = MPI_Wtime() - start;
  return result;
}

void Optimizer::forget_warm_start() {
  impl_->warm = false;
}

std::vector<Field> Optimizer::cell_fields() const {
  const Impl& r = *impl_;
  if (!r.functional || r.functional->desired_volumes().empty()) return {};
  const CellFields fields = r.functional->cell_fields(r.x);
  return {{"energy", fields.energy},
          {"det_G_min", fields.min_det},
          {"Q", fields.volume_ratio},
          {"desired_volume", r.functional->desired_volumes()}};
}

double Optimizer::evaluate(const SmoothOptions& options) {
  options.validate();
  Impl& r = *impl_;
  r.start(options.energy, options.boundary);
  r.x = r.mesh.plex().coordinates();  // as they are: sliding vertices not projected
  r.warm = false;
  r.set_desired_volumes(desired_volumes(options.sizes, r.view(), r.dofs(), r.cell_volumes()));
  return r.functional->value(r.x);
}

}  // namespace neomesh
