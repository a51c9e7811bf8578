// What an optimization reports: one record per quasi-Newton iteration (the rows of the thesis'
// iteration tables, handed to an Observer as they happen), why it stopped, and the whole run.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <neomesh/quality.hpp>

namespace neomesh {

// One row of the thesis' iteration table (Tables 5.9 ff.).
struct IterationRecord {
  int k = 0;             // 1-based, as the thesis prints it
  int armijo_steps = 0;  // halvings: σ = 0.5^armijo_steps
  int trials = 0;  // energies the line search evaluated (SolverOptions::Advanced::max_trial_move)
  // Trials the barrier of a curved mesh rejected: a cell certified valid where the run started
  // was no longer certified valid there (docs/method.md §12).
  int inadmissible_trials = 0;
  double defect = 0.0;          // ‖g_k‖ over free dofs at the start of the iteration
  double direction_norm = 0.0;  // ‖δ‖ before scaling by σ
  double energy = 0.0;          // F after the step
  double eta = 1.0;             // η_k of the angle test (1 for antigradient steps)
  double alpha = 0.0;           // α used in this iteration
  int krylov_delta = 0;         // Krylov iterations for δ̃ (0: not solved)
  double residual_delta = 0.0;
  bool delta_solved = false;
  bool delta_failed = false;      // the δ̃ solve did not converge (α is then cut to 0.1 α)
  bool delta_truncated = false;   // CG stopped at negative curvature; its iterate was used
  bool hessian_pc_built = false;  // amg: the H(α) hierarchy was built for this solve
  int krylov_s = 0;               // Krylov iterations for s
  bool s_solved = false;          // s was solved (SolverOptions::Advanced::lazy_riesz: not always)
  bool used_s = false;            // the step went along −s
  bool blended = false;           // δ̃ failed the angle test and was turned towards −s
  bool roundoff_step = false;     // Armijo skipped: predicted decrease below round-off
  double max_move = 0.0;          // largest vertex move / local cell size
  double seconds = 0.0;           // wall time since start
  // Untangling (docs/untangling.md) sets these; 0 and −1 in the Neo-Hookean phase.
  int untangling_round = 0;    // ≥ 1: the round (value of ε) this iteration belongs to
  double epsilon = 0.0;        // ε of the untangling energy
  std::int64_t inverted = -1;  // cells inverted after the step
  // The untangling energy lifting nearly flat corners after the optimum (the worst-cell phase):
  // `inverted` then counts cells with det G below kLiftedDet at a corner, none of them inverted.
  bool lifting_flat_corners = false;
};

enum class StopReason {
  DefectAbsolute,  // ‖g‖ ≤ defect_atol
  DefectRelative,  // ‖g‖ ≤ defect_rtol ‖g_0‖
  Practical,       // energy and vertices stopped changing
  MaxIterations,
  LineSearchFailed,  // no step size in max_halvings halvings gave a finite, decreasing F
  TimeLimit,         // SolverOptions::time_limit ran out
  OnBarrier,         // curved cells: the certificate cut the steps; the energy's minimum lies
                     // beyond the certified-valid meshes
};
// "Newton defect below the absolute tolerance", ...
std::string describe(StopReason reason);

// Wall time per phase, seconds. setup: matrix patterns; *_setup: preconditioner (AMG
// hierarchy or factorization) of H(α) and of L, the latter including L's assembly.
struct PhaseTimes {
  double setup = 0, gradient = 0, hessian_assembly = 0, hessian_setup = 0, hessian_solve = 0,
         riesz_setup = 0, riesz_solve = 0, line_search = 0;
};

// What sliding found on the whole boundary (docs/boundary.md).
struct BoundarySummary {
  std::int64_t corners = 0, ridge_vertices = 0, surface_vertices = 0;
  int patches = 0, ridges = 0;
  // Per patch: "part 'hole': circle ...", "unnamed: the input's boundary", ...
  std::vector<std::string> patch_geometry;
  // Boundary vertices of parts with a FEAT3 chart that were off it and moved onto it before
  // the first step, and the largest such move.
  std::int64_t moved_onto_charts = 0;
  double max_move_onto_charts = 0.0;
};

// The problem an optimization solves, once it is set up.
// The target cells of smoothing (TargetMode): how many cells keep all of their input cell, part
// of it, or none (the ideal cell).
struct TargetSummary {
  // "ideal", "input" or "smoothed"; for adaptation "metric" (a metric field's cells) or empty
  // (ideal cells)
  std::string mode;
  std::int64_t input = 0, blended = 0, ideal = 0;
  // The input has inverted cells: the targets are ideal whatever was asked (its cells around
  // the inverted ones are no design to keep).
  bool ideal_because_tangled = false;
  // Uniform sizes were asked with the smoothed targets: the targets are ideal, because a cell's
  // design is its sizes (a layer's height is its size across the wall) and the sizes asked for
  // replace it.
  bool ideal_because_sizes = false;
  // How many times the input's cells cover its domain (1: nothing folded; see
  // `uniform_because_folded`).
  double coverage = 1.0;
  // The input is folded over itself throughout (coverage above 2): the desired volumes are
  // uniform whatever --sizes asked (its cell volumes are no sizes).
  bool uniform_because_folded = false;
};

struct ProblemSummary {
  std::int64_t free_coordinates = 0;  // over all processes
  BoundarySummary boundary;           // empty with fixed boundary vertices
  double alpha0 = 0.0;                // the initial α the method starts with
  // The linear solvers of the δ̃ and Riesz solves as PETSc will run them, after the options
  // database's -hess_* and -riesz_* options: "KSP cg, PC hypre boomeramg, rtol 0.0001, ...".
  std::string hessian_solver, riesz_solver;
  TargetSummary targets;
};

// Untangling before smoothing (docs/untangling.md).
struct UntanglingSummary {
  std::int64_t inverted_before = 0, inverted_after = 0;
  double min_det_before = 0.0, min_det_after = 0.0;  // smallest det G at a sample point
  std::vector<IterationRecord> history;              // its iterations (rows with a round)
  int rounds = 0;
  double seconds = 0.0;
  // Untangling with the boundary sliding stalled, so the input's boundary was kept fixed while
  // untangling (and then slides in the smoothing).
  bool boundary_fixed = false;
  // ... and towards equal cell volumes, which untangled where the desired ones stalled.
  bool equal_volumes = false;
};

// The quality guard of smoothing: vertices pulled back toward the input so that no cell is
// worse than the input's worst.
struct QualityGuardResult {
  double input_min = 0.0;   // the threshold: the input's minimum scaled Jacobian (adapt: ≤ 0.2)
  double min_before = 0.0;  // ... of the optimized mesh before the guard
  double min_after = 0.0;   // ... after it (≥ input_min)
  std::int64_t vertices_moved = 0;  // vertices the guard pulled back (global count)
  int rounds = 0;
  // Always false: the guard falls back to the input, which meets its threshold (the report
  // keeps the field).
  bool gave_up = false;
  // The mean scaled Jacobian, the other figure users read: of the input (its vertices placed on
  // their charts), and of the optimized mesh after the worst cells' guard. Where the optimum's
  // mean is below the input's by more than kMeanSlack (a mesh its author optimized by another
  // measure), the input is returned instead (its worst cells repaired with
  // SmoothOptions::repair_worst_cells, within kMeanSlack of the input's mean).
  double input_mean = 0.0;
  double mean_optimum = 0.0;
  // Of a surface mesh, likewise its mean inverse mean ratio (the shapes alone, which the
  // cells' sizes do not sway): where the optimum's is above the input's, the input is returned
  // too, its worst cells repaired by moves that do not raise it. Unset for other meshes.
  std::optional<double> input_mean_inverse_mean_ratio, mean_inverse_mean_ratio_optimum;
  bool input_returned = false;
  static constexpr double kMeanSlack = 0.005;
};

// Smoothing a mesh of second-order cells (docs/method.md §12, "The solver"): every node moves,
// with the curved cells' energy. The worst cells' phases of straight meshes (corner lift,
// worst-cell repair, the guards by the straight scaled Jacobian) are not run; the validity
// certificate and the curved scaled Jacobian (§11) judge the optimum instead.
struct CurvedSmoothingSummary {
  std::int64_t cells = 0;  // curved cells
  std::int64_t nodes = 0;  // their nodes: corners, edge, face and centre nodes
  // The least curved scaled Jacobian (CurvedQualitySummary) of the input and of the optimum.
  double min_scaled_jacobian_before = 0.0, min_scaled_jacobian_optimum = 0.0;
  std::int64_t not_valid_optimum = 0;  // cells of the optimum the certificate did not find valid
  // The optimum had a cell not certified valid, or a worse worst cell than the input: the input
  // is returned instead.
  bool input_returned = false;
};

// Smoothing's worst-cell phase (docs/method.md, "Corners"): the optimum of the thesis' energy
// left a corner of a Q1 cell, wedge or pyramid nearly flat, so smoothing went on with the
// corners sampled too.
struct CornerPhaseSummary {
  double min_scaled_jacobian_before = 0.0;  // of those cells, at the thesis' optimum
  double min_scaled_jacobian_after = 0.0;
  int iterations = 0;
  bool gave_up = false;  // lifting stalled with a cell inverted: the optimum was kept
};

// Smoothing once more, towards ideal cells (docs/method.md, "Corners"): the cells kept from the
// input ask for a corner the mesh cannot open (the corner phase gave up), or keep a cell
// flattened across its edges (Mesquite's shashkov_quad and shashkov, grids sheared by an ALE
// step). The run from the input with ideal targets is kept where its worst cell is better.
struct IdealRetrySummary {
  double min_scaled_jacobian_kept = 0.0;   // where the run with the smoothed targets ended
  double min_scaled_jacobian_ideal = 0.0;  // where the run towards ideal cells ended
  int iterations = 0;                      // of the run towards ideal cells
  bool ideal_kept = false;
};

// The local repair of the worst cells after the optimization (docs/method.md, "Worst cells"):
// interior vertices of the worst cells moved to raise the worst scaled Jacobian around them.
struct WorstCellRepairSummary {
  double min_scaled_jacobian_before = 0.0;  // of the whole mesh
  double min_scaled_jacobian_after = 0.0;
  std::int64_t vertices_moved = 0;  // distinct vertices
  int sweeps = 0;
};

// Fitting to the zero set of a level set (Optimizer::adapt with a LevelSet, docs/adaptivity.md).
struct FitSummary {
  std::string level_set;  // φ's expression
  std::int64_t facets = 0, vertices = 0;
  double max_distance = 0.0;   // of an interface vertex from φ = 0 (|φ| / |∇φ|)
  int stages = 0;              // steps of lowering the vertices' levels to zero
  int undone = 0;              // steps undone because a cell would have inverted
  int cells_moved_across = 0;  // by the interface's clean-up
  int iterations = 0;          // the fit's, the last ones of Result::history
};

// The quasi-Newton iterations and how they ended: what the solver reports of one minimization,
// and the first part of a Result.
struct SolverRun {
  std::vector<IterationRecord> history;  // the iterations on the Neo-Hookean energy
  StopReason reason = StopReason::MaxIterations;
  double initial_energy = 0.0, final_energy = 0.0;
  double initial_defect = 0.0, final_defect = 0.0;
  PhaseTimes times;
};

struct Result : SolverRun {
  QualitySummary quality_before, quality_after;
  ProblemSummary problem;  // what was optimized
  // How the domain changed: the largest distance of a boundary vertex from the boundary where
  // the call started (0 with fixed boundary vertices; with sliding ones bounded by the
  // input's discretization), and the relative change of its volume.
  double boundary_distance = 0.0, volume_change = 0.0;
  std::optional<UntanglingSummary> untangling;              // smooth, if cells were inverted
  std::optional<CornerPhaseSummary> corner_phase;           // smooth, if a corner had flattened
  std::optional<IdealRetrySummary> ideal_retry;             // smooth, if kept cells stayed flat
  std::optional<WorstCellRepairSummary> worst_cell_repair;  // unless the guard is off
  std::optional<QualityGuardResult> quality_guard;          // smooth, unless switched off
  std::optional<CurvedSmoothingSummary> curved;             // smooth, a mesh of curved cells
  std::vector<int> update_iterations;  // adapt: iterations after which volumes were updated
  VolumeRatioStats volume_ratio;       // adapt: Q = actual / desired volume at the end
  std::optional<FitSummary> fit;       // adapt with a LevelSet
  double seconds = 0.0;
};

// What the Optimizer tells while it runs; every member may be empty.
struct Observer {
  // The problem is set up; the first iteration assembles the matrices and builds the
  // preconditioners (on a large mesh the longest wait before the first iteration).
  std::function<void(const ProblemSummary&)> started;
  // Smoothing: this many cells are inverted and are untangled first ...
  std::function<void(std::int64_t inverted)> untangling;
  // ... and this is how it went (then the Neo-Hookean iterations follow).
  std::function<void(const UntanglingSummary&)> untangled;
  std::function<void(const IterationRecord&)> iteration;
  // Adaptation: after iteration k the desired volumes were updated for the `update`-th time.
  std::function<void(int k, int update)> volumes_updated;
  // Adaptation with a LevelSet: adapted; now the mesh is fitted to φ = 0 (φ's expression).
  std::function<void(const std::string& level_set)> fitting;
};

}  // namespace neomesh
