// The quasi-Newton method of thesis §5.1 (docs/method.md §4): the Riesz representative s of the
// gradient, a quasi-Newton direction δ̃ from H(α) δ̃ = −g accepted by the angle test,
// Armijo backtracking that rejects non-finite energies, k_min initial antigradient steps
// and the α heuristic; stopping on the Newton defect or on a practical criterion.
//
// smooth runs it to the end (minimize); adapt drives it step by step and calls restart()
// after changing the desired volumes.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "energy/functional.hpp"
#include "solver/linear_solver.hpp"

namespace neomesh {

// What preconditions the δ̃ solve with --linear-solver amg: the Riesz solve's AMG hierarchy
// of L = B3/μ, which is built anyway and changes only with the desired volumes, or a
// hierarchy of H(α) itself, rebuilt when it has gone stale. H(α) = B1 + α B2 + μ L is
// spectrally close to μ L: CG needs more iterations with L's hierarchy, but its V-cycles are
// cheaper (L is block-diagonal) and no hierarchy of H is built or stored (square-midpoint
// 1024²: 37 instead of 30 CG iterations, δ̃ setup + solve 31.6 → 8.8 s, peak RSS 3.8 → 2.2
// GiB; in 3D and in adaptation about equal or better).
enum class HessianPreconditioner { Hessian, Laplacian };

struct QuasiNewtonOptions {
  double alpha0 = 0.3;  // initial α of H(α) = B1 + α B2 + B3
  double eta = 0.6;     // angle test: accept δ̃ if η_k ≥ η
  int kmin = 2;         // initial antigradient steps (thesis §5.5 recommends 2)
  int max_iterations = 200;
  double defect_atol = 1e-10;  // stop when ‖g‖ ≤ defect_atol
  double defect_rtol = 1e-10;  // ... or ‖g‖ ≤ defect_rtol · ‖g_0‖
  // Practical criterion (docs/method.md §6): stop when the relative energy decrease is below
  // energy_rtol and no vertex moved more than move_rtol times its local cell size.
  bool practical = true;
  double energy_rtol = 1e-9;
  double move_rtol = 1e-6;
  double armijo_beta = 1e-2;  // sufficient decrease (thesis (2.5.4))
  int max_halvings = 40;      // σ ≥ 0.5^40 ≈ 1e-12, then give up
  // ‖g_{-1}‖ for the first α update; 10 reproduces the thesis' tables (docs/method.md §4).
  double initial_previous_defect = 10.0;
  LinearSolverKind linear_solver = LinearSolverKind::Amg;
  double hessian_rtol = 1e-4;           // loose δ̃ solve: 4 digits ...
  double hessian_defect_factor = 1e-3;  // ... or residual ≤ 1e-3 ‖g‖ (thesis §5.2)
  // s only steers: it is the antigradient direction of the first k_min steps and enters the
  // angle test's cosine, so three digits do (same Newton iterations on every case measured,
  // half the Krylov iterations of 1e-8; docs/benchmarks.md). The thesis solves to 1e-8.
  double riesz_rtol = 1e-3;
  static constexpr double kThesisRieszRtol = 1e-8;
  // With amg and hessian_pc = Hessian: keep the AMG hierarchy of an earlier H(α) while the δ̃ solve
  // needs at most this many times the Krylov iterations it needed when the hierarchy was built
  // (H(α) changes little between iterations, its setup costs about ten V-cycles); 0: rebuild
  // always. 2 kept a hierarchy that needed 9-11 iterations where a fresh one needs 4 (square
  // 1024²).
  double hessian_pc_reuse = 1.5;
  HessianPreconditioner hessian_pc = HessianPreconditioner::Laplacian;
  RieszLaplacian riesz = RieszLaplacian::OptimalCells;
  // Absolute round-off level of F (docs/method.md §4): when the predicted decrease σ·(−gᵀδ) is
  // below it, the Armijo test is decided by noise, so the step is taken as it is. About
  // 1e-15 (λ+μ) d |Ω|; see energy_roundoff().
  double energy_roundoff = 0.0;
};

// 1e-15 (λ + μ) d |Ω|: the round-off level of F for a mesh of volume |Ω| in `dim` dimensions.
double energy_roundoff(const EnergyOptions& energy, int dim, double mesh_volume);

// One row of the thesis' iteration table (Tables 5.9 ff.).
struct IterationRecord {
  int k = 0;                    // 1-based, as the thesis prints it
  int armijo_steps = 0;         // halvings: σ = 0.5^armijo_steps
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
  bool used_s = false;            // the step went along −s
  bool roundoff_step = false;     // Armijo skipped: predicted decrease below round-off
  double max_move = 0.0;          // largest vertex move / local cell size
  double seconds = 0.0;           // wall time since start
  // Untangling (solver/untangle.hpp) sets these; 0 and −1 in the Neo-Hookean phase.
  int untangling_round = 0;  // ≥ 1: the round (value of ε) this iteration belongs to
  double epsilon = 0.0;      // ε of the untangling energy
  PetscInt inverted = -1;    // cells inverted after the step
};

enum class StopReason {
  DefectAbsolute,  // ‖g‖ ≤ defect_atol
  DefectRelative,  // ‖g‖ ≤ defect_rtol ‖g_0‖
  Practical,       // energy and vertices stopped changing
  MaxIterations,
  LineSearchFailed,  // no step size in max_halvings halvings gave a finite, decreasing F
};
std::string describe(StopReason reason);

// Wall time per phase, seconds. setup: matrix patterns; *_setup: preconditioner (AMG
// hierarchy or factorization) of H(α) and of L, the latter including L's assembly.
struct PhaseTimes {
  double setup = 0, gradient = 0, hessian_assembly = 0, hessian_setup = 0, hessian_solve = 0,
         riesz_setup = 0, riesz_solve = 0, line_search = 0;
};

struct QuasiNewtonResult {
  std::vector<IterationRecord> history;
  StopReason reason = StopReason::MaxIterations;
  double initial_energy = 0.0;
  double final_energy = 0.0;
  double initial_defect = 0.0;
  double final_defect = 0.0;
  PhaseTimes times;
};

class QuasiNewton {
 public:
  // `cell_size`: local cell size per dof (global Vec laid out like x), for the practical
  // criterion; see local_cell_size().
  QuasiNewton(const Functional& functional, const QuasiNewtonOptions& options, Vec cell_size);
  ~QuasiNewton();

  // Starts at x (or restarts after the desired volumes changed): evaluates F and g, builds
  // the Riesz Laplacian and restarts the k_min antigradient steps. α keeps its value.
  void restart(Vec x);
  // The stop reason at the current iterate, if any (defect tests; after a step also the
  // practical criterion and line-search failure).
  std::optional<StopReason> stop_reason() const;
  // One iteration; x is updated in place.
  IterationRecord step(Vec x);

  double energy() const;
  double defect() const;
  const PhaseTimes& times() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Runs QuasiNewton from x until a stop reason; `observe` sees every iteration.
QuasiNewtonResult minimize(const Functional& functional, Vec x, const QuasiNewtonOptions& options,
                           Vec cell_size,
                           const std::function<void(const IterationRecord&)>& observe = {});

// Mean size v^(1/d) of the cells around each vertex, as a global Vec laid out by `dofs`
// (the same value for the vertex's d dofs).
OwnedVec local_cell_size(const MeshView& view, const DofMap& dofs,
                         std::span<const double> desired_volumes);

}  // namespace neomesh
