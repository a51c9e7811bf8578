// Smoothing a mesh of second-order cells: the phases of Optimizer::smooth for curved meshes
// (docs/method.md §12, "The solver").
#include <mpi.h>

#include <algorithm>
#include <memory>
#include <numeric>

#include "api/optimizer_impl.hpp"
#include "core/error.hpp"
#include "geometry/curved_quality.hpp"
#include "geometry/node_mesh.hpp"
#include "mesh/from_input_vertices.hpp"
#include "mesh/gather.hpp"
#include "solver/curved_repair.hpp"
#include "solver/quasi_newton.hpp"
#include "solver/worst_cells.hpp"
#include "targets/input_targets.hpp"

namespace neomesh {

void Optimizer::Impl::start_curved(const SmoothOptions& options) {
  // Nothing of an earlier call is kept: the node mesh is the mesh's as it is now.
  functional.reset();
  fitted.reset();
  boundary.reset();
  problem = Problem();
  input_cells.reset();
  input_share.clear();
  curved.reset();
  // The whole curved mesh on rank 0, which builds the node mesh and sends each process its part.
  const InputMesh input = gather_mesh(mesh.plex(), {}).mesh;
  curved = std::make_unique<CurvedMesh>(distribute_node_mesh(input, mesh.name(), mesh.comm()));
  x = curved->nodes.coordinates();
  const std::vector<double> volumes = cell_volumes();
  const double local_volume = std::accumulate(volumes.begin(), volumes.end(), 0.0);
  MPI_Allreduce(&local_volume, &mesh_volume, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
  boundary = std::make_unique<Boundary>(curved->nodes.view(), dofs(), options.boundary, true);
  energy = options.energy;
  boundary_options = options.boundary;
  constrain({});
  boundary->project(x);
}

CurvedQualitySummary Optimizer::Impl::curved_quality_at_x() {
  std::vector<double> local(dofs().num_local_dofs());
  dofs().global_to_local(x, local);
  return curved_quality(curved->cells, local, mesh.comm());
}

void Optimizer::Impl::finish_curved(Result& result) {
  PlexMesh& plex = mesh.plex();
  const MeshView& view = plex.view();
  const int d = view.dim;
  std::vector<double> local_x(dofs().num_local_dofs());
  dofs().global_to_local(x, local_x);
  // Every point on rank 0 in input numbering, the corners back to the processes that hold them in
  // the mesh's own partition (another than the node mesh's).
  const std::vector<double> points =
      gather_points(curved->nodes.view(), local_x, curved->points, mesh.comm());
  std::vector<double> local =
      FromInputVertices(view, static_cast<PetscInt>(points.size()) / d, mesh.comm())(points, d);
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    if (!view.owned[v]) std::fill_n(local.begin() + d * v, d, 0.0);
  const OwnedVec corners = plex.dofs().create_global_vector();
  plex.dofs().add_local_to_global(local, corners);
  // Rank 0's high-order nodes: its points after the corners (none elsewhere).
  const std::size_t corners_end = points.empty() ? 0 : d * plex.global_num_vertices();
  plex.set_high_order_nodes(std::span(points).subspan(corners_end));
  plex.set_coordinates(corners);
  result.quality_after = mesh.quality();
  result.boundary_distance = boundary->max_distance_from_input(x);
  const std::vector<double> volumes = curved_cell_volumes(curved->cells, local_x);
  double volume = std::accumulate(volumes.begin(), volumes.end(), 0.0);
  MPI_Allreduce(MPI_IN_PLACE, &volume, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
  result.volume_change = (volume - mesh_volume) / mesh_volume;
}

QuasiNewtonOptions Optimizer::Impl::curved_method(const SolverOptions& solver) {
  QuasiNewtonOptions o = method(solver);
  // The energy sees det J at its sample points only; between them a step may fold a cell that
  // the certificate passed (§11). Cells certified valid here must stay so at every point taken.
  std::vector<double> local(dofs().num_local_dofs());
  dofs().global_to_local(x, local);
  auto valid = std::make_shared<const std::vector<char>>(certified_valid(curved->cells, local));
  o.admissible = [this, valid, local = std::move(local)](Vec trial) mutable {
    dofs().global_to_local(trial, local);
    const std::vector<char> still = certified_valid(curved->cells, local, *valid);
    int lost = !std::equal(still.begin(), still.end(), valid->begin());
    MPI_Allreduce(MPI_IN_PLACE, &lost, 1, MPI_INT, MPI_MAX, mesh.comm());
    return lost == 0;
  };
  return o;
}

void Optimizer::Impl::lift_curved_corners(const SmoothOptions& options, const Observer& observer,
                                          Result& result) {
  // The thesis' energy samples the Gauss points only, and its barrier keeps det J > 0 at the
  // corners without holding it away from 0 there: an untangled tetrahedron10 ended with a corner
  // at curved scaled Jacobian 8e-4 (sphereCylinder_1194_inv). The worst-cell phase of straight
  // meshes lifts it, the corners in the energy; its result is kept only where the least curved
  // scaled Jacobian rose (which also certifies every cell: a cell not certified valid has ≤ 0).
  const OwnedVec optimum = copy_of(x);
  const SolverRun run = result;
  const auto least = [this](Vec) { return curved_quality_at_x().scaled_jacobian.min; };
  result.corner_phase =
      lift_flat_corners(*functional, view(), dofs(), x, curved_method(options.solver), cell_size,
                        result, observer.iteration, least);
  CornerPhaseSummary* phase = result.corner_phase ? &*result.corner_phase : nullptr;
  if (phase && !phase->gave_up &&
      !(phase->min_scaled_jacobian_after > phase->min_scaled_jacobian_before)) {
    NM_PETSC(VecCopy(optimum, x));
    static_cast<SolverRun&>(result) = run;
    phase->min_scaled_jacobian_after = phase->min_scaled_jacobian_before;
    phase->gave_up = true;
  }
}

Result Optimizer::Impl::smooth_curved(const SmoothOptions& options, const Observer& observer) {
  options.validate();
  started = MPI_Wtime();
  Result result;
  result.quality_before = mesh.quality();
  const CurvedQualitySummary before = *result.quality_before.curved;
  // Cells not certified valid (det J ≤ 0 somewhere) are untangled first, towards ideal cells as
  // a tangled straight mesh's are; the result must be certified valid then, or nothing is.
  const bool tangled = before.not_valid > 0;
  if (tangled && !options.untangle)
    fail(
        "{}: {} of its second-order cells are not certified valid (det J > 0 everywhere), and "
        "untangling is switched off",
        mesh.name(), before.not_valid);
  start_curved(options);
  warm = false;
  const TargetMode mode = tangled ? TargetMode::Ideal : targets_asked(options);
  const CellTargets targets = smoothing_targets(mode, options.sizes);
  set_targets(targets);
  const KeptCells kept = count_kept(targets.input_share, mesh.comm());
  result.problem = problem_summary(options.solver);
  result.problem.targets = {
      .mode = std::string(name(mode)),
      .input = kept.all,
      .blended = kept.part,
      .ideal = kept.none,
      .ideal_because_tangled = tangled && options.targets != TargetMode::Ideal,
      .ideal_because_sizes = !tangled && mode != options.targets};
  if (observer.started) observer.started(result.problem);
  const OwnedVec input = copy_of(x);
  // Cells folded at a sample point of the untangling energy (the corners and Gauss points).
  if (options.untangle) result.untangling = untangle(method(options.solver), observer);
  static_cast<SolverRun&>(result) =
      minimize(*functional, x, curved_method(options.solver), cell_size, observer.iteration);
  // A valid input is returned where the optimum is worse (below), which costs nothing; the lift
  // cost sphereCylinder_22492 twice the time and still ended below the input.
  if (tangled) lift_curved_corners(options, observer, result);

  // The certificate decides (§11). The worst cells of the optimum are repaired, which may also
  // lift cells it left uncertified; with the quality guard, the worst cell may not get worse
  // than the input's either: a valid input is kept (its own worst cells repaired) where the
  // repaired optimum's is worse.
  CurvedSmoothingSummary& summary = result.curved.emplace();
  summary.cells = mesh.plex().global_num_cells();
  summary.nodes = curved->points;
  summary.min_scaled_jacobian_before = before.scaled_jacobian.min;
  const CurvedQualitySummary optimum = curved_quality_at_x();
  summary.min_scaled_jacobian_optimum = optimum.scaled_jacobian.min;
  summary.not_valid_optimum = optimum.not_valid;
  const bool repair =
      options.quality_guard && options.repair_worst_cells && result.reason != StopReason::TimeLimit;
  const auto repair_worst = [&] {
    const WorstCellRepair r = repair_worst_curved_cells(view(), dofs(), repair_freedom(), x);
    result.worst_cell_repair = {.min_scaled_jacobian_before = r.min_before,
                                .min_scaled_jacobian_after = r.min_after,
                                .vertices_moved = r.vertices_moved,
                                .sweeps = r.sweeps};
    return r.vertices_moved > 0 ? curved_quality_at_x() : optimum;
  };
  const CurvedQualitySummary repaired = repair ? repair_worst() : optimum;
  if (tangled && repaired.not_valid > 0)
    fail(
        "{}: {} of its {} second-order cells are still not certified valid after untangling, "
        "smoothing and repairing the worst cells ({} before): det J ≤ 0 between the points the "
        "energy samples",
        mesh.name(), repaired.not_valid, summary.cells, before.not_valid);
  summary.input_returned =
      !tangled &&
      (repaired.not_valid > 0 ||
       (options.quality_guard && repaired.scaled_jacobian.min < before.scaled_jacobian.min));
  if (summary.input_returned) {
    NM_PETSC(VecCopy(input, x));
    if (repair) repair_worst();
  }
  result.final_energy = functional->value(x);
  finish_curved(result);
  result.seconds = MPI_Wtime() - started;
  return result;
}

}  // namespace neomesh
