// What an Optimizer holds (include/neomesh/optimizer.hpp).
//
// One owner per piece of state: the Mesh owns the coordinates between calls; during a call
// they are the Vec x, which is handed back with finish(). The Impl owns the problem (targets and
// constraints) and the functional built from it, the boundary classification, what derives
// from the desired volumes (the cell size of the practical criterion, the round-off level of
// F), and a fit's interface with the level set its constraint refers to.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include <neomesh/optimizer.hpp>

#include "adapt/fit.hpp"
#include "boundary/boundary.hpp"
#include "energy/functional.hpp"
#include "geometry/node_mesh.hpp"
#include "mesh/input_mesh.hpp"
#include "mesh/plex_mesh.hpp"
#include "solver/quasi_newton.hpp"
#include "solver/worst_cell_repair.hpp"
#include "targets/cell_targets.hpp"

namespace neomesh {

// The share of a surface's gain in mean inverse mean ratio over the input that the worst-cell
// repair may spend (Optimizer::Impl::repair_imr_ceiling).
inline constexpr double kRepairImrSpend = 0.5;
// Smoothing's target mode after the sizes asked for (docs/method.md §9): smoothed targets with
// uniform sizes are ideal ones.
TargetMode targets_asked(const SmoothOptions& options);

struct Optimizer::Impl {
  explicit Impl(Mesh& mesh);

  // A mesh of second-order cells as smoothing optimizes it (geometry/node_mesh.hpp): every node
  // a vertex of `nodes`, whose view the boundary is classified on; the energy's cells are
  // `cells`, the curved ones; `corners` their straight corner cells. Built where a smoothing of
  // a curved mesh starts, from the mesh's coordinates then.
  using CurvedMesh = DistributedNodeMesh;
  std::unique_ptr<CurvedMesh> curved;

  // The vertices and cells the optimization runs on: the mesh's, or for a curved mesh the nodes
  // and the curved cells. Read-only: the mesh keeps its quality cache (Mesh::plex()).
  const MeshView& view() const {
    return curved ? curved->cells : std::as_const(mesh).plex().view();
  }
  const DofMap& dofs() const {
    return curved ? curved->nodes.dofs() : std::as_const(mesh).plex().dofs();
  }

  // Smoothing a mesh of second-order cells (docs/method.md §12, "The solver"): its own list of
  // phases — set up the node mesh, the targets, untangle, minimize inside the certified-valid
  // cells, lift flat corners, judge by the certificate and the curved scaled Jacobian, repair the
  // worst cells, finish.
  Result smooth_curved(const SmoothOptions& options, const Observer& observer);
  // The node mesh of the mesh's curved cells, the boundary and the constraints on it; x at its
  // vertices.
  void start_curved(const SmoothOptions& options);
  // The worst-cell phase on the curved optimum at x: result.corner_phase, by the least curved
  // scaled Jacobian; x and result's run are the optimum's again unless that rose.
  void lift_curved_corners(const SmoothOptions& options, const Observer& observer, Result& result);
  // The solver options of a curved mesh at x: method()'s, with the barrier that keeps the cells
  // certified valid at x so (QuasiNewtonOptions::admissible).
  QuasiNewtonOptions curved_method(const SolverOptions& solver);
  // The curved quality of the cells at x (collective: every process gets the summary).
  CurvedQualitySummary curved_quality_at_x();
  // Moves the mesh's corners and high-order nodes to x, and sets result's quality_after,
  // boundary change and volume change.
  void finish_curved(Result& result);

  // The mesh's quality where a call starts; throws Error if cells are inverted or degenerate
  // and `untangle` is false.
  QualitySummary input_quality(bool untangle) const;
  // On a surface mesh, throws Error for what it does not support: degenerate cells in `input`;
  // in adapt, a metric `field` (a fit to a level set: find_interface).
  void refuse_surface(const QualitySummary& input) const;
  void refuse_surface(const SizeField& field) const;
  // What smooth() and adapt() do first: checks `options` and the input (input_quality), takes
  // the mesh's coordinates into x, and (re)builds the boundary classification and the
  // problem's constraints unless they were built for the same energy and boundary options
  // (then the desired volumes stay). An earlier fit's interface is released. Sliding vertices are
  // projected onto their geometry. Returns the result with quality_before.
  template <typename Options>
  Result start(const Options& options) {
    options.validate();
    started = MPI_Wtime();
    Result result;
    result.quality_before = input_quality(options.untangle);
    refuse_surface(result.quality_before);
    keep_input_cells();
    start(options.energy, options.boundary, &options.solver);
    return result;
  }
  // `solver`: the solves to come, for the memory check (none: evaluation only).
  void start(const EnergyOptions& energy, const BoundaryOptions& boundary,
             const SolverOptions* solver = nullptr);
  // Smoothing's targets (targets/input_targets.hpp) from the input cells at x, and setting them:
  // the volumes absolute per local cell (MeshView order), summing to mesh_volume. Returns the
  // functional of the new problem.
  CellTargets smoothing_targets(TargetMode mode, SizeMode sizes) const;
  const Functional& set_targets(const CellTargets& targets);
  // The problem with `extra` vertices sliding besides the boundary's (an interface fitted to a
  // level set; none: the boundary's alone), keeping the targets; returns its functional.
  const Functional& constrain(SlidingVertices extra);
  // The functional of `problem` as it is now.
  const Functional& rebuild_functional();

  // The phases, in the order smooth() and adapt() call them: each is a function of the run's
  // state (x, the problem, and for smoothing the Smoothing below) that fills its own part of
  // the Result.

  // What the phases of one smoothing share.
  struct Smoothing {
    const SmoothOptions& options;
    const Observer& observer;
    QuasiNewtonOptions method;
    TargetMode mode;    // of the targets set up (ideal for a tangled input)
    bool tangled;       // the input has inverted or degenerate cells
    OwnedVec input;     // x before untangling: the input, its vertices placed on their charts
    double input_mean;  // ... and its mean scaled Jacobian
    double input_imr;   // ... and, of a surface, its mean inverse mean ratio (else +∞)
  };
  // Smoothing's targets from the input cells (docs/method.md §9) and the problem with them:
  // result.problem, told to the observer. Returns the run's state.
  Smoothing set_up_smoothing(const SmoothOptions& options, const Observer& observer,
                             Result& result);
  // If cells are inverted at x, untangles them (docs/untangling.md) towards the current targets,
  // telling `observer`; throws Error naming the cells that stay inverted.
  std::optional<UntanglingSummary> untangle(const QuasiNewtonOptions& method,
                                            const Observer& observer);
  // The minimization (docs/method.md §4) and, unless the guard is off, the worst cells' phases
  // after it (§8): lift_corners(), repair_worst() (unless switched off), guard_worst() and, for a
  // valid input, guard_mean(); into `run`.
  void optimize(const Smoothing& s, Result& run);
  // Where the cells kept from the input stayed flat (the corner phase gave up, or a kept cell is
  // a flat cap), optimize() once more from the input towards ideal cells; the run whose worst
  // cell is better is kept (docs/method.md §8, "Corners"). Fills result.ideal_retry.
  void retry_towards_ideal_cells(const Smoothing& s, Result& result);
  // Adaptation's targets for `field` at x and the problem with them: result.problem, told to
  // the observer. Returns the targets at any x (adaptation_targets).
  TargetsAt set_up_adaptation(const SizeField& field, const AdaptOptions& options,
                              const Observer& observer, Result& result);
  // The Picard iterations towards `targets` (adapt/picard.hpp): the run and its updates go into
  // `result`.
  void picard_iteration(const TargetsAt& targets, const AdaptOptions& options,
                        const Observer& observer, Result& result);
  // Adapts x to `field`: set_up_adaptation(), untangle() if asked, picard_iteration().
  void adapt(const SizeField& field, const AdaptOptions& options, const Observer& observer,
             Result& result);
  // After an adaptation: fits x to the zero set of `level_set` (adapt/fit.hpp), the last stage
  // adapting with `last_stage`; appends the fit's iterations to `result` and fills result.fit.
  void fit(const LevelSet& level_set, const SizeField& field, const AdaptOptions& options,
           const PicardOptions& last_stage, const Observer& observer, Result& result);
  // Once the method has stopped (unless at the time limit): corners it left nearly flat are
  // lifted (worst_cells.hpp); fills run.corner_phase and appends its iterations.
  void lift_corners(const QuasiNewtonOptions& method, const Observer& observer, Result& run);
  // Unless the method stopped at the time limit: the local repair of x's worst cells
  // (worst_cell_repair.hpp) into run.worst_cell_repair. No move takes the mean scaled Jacobian
  // below `mean_floor` while x's is above it, nor the mean inverse mean ratio above
  // `imr_ceiling` (repair_imr_ceiling).
  void repair_worst(Result& run, double mean_floor,
                    double imr_ceiling = std::numeric_limits<double>::infinity());
  // How far the repair may raise a surface's mean inverse mean ratio: by kRepairImrSpend of
  // what x gained over the input, and not at all where x gained nothing (+∞ for a volume mesh,
  // whose promise is on the mean scaled Jacobian alone).
  double repair_imr_ceiling(const Smoothing& s) const;
  // No cell stays below the input's worst (run.quality_before) or `ceiling`, whichever is
  // lower: vertices are pulled back toward `input`, x where the call started
  // (quality_guard.hpp). Fills run.quality_guard.
  void guard_worst(Vec input, Result& run, double ceiling = 1.0);
  // Smoothing's promise on the mean scaled Jacobian, after guard_worst(): where x's mean is
  // below the input's by more than QualityGuardResult::kMeanSlack, x becomes the input again
  // (its worst cells repaired unless switched off, the mean kept within the slack). Judged
  // after the worst cells' phases, not before: they lift the optimum's mean back within the
  // slack on some meshes (FEAT3's flowbench_c3d_00_hexa_48: 0.825 instead of the input's
  // 0.591). On a surface, likewise where x's mean inverse mean ratio is above the input's (the
  // repair then makes no move that raises it). Fills the mean's part of run.quality_guard.
  void guard_mean(const Smoothing& s, Result& run);
  // Moves the mesh to x and sets result's quality_after and boundary change; throws
  // Error if a cell is inverted (the energy is infinite there, so the method cannot produce
  // one: a promise kept for every output).
  void finish(Result& result);
  // Q = actual / desired volume at x.
  VolumeRatioStats volume_ratio() const;
  // Adaptation's targets (build_targets) at the x the Picard iteration passes, desired volumes
  // summing to mesh_volume. A metric's target shapes are turned by the cells' Jacobians where
  // the adaptation starts (at x now), which stay fixed: taken from the moving cells, the targets
  // would turn with them, and cells that shear away from the surface (a star of flat cells
  // around a circle) would be their own fixed point. Keeps a reference to `field`.
  TargetsAt adaptation_targets(const SizeField& field, const SizeFieldOptions& field_options) const;
  // The free coordinates, the boundary's classification and the linear solvers.
  ProblemSummary problem_summary(const SolverOptions& solver) const;
  // The solver options with what derives from the mesh.
  QuasiNewtonOptions method(const SolverOptions& solver) const;
  // Volume of each local cell at the mesh's coordinates (where a call starts).
  std::vector<double> cell_volumes() const;
  // Longest over shortest edge of each local cell at the mesh's coordinates.
  std::vector<double> cell_edge_ratios() const;
  std::vector<double> cell_scaled_jacobians() const;
  // Whether y holds the mesh's coordinates bit for bit on every rank (no vertex moved onto a
  // chart or boundary): the quality before then measured y's cells. Collective.
  bool at_mesh_coordinates(Vec y) const;
  // Keeps the volumes and edge ratios of the mesh's quality (computed by input_quality) for
  // cell_volumes() and cell_edge_ratios() while the mesh's coordinates stay: one pass over the
  // cells for the quality before and the targets instead of three.
  void keep_input_cells();
  // How each vertex may move in the worst-cell repair: as it does in the optimization, except
  // that the vertices of cells keeping their input cell stay.
  RepairFreedom repair_freedom() const;

  Mesh& mesh;
  double started = 0.0;      // MPI_Wtime() at the call's start: its time, and the time limit
  OwnedVec x;                // set by start()
  double mesh_volume = 0.0;  // of the mesh when the functional was built
  std::optional<EnergyOptions> energy;
  std::optional<BoundaryOptions> boundary_options;
  std::unique_ptr<Boundary> boundary;
  Problem problem;
  std::unique_ptr<Functional> functional;  // of `problem`
  std::vector<double> input_share;  // per local cell: the share of its input cell its target keeps
  struct InputCells {
    std::uint64_t coordinates_version;  // of the mesh, when they were kept
    std::vector<double> volumes, edge_ratios, scaled_jacobians;
  };
  std::optional<InputCells> input_cells;  // set by keep_input_cells()
  // input_cells if the mesh's coordinates are still those they were kept at, else null.
  const InputCells* current_input_cells() const;
  OwnedVec cell_size;  // local cell size per dof, for the practical criterion
  bool warm = false;   // an adapt() ran: the next one starts from its volumes
  // The last smooth()'s minimization, for a warm start of the next one on the same problem
  // (same energy, boundary and targets options; the connectivity is the Mesh's, fixed): the α
  // it ended with. Reset by anything else that sets up a problem.
  struct SmoothingEnd {
    double alpha;
    TargetMode targets;
    SizeMode sizes;
  };
  std::optional<SmoothingEnd> smoothed;
  std::unique_ptr<LevelSetFunction> phi;  // of the last fit; its constraint refers to it
  std::optional<FitResult> fitted;        // the last fit, until the next call
};

}  // namespace neomesh
