// The options of an optimization, as plain structs: the energy, the boundary, the quasi-Newton
// method and its linear solvers, the desired volumes of smoothing and the size field and
// Picard updates of adaptation. SmoothOptions and AdaptOptions gather them per task, with the
// defaults neomesh recommends, thesis() presets that reproduce the dissertation's tables
// (docs/method.md §9 lists every difference), and validate(), which throws OptionError naming
// the field.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace neomesh {

// The Neo-Hookean energy (docs/method.md §2).
struct EnergyOptions {
  double lambda = 1.0;
  double mu = 10.0;
  double kappa = -1.0;  // < 0 means κ = λ (enough for convexity, thesis §4.3)
  // Gauss points per direction for Q1 cells, wedges and pyramids; 3 reproduces the thesis.
  // SmoothOptions and AdaptOptions use 2 (docs/benchmarks.md: the same optimum and iterations).
  int gauss_points = 3;

  // κ as the energy uses it: λ where kappa < 0.
  double effective_kappa() const { return kappa < 0.0 ? lambda : kappa; }
  void validate() const;
};

// What the boundary vertices may do (docs/boundary.md): stay put (the thesis' H¹₀ setting), or
// slide along the input's boundary, corners and ridges kept.
enum class BoundaryMode { Fixed, Slide };
// Each choice of an option has one name, the command line's and the report's ("fixed",
// "slide"); parse_*() throws Error for another name, choice_names<E>() lists them all (the
// default first). All are defined in one table per enum (src/api/options.cpp).
std::string_view name(BoundaryMode mode);
BoundaryMode parse_boundary_mode(std::string_view name);
template <typename E>
std::vector<std::string> choice_names();

// What the vertices of a surface mesh slide on, where no shape is given for their cells
// (docs/user-guide.md, "Surface meshes"): the input's flat cells, or a Phong tessellation
// through their vertices, flat where it could fold (boundary/discrete_geometry.hpp). A volume
// mesh's boundary vertices slide on its flat facets either way.
enum class SurfaceGeometry { Cells, Phong };
std::string_view name(SurfaceGeometry geometry);  // "cells", "phong"
SurfaceGeometry parse_surface_geometry(std::string_view name);

struct BoundaryOptions {
  BoundaryOptions() = default;
  explicit BoundaryOptions(BoundaryMode m) : mode(m) {}

  BoundaryMode mode = BoundaryMode::Fixed;
  // Corners and ridges: where the boundary turns (2D) or folds (3D) by more than this, in
  // degrees. 40 keeps the facets of a circle or sphere meshed with ≥ 9 edges per right angle
  // in one patch and finds every corner of a box.
  double feature_angle = 40.0;
  // (part name, shape spec) pairs: boundary part `name` lies on the shape, e.g. ("hole",
  // "circle:0,0,0.5"); docs/boundary.md lists the shapes.
  std::vector<std::pair<std::string, std::string>> shapes;
  SurfaceGeometry surface_geometry = SurfaceGeometry::Cells;

  void validate() const;
};

// Which matrix represents the H¹₀ inner product for the Riesz representative (docs/method.md §4).
enum class RieszLaplacian {
  OptimalCells,  // ∫ over the optimal cells = B3/μ; the thesis' choice; built once per volumes
  CurrentMesh,   // stiffness matrix of the current mesh; depends on x
};
std::string_view name(RieszLaplacian kind);  // "optimal", "current"
RieszLaplacian parse_riesz_laplacian(std::string_view name);

// The linear solvers' defaults (PETSc options -hess_* and -riesz_* still win):
//   Amg     CG + hypre BoomerAMG (mesh-independent iteration counts; the default)
//   Jacobi  CG + Jacobi (the thesis' PCG)
//   Direct  Cholesky (MUMPS, works in parallel; the thesis used UMFPACK)
enum class LinearSolverKind { Amg, Jacobi, Direct };
std::string_view name(LinearSolverKind kind);  // "amg", "jacobi", "direct"
LinearSolverKind parse_linear_solver(std::string_view name);

// What preconditions the δ̃ solve with LinearSolverKind::Amg: the Riesz solve's AMG hierarchy
// of L = B3/μ, which is built anyway and changes only with the desired volumes, or a
// hierarchy of H(α) itself, rebuilt when it has gone stale. H(α) = B1 + α B2 + μ L is
// spectrally close to μ L: CG needs more iterations with L's hierarchy, but its V-cycles are
// cheaper (L couples no two components; without sliding vertices it is one scalar hierarchy
// per component) and no hierarchy of H is built or stored (docs/benchmarks.md).
enum class HessianPreconditioner { Hessian, Laplacian };
std::string_view name(HessianPreconditioner kind);  // "hessian", "laplacian"
HessianPreconditioner parse_hessian_preconditioner(std::string_view name);

// What an iteration does when the quasi-Newton direction δ̃ fails the angle test
// (docs/method.md §4):
//   Antigradient  it goes along −s instead (the thesis);
//   Blend         it turns δ̃ towards −s just enough to pass the test, when δ̃ points downhill
//                 and CG did not stop at negative curvature, keeping most of the Newton step
//                 where H(α) and L disagree (fitted interfaces, sliding boundaries); else −s.
enum class RejectedDirection { Antigradient, Blend };
std::string_view name(RejectedDirection direction);  // "antigradient", "blend"
RejectedDirection parse_rejected_direction(std::string_view name);

// The quasi-Newton method of thesis §5.1 (docs/method.md §4).
struct SolverOptions {
  int max_iterations = 200;
  // Wall-clock seconds for a whole smooth() or adapt() call; 0: no limit. When it runs out the
  // call ends with the mesh as it is (every iterate is valid, and better than the last), the
  // stop reason says so; a mesh still tangled then is an error.
  double time_limit = 0.0;
  double defect_atol = 1e-10;  // stop when ‖g‖ ≤ defect_atol
  double defect_rtol = 1e-10;  // ... or ‖g‖ ≤ defect_rtol · ‖g_0‖
  // Practical criterion (docs/method.md §6): stop when the relative energy decrease is below
  // energy_rtol and no vertex moved more than move_rtol times its local cell size.
  bool practical = true;
  double energy_rtol = 1e-9;
  double move_rtol = 1e-6;
  // Practical criterion, Newton's half: also stop after a full Newton step (α = 1, δ̃ taken
  // unchanged, σ = 1) that moved no vertex more than newton_move_rtol times its local cell
  // size; the next step would move them by about the square of that (0: off).
  double newton_move_rtol = 1e-2;
  // Practical criterion, the stall's half: also stop when the Newton defect fell by less than
  // half over the last settle_window iterations and they lowered F by less than settle_rtol
  // times what it fell since the start (0: off). On a surface slid on as its input's cells F
  // has a kink at every edge, and on a closed one a direction it does not see (turning about
  // an axis): the defect stalls and the vertices creep on for hundreds of iterations, each
  // gaining next to nothing (docs/method.md §6). Unset: settle_rtol_for() picks it — on for
  // surface meshes only, since on volume meshes it cut runs whose last iterations still
  // lifted the worst cell (Mesquite's hole_in_square_tanglap: 0.504 → 0.485).
  std::optional<double> settle_rtol = std::nullopt;
  static constexpr double kSurfaceSettleRtol = 1e-2;
  int settle_window = 5;
  LinearSolverKind linear_solver = LinearSolverKind::Amg;
  double hessian_rtol = 1e-4;  // loose δ̃ solve: 4 digits (or Advanced::hessian_defect_factor)
  // s only steers: it is the antigradient direction of the first k_min steps and enters the
  // angle test's cosine, so three digits do (same Newton iterations on every case measured,
  // half the Krylov iterations of 1e-8; docs/benchmarks.md). The thesis solves to 1e-8.
  double riesz_rtol = 1e-3;
  static constexpr double kThesisRieszRtol = 1e-8;

  // The method's research switches: the thesis' parameters and what neomesh changed in its
  // steps, line search and linear solves (docs/method.md §4, §10). The defaults are what
  // docs/benchmarks.md measured best; thesis() sets the thesis' choices.
  struct Advanced {
    // Initial α of H(α) = B1 + α B2 + B3. Unset: initial_alpha() picks it (docs/method.md §4).
    std::optional<double> alpha0 = std::nullopt;
    static constexpr double kThesisAlpha0 = 0.3;
    double eta = 0.6;  // angle test: accept δ̃ if η_k ≥ η
    RejectedDirection rejected_direction = RejectedDirection::Blend;  // the thesis: Antigradient
    int kmin = 2;               // initial antigradient steps (thesis §5.5 recommends 2)
    double armijo_beta = 1e-2;  // sufficient decrease (thesis (2.5.4))
    int max_halvings = 40;      // σ ≥ 0.5^40 ≈ 1e-12, then give up
    // Along −s (antigradient steps), the line search's first trial σ is the largest of 1, 1/2,
    // 1/4, ... that moves no vertex more than this many times its local cell size: larger
    // trials of the same halving sequence are skipped, not tried. −s has L's scale, not the
    // mesh's: the first antigradient steps of square-midpoint 1024² evaluated the energy 12 and
    // 8 times to accept 2⁻¹¹ and 2⁻⁷, now 5 and 1 (docs/method.md §4). A quasi-Newton step's
    // σ = 1 is its natural length and is always tried. 0: start at σ = 1 (the thesis).
    double max_trial_move = 64.0;
    // ‖g_{-1}‖ for the first α update; 10 reproduces the thesis' tables (docs/method.md §4).
    double initial_previous_defect = 10.0;
    double hessian_defect_factor = 1e-3;  // δ̃ solve: or residual ≤ 1e-3 ‖g‖ (thesis §5.2)
    // Far from the minimum the δ̃ solve may stop sooner, at a residual of f ‖g‖ with
    // f = ‖g‖/‖g₀‖ clamped to [hessian_defect_factor, hessian_forcing_max]: the first steps
    // need a direction, not digits, and the last (Newton) steps are solved as in the thesis,
    // so they converge as fast (docs/method.md §4). 0: the thesis' solve throughout.
    double hessian_forcing_max = 1e-2;
    // A quasi-Newton step needs s only for the angle test's cosine η (and a blend): with AMG,
    // η is first estimated without s, from (s, δ̃)_L = gᵀδ̃ and ‖s‖²_L ≈ gᵀM⁻¹g with one
    // application M⁻¹ of L's hierarchy; s is solved only if the estimate does not pass the
    // test with a margin that covers a V-cycle's error (docs/method.md §4). false: s every
    // iteration (the thesis).
    bool lazy_riesz = true;
    // With Amg and hessian_pc = Hessian: keep the AMG hierarchy of an earlier H(α) while the
    // δ̃ solve needs at most this many times the Krylov iterations it needed when the
    // hierarchy was built (0: rebuild always).
    double hessian_pc_reuse = 1.5;
    HessianPreconditioner hessian_pc = HessianPreconditioner::Laplacian;
    RieszLaplacian riesz = RieszLaplacian::OptimalCells;
  };
  Advanced advanced;

  // advanced.alpha0 if set; else 1 (start in the Newton regime) unless some vertex slides on a
  // curved or oblique boundary, where the thesis' 0.3 measured better (docs/benchmarks.md).
  // From the automatic 1 the method falls back to 0.3 if its first δ̃ solve meets negative
  // curvature (docs/method.md §4).
  double initial_alpha(bool slides) const {
    return advanced.alpha0.value_or(slides ? Advanced::kThesisAlpha0 : 1.0);
  }

  double settle_rtol_for(bool surface) const {
    return settle_rtol.value_or(surface ? kSurfaceSettleRtol : 0.0);
  }

  // Throws OptionError ("solver.advanced.eta must be in (0, 1) (got 2)") for a field out of
  // range.
  void validate() const;
};

// Desired cell volumes for smoothing. Real meshes are graded — fine near a cylinder, coarse far
// away — so making every cell the same size would wreck them:
//   Uniform   every cell gets |Ω| / N (the thesis' setting and its test cases)
//   Input     every cell keeps its own input volume
//   Smoothed  the input volumes averaged over neighbouring cells a few times: the grading
//             stays while noise from badly shaped cells is removed (the default)
enum class SizeMode { Uniform, Input, Smoothed };
// "uniform", "input" or "smoothed" (the command line's --sizes); throws Error for another name.
SizeMode parse_size_mode(std::string_view name);
std::string_view name(SizeMode mode);

// The cells smoothing pulls each cell towards (docs/method.md, "Target cells"):
//   Ideal     the thesis' isotropic cell (square, cube, equilateral simplex, ...) of the
//             desired volume (SizeMode)
//   Input     the input cell itself, shape and volume: the input is the energy's minimum, so
//             only untangling and the worst-cell repair move vertices
//   Smoothed  the input's design where a neighbourhood is stretched coherently (boundary
//             layers, graded CAD meshes: kept), ideal cells where the stretching is noise
//             (the default)
enum class TargetMode { Ideal, Input, Smoothed };
// "ideal", "input" or "smoothed" (the command line's --targets); throws Error for another name.
TargetMode parse_target_mode(std::string_view name);
std::string_view name(TargetMode mode);

// How a size field becomes desired volumes (docs/adaptivity.md): v_K = floor + d(c_K)^p, made
// consistent.
struct SizeFieldOptions {
  double floor = 1e-8;  // added to d^p so that no cell asks for volume 0
  double power = 1.0;   // p
  // Largest over smallest desired volume (0: unbounded, the thesis). The smallest volumes
  // are raised to max/ratio, because no mesh of fixed connectivity can shrink a cell on the
  // surface to the 1e-8-fold of its neighbours. 32 (edge lengths 1 : 3.2 in 3D) is what the
  // meshes of docs/adaptivity.md reach with good shapes; 100 squeezed cells to scaled
  // Jacobians of 0.1. Fitting an interface moves the smallest cells once more: there 16 keeps
  // fitted triangles above a scaled Jacobian of 0.3, where 32 left 0.27 (docs/adaptivity.md).
  // Unset: kMaxRatio, or kFitMaxRatio when the mesh is fitted.
  std::optional<double> max_ratio = std::nullopt;
  static constexpr double kMaxRatio = 32.0, kFitMaxRatio = 16.0;
  // Passes of averaging log v over neighbouring cells (0: none, the thesis): limits how fast
  // the desired volume may change from a cell to its neighbour.
  int smoothing_passes = 1;

  // The thesis' field: v = 1e-8 + d, nothing bounded or smoothed.
  static SizeFieldOptions thesis() { return {.max_ratio = 0.0, .smoothing_passes = 0}; }
  double ratio(bool fitted = false) const {
    return max_ratio.value_or(fitted ? kFitMaxRatio : kMaxRatio);
  }
  void validate() const;
};

// The Picard iteration of adaptation (thesis §6, docs/method.md §5): when the desired volumes
// are recomputed from the moving mesh.
struct PicardOptions {
  int min_updates = 6;            // updates before the run may stop (the thesis made 7)
  int update_every = 8;           // iterations after which the volumes are updated anyway
  double update_move = 1e-3;      // update when the step moved no vertex more than this · h
  double update_step_norm = 0.0;  // thesis: update when σ‖δ‖ < this (0: not used)
  // Under-relaxation ω of an update: v ← (1−ω) v_old + ω v(centroids). 1 is the thesis.
  double relaxation = 1.0;

  // The thesis' scheme: full updates when σ‖δ‖ < 1e-6 or every 8 iterations, 7 updates.
  static PicardOptions thesis() {
    return {.min_updates = 7,
            .update_every = 8,
            .update_move = 0.0,
            .update_step_norm = 1e-6,
            .relaxation = 1.0};
  }
  void validate() const;
};

// Optimizer::smooth: every cell towards an ideal cell of its desired volume (thesis chapter 5).
struct SmoothOptions {
  // λ = 1, μ = 10: shape dominates. 2×2(×2) Gauss points: on jittered quads and hexes the
  // same iterations and optimum (mean inverse mean ratio to 1e-6) as 3×3(×3), the energy's
  // terms at a third of the cost in 3D.
  EnergyOptions energy{.gauss_points = 2};
  // The worst cells of real meshes touch the boundary, and only sliding vertices can fix them.
  BoundaryOptions boundary{BoundaryMode::Slide};
  SolverOptions solver;
  SizeMode sizes = SizeMode::Smoothed;
  TargetMode targets = TargetMode::Smoothed;
  // Inverted cells are untangled first (docs/untangling.md); false: they are an error.
  bool untangle = true;
  // The worst cell: a corner left nearly flat by the thesis' optimum is lifted by going on with
  // corner samples (docs/method.md, "Corners"), and no cell of the result is worse than the
  // input's worst (vertices pulled back, solver/quality_guard.hpp). false: the thesis' optimum.
  bool quality_guard = true;
  // With the quality guard: after the optimum, the vertices of the worst cells (boundary ones
  // sliding) are moved one at a time to where the worst cell around them is best
  // (solver/worst_cell_repair.hpp): it lifts what the energy, a sum over cells, leaves behind.
  // A max–min search is discontinuous, so meshes equal up to round-off (a mirrored twin,
  // another number of ranks) may come out visibly different.
  bool repair_worst_cells = true;

  // `base` with the thesis' conventions: uniform desired volumes, fixed boundary vertices, no
  // practical stopping criterion, the Riesz solve to 1e-8, 3×3(×3) Gauss points, no quality
  // guard.
  static SmoothOptions thesis(SmoothOptions base);
  static SmoothOptions thesis() { return thesis(SmoothOptions{}); }
  void validate() const;
};

// Optimizer::adapt: cells crowd where a size field is small (thesis chapter 6).
struct AdaptOptions {
  // Adaptation wants volumes met, not only shapes: λ = 4 μ, and boundary vertices that slide
  // so that the cells at the boundary can grade too (docs/adaptivity.md).
  EnergyOptions energy{.lambda = 4.0, .mu = 1.0, .gauss_points = 2};
  BoundaryOptions boundary{BoundaryMode::Slide};
  SolverOptions solver;
  SizeFieldOptions field;  // how the size field's relative volumes become desired volumes
  PicardOptions picard;
  // A warm start (adapt() after an earlier adapt() on the same Optimizer, e.g. the next time
  // step): Picard updates before it may stop, instead of picard.min_updates.
  int warm_updates = 1;
  // Inverted cells are untangled first, towards the size field's volumes (a geometry that
  // moved through the mesh); false: they are an error.
  bool untangle = true;
  // As SmoothOptions::quality_guard: flat corners lifted, and no cell below the input's worst
  // scaled Jacobian or kGuardCeiling, whichever is lower: grading a mesh changes the shapes of
  // its cells, and against a uniform input (every cell 1) the guard would undo the whole
  // adaptation; 0.2 is below what isotropic adaptation with the default sizes leaves
  // (docs/adaptivity.md: 0.31 quads, 0.26 triangles) and above nearly flat cells. Not with a fit
  // to a level set, whose interface vertices must stay on it; with a metric field, whose cells
  // are stretched on purpose, only flat corners are lifted (the guard measures cells against
  // ideal ones).
  bool quality_guard = true;
  static constexpr double kGuardCeiling = 0.2;

  // `base` with the thesis' scheme (§6.1): the raw field, λ = 1, μ = 10, 3×3(×3) Gauss points,
  // fixed boundary vertices, the thesis' Picard updates and stopping rule, the Riesz solve to
  // 1e-8.
  static AdaptOptions thesis(AdaptOptions base);
  static AdaptOptions thesis() { return thesis(AdaptOptions{}); }
  void validate() const;
};

}  // namespace neomesh
