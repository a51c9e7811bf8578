// The quasi-Newton method of thesis §5.1 (docs/method.md §4): the Riesz representative s of the
// gradient, a quasi-Newton direction δ̃ from H(α) δ̃ = −g accepted by the angle test,
// Armijo backtracking that rejects non-finite energies, k_min initial antigradient steps
// and the α heuristic; stopping on the Newton defect or on a practical criterion.
//
// smooth runs it to the end (minimize); adapt drives it step by step and restarts it on the
// Functional of each new set of desired volumes.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <neomesh/options.hpp>
#include <neomesh/result.hpp>

#include "energy/functional.hpp"
#include "solver/linear_solver.hpp"

namespace neomesh {

// The method's options and what the Optimizer derives from the mesh for them.
struct QuasiNewtonOptions : SolverOptions {
  // Absolute round-off level of F (docs/method.md §4): when the predicted decrease σ·(−gᵀδ) is
  // below it, the Armijo test is decided by noise, so the step is taken as it is. About
  // 1e-15 (λ+μ) d |Ω|; see energy_roundoff().
  double energy_roundoff = 0.0;
  // MPI_Wtime() after which no step starts (SolverOptions::time_limit from the call's start).
  double deadline = std::numeric_limits<double>::infinity();
  // A warm start (Optimizer: smooth() called again on the same problem, the mesh moved a little):
  // α starts here instead of at initial_alpha() unless advanced.alpha0 is set, and no
  // antigradient steps are taken. Above the thesis' α₀ it is proven as the automatic α₀ = 1 is.
  std::optional<double> warm_alpha;
  // Collective, if set: whether the line search may take a trial point (curved meshes: no cell
  // certified valid where the run started is uncertified there, docs/method.md §12). A trial it
  // refuses is halved as one of non-finite energy is.
  std::function<bool(Vec)> admissible;
};

// Iterations in a row whose step the barrier (QuasiNewtonOptions::admissible) cut, after which
// the method stops on it: the energy's minimum lies beyond it, and the steps only crawl along it.
inline constexpr int kBarrierIterations = 3;

// Whether MPI_Wtime() is past `deadline` (never for +∞), by the first rank's clock. Collective
// unless the deadline is +∞.
bool past_deadline(double deadline, MPI_Comm comm);

// 1e-15 (λ + μ) d |Ω|: the round-off level of F for a mesh of volume |Ω| in `dim` dimensions.
double energy_roundoff(const EnergyOptions& energy, int dim, double mesh_volume);

// How the amg solver's Riesz solve preconditions the components of L, if by component
// (docs/method.md §4): Shared where L is one scalar Laplacian per component
// (Functional::laplacian_is_scalar; L is then MatCreateMAIJ(L₁, d) and one BoomerAMG hierarchy
// of L₁ serves all d components), Own where no vertex slides but components have different
// fixed coordinates (a hierarchy per component); none where vertices slide, whose projectors
// couple the components.
std::optional<ComponentOperators> riesz_components(const Functional& functional,
                                                   const SolverOptions& options);

class QuasiNewton {
 public:
  // `cell_size`: local cell size per dof (global Vec laid out like x), for the practical
  // criterion; see local_cell_size().
  QuasiNewton(const Functional& functional, const QuasiNewtonOptions& options, Vec cell_size);
  ~QuasiNewton();

  // Starts at x: evaluates F and g, builds the Riesz Laplacian and restarts the k_min
  // antigradient steps. α keeps its value.
  void restart(Vec x);
  // The same on a new problem (new desired volumes, a new ε) of the same Constraints, whose
  // pattern the matrices kept share; `functional` must outlive the steps that follow.
  void restart(Vec x, const Functional& functional);
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
SolverRun minimize(const Functional& functional, Vec x, const QuasiNewtonOptions& options,
                   Vec cell_size, const std::function<void(const IterationRecord&)>& observe = {});

// Mean size v^(1/d) of the cells around each vertex, as a global Vec laid out by `dofs`
// (the same value for the vertex's d dofs).
OwnedVec local_cell_size(const MeshView& view, const DofMap& dofs,
                         std::span<const double> desired_volumes);

}  // namespace neomesh
