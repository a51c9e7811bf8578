// Smoothing a mesh of second-order cells: the phases of Optimizer::smooth for curved meshes
// (docs/method.md §12, "The solver").
#include <mpi.h>

#include <numeric>

#include "api/optimizer_impl.hpp"
#include "core/error.hpp"
#include "geometry/curved_quality.hpp"
#include "geometry/node_mesh.hpp"
#include "mesh/gather.hpp"
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
  InputMesh input = gather_mesh(mesh.plex(), {}).mesh;
  NodeMesh nodes = node_mesh(input);
  // Sub-cells of a valid curved cell may be inverted (a bent edge): they give the topology only.
  PlexMesh plex = PlexMesh::from_input(nodes.mesh, mesh.name(), mesh.comm(), true);
  MeshView cells = curved_cells_view(plex.view(), input);
  MeshView corners = corner_cells_view(plex.view(), input);
  curved = std::make_unique<CurvedMesh>(
      CurvedMesh{std::move(input), std::move(plex), std::move(cells), std::move(corners)});
  x = curved->nodes.coordinates();
  const std::vector<double> volumes = cell_volumes();
  mesh_volume = std::accumulate(volumes.begin(), volumes.end(), 0.0);
  boundary = std::make_unique<Boundary>(curved->nodes.view(), dofs(), options.boundary, true);
  energy = options.energy;
  boundary_options = options.boundary;
  constrain({});
  boundary->project(x);
}

CurvedQualitySummary Optimizer::Impl::curved_quality_at_x() {
  InputMesh& input = curved->input;
  const MeshView& nodes = curved->nodes.view();
  const int d = nodes.dim;
  std::vector<double> local(dofs().num_local_dofs());
  dofs().global_to_local(x, local);
  // The node mesh's first vertices are the curved mesh's points (node_mesh.hpp).
  std::vector<double> points(static_cast<std::size_t>(d * input.num_points()));
  for (PetscInt v = 0; v < nodes.num_vertices; ++v)
    if (const PetscInt p = nodes.input_vertex[v]; p < input.num_points())
      std::copy_n(local.begin() + d * v, d, points.begin() + d * p);
  set_curved_point_coordinates(input, points);
  return curved_quality(input);
}

void Optimizer::Impl::finish_curved(Result& result) {
  const InputMesh& input = curved->input;  // its points at x (curved_quality_at_x)
  PlexMesh& plex = mesh.plex();
  const MeshView& view = plex.view();
  const int d = view.dim;
  // The corners, by their input numbers (the curved mesh's first points).
  std::vector<double> local(static_cast<std::size_t>(d * view.num_vertices));
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    std::copy_n(input.coords.begin() + d * view.input_vertex[v], d, local.begin() + d * v);
  const OwnedVec corners = plex.dofs().create_global_vector();
  plex.dofs().add_local_to_global(local, corners);
  const std::vector<double> points = curved_point_coordinates(input);
  plex.set_high_order_nodes(std::span(points).subspan(input.coords.size()));
  plex.set_coordinates(corners);
  result.quality_after = mesh.quality();
  result.boundary_distance = boundary->max_distance_from_input(x);
  std::vector<double> local_x(dofs().num_local_dofs());
  dofs().global_to_local(x, local_x);
  const std::vector<double> volumes = curved_cell_volumes(curved->cells, local_x);
  const double volume = std::accumulate(volumes.begin(), volumes.end(), 0.0);
  result.volume_change = (volume - mesh_volume) / mesh_volume;
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
  result.corner_phase = lift_flat_corners(*functional, view(), dofs(), x, method(options.solver),
                                          cell_size, result, observer.iteration, least);
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
  if (mpi_size(mesh.comm()) > 1)
    fail(
        "{}: a mesh of second-order (curved) cells is smoothed on one process only; run it "
        "without mpiexec",
        mesh.name());
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
      minimize(*functional, x, method(options.solver), cell_size, observer.iteration);
  // A valid input is returned where the optimum is worse (below), which costs nothing; the lift
  // cost sphereCylinder_22492 twice the time and still ended below the input.
  if (tangled) lift_curved_corners(options, observer, result);

  // The barrier sees det J at sample points only; the certificate decides (§11). With the quality
  // guard, the worst cell may not get worse either.
  CurvedSmoothingSummary& summary = result.curved.emplace();
  summary.cells = curved->input.num_cells();
  summary.nodes = curved->input.num_points();
  summary.min_scaled_jacobian_before = before.scaled_jacobian.min;
  const CurvedQualitySummary optimum = curved_quality_at_x();
  summary.min_scaled_jacobian_optimum = optimum.scaled_jacobian.min;
  summary.not_valid_optimum = optimum.not_valid;
  if (tangled && optimum.not_valid > 0)
    fail(
        "{}: {} of its {} second-order cells are still not certified valid after untangling "
        "and smoothing ({} before): det J ≤ 0 between the points the energy samples",
        mesh.name(), optimum.not_valid, summary.cells, before.not_valid);
  summary.input_returned =
      !tangled &&
      (optimum.not_valid > 0 ||
       (options.quality_guard && optimum.scaled_jacobian.min < before.scaled_jacobian.min));
  if (summary.input_returned) {
    NM_PETSC(VecCopy(input, x));
    curved_quality_at_x();
    result.final_energy = functional->value(x);
  }
  finish_curved(result);
  result.seconds = MPI_Wtime() - started;
  return result;
}

}  // namespace neomesh
