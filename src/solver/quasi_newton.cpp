#include "solver/quasi_newton.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <mpi.h>

namespace neomesh {

namespace {

// Bisections for the blend of a rejected δ̃ with −s: θ to 2^-50, far below what matters.
constexpr int kBlendBisections = 50;

// α heuristic of thesis §5.1: g(t) = 0.15 + 6.51657 / (3.66657 + e^(1.38629 t)), through
// (0, 1.5464), (1, 1), (2, 0.4814): α grows while the defect falls fast.
double alpha_factor(double defect_ratio) {
  return 0.15 + 6.51657 / (3.66657 + std::exp(1.38629 * defect_ratio));
}

double dot(Vec a, Vec b) {
  double r = 0.0;
  NM_PETSC(VecDot(a, b, &r));
  return r;
}
// CG stopped at negative curvature with an iterate (H(α) is not positive definite there).
bool truncated_at_negative_curvature(const LinearSolver::Outcome& out) {
  return !out.converged && out.indefinite && out.iterations > 0;
}

double norm(Vec a) {
  double r = 0.0;
  NM_PETSC(VecNorm(a, NORM_2, &r));
  return r;
}

class Stopwatch {
 public:
  explicit Stopwatch(double& total) : total_(total), start_(MPI_Wtime()) {}
  ~Stopwatch() { total_ += MPI_Wtime() - start_; }

 private:
  double& total_;
  double start_;
};

}  // namespace

std::string describe(StopReason reason) {
  switch (reason) {
    case StopReason::DefectAbsolute:
      return "Newton defect below the absolute tolerance";
    case StopReason::DefectRelative:
      return "Newton defect below the relative tolerance";
    case StopReason::Practical:
      return "practical criterion: energy and vertex positions stopped changing";
    case StopReason::MaxIterations:
      return "maximum number of iterations reached";
    case StopReason::LineSearchFailed:
      return "line search failed: no step along the direction decreases the energy";
    case StopReason::TimeLimit:
      return "time limit reached: the mesh is the best one so far";
    case StopReason::OnBarrier:
      return "on the barrier: steps towards the energy's minimum leave the certified-valid cells";
  }
  return "?";
}

bool past_deadline(double deadline, MPI_Comm comm) {
  if (!std::isfinite(deadline)) return false;
  int past = MPI_Wtime() > deadline;  // the first rank's clock decides, for all
  MPI_Bcast(&past, 1, MPI_INT, 0, comm);
  return past != 0;
}

double energy_roundoff(const EnergyOptions& energy, int dim, double mesh_volume) {
  return 1e-15 * (energy.lambda + energy.mu) * dim * mesh_volume;
}

std::optional<ComponentOperators> riesz_components(const Functional& functional,
                                                   const SolverOptions& options) {
  if (options.linear_solver != LinearSolverKind::Amg || functional.slides()) return {};
  return functional.laplacian_is_scalar() ? ComponentOperators::Shared : ComponentOperators::Own;
}

struct QuasiNewton::Impl {
  const Functional* functional;  // of the problem being minimized (restart may change it)
  std::shared_ptr<const Constraints> constraints;  // the matrices' pattern is theirs
  QuasiNewtonOptions options;
  Vec cell_size;
  LinearSolver hessian_solver;
  LinearSolver riesz_solver;
  OwnedMat hessian, laplacian;
  // `trial`: the line search's trial point; outside the line search, scratch space.
  OwnedVec gradient, s, delta_tilde, trial;
  // δ, the direction taken: δ̃ itself, a blend of δ̃ and −s, or −s, in δ̃'s storage (δ̃ is not
  // needed once the direction is chosen; s is kept for a blend that fails).
  Vec delta = nullptr;

  double energy = 0.0;
  double defect = 0.0;
  double initial_defect = -1.0;
  double previous_defect = 0.0;
  double alpha = 0.0;
  // α is the automatic α₀ = 1 and no δ̃ solve has shown yet whether H(1) is positive definite.
  bool alpha_unproven = false;
  int k = 0;
  int antigradient_left = 0;
  int hessian_pc_iterations = 0;  // δ̃ iterations right after the H preconditioner was built
  int last_delta_iterations = 0;
  bool laplacian_fresh = false;  // L was assembled at the current x
  // restart() asked for L at the current x; the next step assembles it (x has not moved).
  bool laplacian_pending = false;
  std::optional<StopReason> stop;
  int barrier_cuts = 0;  // iterations in a row whose step the barrier cut
  // F and the defect at the start of the solve and after each step since, for the stall's half
  // of the practical criterion; a restart begins them anew (F may be another problem's).
  double start_energy = 0.0;
  std::vector<double> energies, defects;
  PhaseTimes times;
  double start_time = MPI_Wtime();

  Impl(const Functional& f, const QuasiNewtonOptions& o, Vec size)
      : functional(&f),
        constraints(f.problem().constraints),
        options(o),
        cell_size(size),
        hessian_solver(f.dofs().comm(), o.linear_solver, "hess_", f.dofs().dim(), o.hessian_rtol),
        riesz_solver(f.dofs().comm(), o.linear_solver, "riesz_", f.dofs().dim(), o.riesz_rtol),
        previous_defect(o.advanced.initial_previous_defect),
        alpha(o.advanced.alpha0 ? *o.advanced.alpha0
                                : o.warm_alpha.value_or(o.initial_alpha(f.slides()))),
        alpha_unproven(!o.advanced.alpha0 && alpha > SolverOptions::Advanced::kThesisAlpha0) {
    Stopwatch watch(times.setup);
    if (const auto kind = riesz_components(*functional, options))
      riesz_solver.precondition_per_component(*kind);
    if (laplacian_preconditions_hessian()) hessian_solver.precondition_with(riesz_solver);
    for (OwnedVec* v : {&gradient, &s, &delta_tilde, &trial})
      *v = functional->dofs().create_global_vector();
    delta = delta_tilde;
  }

  // H and L, and L's preconditioner, only once a step is taken: a mesh that is already a
  // minimizer needs none (their set-up was most of the run on a uniform 100x100 box). H only
  // once a quasi-Newton step is: after L's set-up, whose memory it may then reuse.
  void create_hessian() {
    if (hessian) return;
    Stopwatch watch(times.setup);
    hessian = functional->create_matrix(laplacian_preconditions_hessian() ? HessianUse::Products
                                                                          : HessianUse::Entries);
  }

  OwnedMat create_laplacian() const {
    return riesz_components(*functional, options) == ComponentOperators::Shared
               ? functional->create_scalar_laplacian_matrix()
               : functional->create_laplacian_matrix();
  }

  void evaluate_gradient(Vec x) {
    Stopwatch watch(times.gradient);
    energy = functional->value_and_gradient(x, gradient);
    if (!std::isfinite(energy))
      fail("the mesh has an inverted or degenerate cell: its energy is not finite");
    defect = norm(gradient);
  }

  void assemble_laplacian(Vec x) {
    if (!laplacian) {
      Stopwatch watch(times.setup);
      laplacian = create_laplacian();
    }
    Stopwatch watch(times.riesz_setup);
    functional->assemble_laplacian(options.advanced.riesz, x, laplacian);
    riesz_solver.set_operator(laplacian, false);
    // The solver multiplies with its own copy of L: keeping L would hold it twice, and freed
    // now, before the hierarchies are built, its memory serves them. It is made again when it
    // is assembled again, except where that is every iteration.
    if (riesz_solver.copies_operator() && options.advanced.riesz != RieszLaplacian::CurrentMesh)
      laplacian.reset();
    riesz_solver.setup();
    laplacian_fresh = true;
    laplacian_pending = false;
  }

  // Vertices that slide on a curved boundary turn their tangent spaces as they move, and L
  // restricted to those spaces changes with them (with a stale L the antigradient steps of a
  // 3:1-bunched ring needed 5-7 halvings and the angle test rejected most δ̃). The interior,
  // and so the preconditioner, barely changes: it is kept, except for a direct solver.
  void update_laplacian_tangents(Vec x) {
    Stopwatch watch(times.riesz_setup);
    if (!laplacian) laplacian = create_laplacian();
    functional->assemble_laplacian(options.advanced.riesz, x, laplacian);
    riesz_solver.set_operator(laplacian, options.linear_solver != LinearSolverKind::Direct);
  }

  bool laplacian_preconditions_hessian() const {
    return options.linear_solver == LinearSolverKind::Amg &&
           options.advanced.hessian_pc == HessianPreconditioner::Laplacian;
  }

  // The δ̃ solve's residual bound over ‖g‖ (SolverOptions::Advanced::hessian_forcing_max).
  double forcing() const {
    const double low = options.advanced.hessian_defect_factor;
    const double progress = initial_defect > 0.0 ? defect / initial_defect : 0.0;
    return std::clamp(progress, low, std::max(low, options.advanced.hessian_forcing_max));
  }

  // (u, v)_L = uᵀ L v
  double inner_L(Vec u, Vec v) {
    riesz_solver.multiply(v, trial);
    return dot(u, trial);
  }

  // Assembles H(α) at x and solves H(α) δ̃ = −g loosely (thesis §5.2).
  LinearSolver::Outcome solve_delta(Vec x, IterationRecord& rec) {
    {
      create_hessian();
      Stopwatch watch(times.hessian_assembly);
      functional->assemble_hessian(x, alpha, hessian);
    }
    // With L's hierarchy (a shell PC) there is nothing of H(α) to build or keep.
    const bool own_pc = !laplacian_preconditions_hessian();
    const bool reuse =
        own_pc && options.linear_solver == LinearSolverKind::Amg && hessian_pc_iterations > 0 &&
        last_delta_iterations <= options.advanced.hessian_pc_reuse * hessian_pc_iterations;
    rec.hessian_pc_built = rec.hessian_pc_built || (own_pc && !reuse);
    {
      Stopwatch watch(times.hessian_setup);
      hessian_solver.set_operator(hessian, reuse);
      if (own_pc && !reuse) hessian_solver.setup();
    }
    LinearSolver::Outcome out;
    {
      Stopwatch watch(times.hessian_solve);
      // H(α) δ̃ = −g as H(α) (−δ̃) = g: CG from zero is odd in its right-hand side, bit for bit,
      // and g needs no negated copy.
      out = hessian_solver.solve(gradient, delta_tilde, forcing() * defect);
      NM_PETSC(VecScale(delta_tilde, -1.0));
    }
    rec.krylov_delta += out.iterations;
    last_delta_iterations = out.iterations;
    if (!reuse) hessian_pc_iterations = std::max(1, out.iterations);
    if (!out.converged) hessian_pc_iterations = 0;  // rebuild next time
    return out;
  }

  // Solves for δ̃ and applies the angle test; returns true if δ̃, or its blend with −s, is the
  // direction to take (then in `delta`).
  bool quasi_newton_direction(Vec x, IterationRecord& rec) {
    LinearSolver::Outcome out = solve_delta(x, rec);
    // α₀ = 1 (SolverOptions::initial_alpha) bets that H(1) is positive definite once the
    // quasi-Newton steps start, as it is on every generated mesh of the benchmarks. Where the
    // first δ̃ solve meets negative curvature it is not, and the run goes on from the thesis'
    // α₀ and its growth rule, this solve repeated: square-midpoint 4096², still far from its
    // minimum after the antigradient steps, took 12 iterations, 4 of them truncated, and 417 s
    // with α₀ = 1 throughout, and takes 8 iterations and 267 s so (docs/benchmarks.md).
    if (alpha_unproven && truncated_at_negative_curvature(out)) {
      alpha = SolverOptions::Advanced::kThesisAlpha0;
      rec.alpha = alpha;
      out = solve_delta(x, rec);
    }
    alpha_unproven = false;
    rec.delta_solved = true;
    rec.residual_delta = out.residual;
    // Negative curvature after that: H(α) is not positive definite here. Like Newton-CG
    // methods, keep CG's last iterate (it decreases the quadratic model) and let the angle
    // test judge it; α is not cut, because a direct solve of the same system would not have
    // failed (and cut, shashkov_quad took 6–10 s instead of 3).
    rec.delta_truncated = truncated_at_negative_curvature(out);
    if (!out.converged && !rec.delta_truncated) {
      rec.delta_failed = true;
      return false;
    }
    // η_k = −(s, δ̃)_L / (‖s‖_L ‖δ̃‖_L)
    const double delta_delta = inner_L(delta_tilde, delta_tilde);
    if (!rec.s_solved && estimated_angle_passes(rec, delta_delta)) return true;
    solve_riesz(rec);
    const double s_delta = inner_L(s, delta_tilde);
    const double s_s = inner_L(s, s);
    rec.eta = -s_delta / std::sqrt(s_s * delta_delta);
    if (rec.eta >= options.advanced.eta) return true;
    if (options.advanced.rejected_direction != RejectedDirection::Blend || rec.delta_truncated ||
        !(rec.eta > 0))
      return false;
    blend_towards_antigradient(rec, std::sqrt(delta_delta / s_s));
    return true;
  }

  // The angle test without s (SolverOptions::Advanced::lazy_riesz): (s, δ̃)_L = gᵀδ̃ because L s = g,
  // and ‖s‖²_L = gᵀL⁻¹g ≈ gᵀM⁻¹g with M⁻¹ one V-cycle of L's hierarchy. If the V-cycle
  // reduces the error's L-norm by ρ ≤ 1/2, gᵀM⁻¹g is within a factor 1 ± ρ of gᵀL⁻¹g, so the
  // estimate η̂ is at most 1/√(1 − ρ) ≤ √2 times η_k: η̂ ≥ √2 η passes the test for certain.
  // Closer to the bound, s is solved and the test made as the thesis makes it. Not where
  // vertices slide: L follows their tangent spaces but keeps its first hierarchy
  // (update_laplacian_tangents), and on the sliding annuli gᵀM⁻¹g was then down to a quarter
  // of gᵀL⁻¹g; with a hierarchy built for L it was within 10% on every mesh measured.
  // estimates_angle(): whether quasi-Newton steps try the estimate before solving for s.
  bool estimates_angle() const {
    return options.advanced.lazy_riesz && options.linear_solver == LinearSolverKind::Amg &&
           !functional->slides();
  }
  bool estimated_angle_passes(IterationRecord& rec, double delta_delta) {
    double g_m_g = 0.0;
    {
      Stopwatch watch(times.riesz_solve);
      riesz_solver.apply_preconditioner(gradient, trial);  // M⁻¹g
      g_m_g = dot(gradient, trial);
    }
    if (!(g_m_g > 0.0) || !(delta_delta > 0.0)) return false;
    const double estimate = -dot(gradient, delta_tilde) / std::sqrt(g_m_g * delta_delta);
    if (estimate < std::sqrt(2.0) * options.advanced.eta) return false;
    rec.eta = std::min(estimate, 1.0);  // a cosine; above 1 the V-cycle underestimated ‖s‖_L
    return true;
  }

  // s: L s = g to riesz_rtol, once per iteration.
  void solve_riesz(IterationRecord& rec) {
    if (rec.s_solved) return;
    Stopwatch watch(times.riesz_solve);
    const auto out = riesz_solver.solve(gradient, s);
    if (!out.converged)
      fail(
          "solver.linear_solver: the Riesz-representative solve (L s = g) did not converge in "
          "{} iterations; the direct solver may help",
          out.iterations);
    rec.krylov_s = out.iterations;
    rec.s_solved = true;
  }

  // δ̃ (solved to tolerance) points downhill but failed the angle test, 0 < η_k < η. With the
  // L-unit vectors u = δ̃/‖δ̃‖_L and v = −s/‖s‖_L, δ = ‖δ̃‖_L ((1 − θ) u + θ v) with the smallest θ
  // whose cosine with −s is η (docs/method.md §4): a full step is still about Newton's length.
  void blend_towards_antigradient(IterationRecord& rec, double delta_over_s) {
    const double c = rec.eta;          // cosine between δ̃ and −s in the L inner product
    auto cosine = [c](double theta) {  // of the mix of unit vectors with −s
      const double mixed_norm_sq =
          (1 - theta) * (1 - theta) + theta * theta + 2 * theta * (1 - theta) * c;
      return ((1 - theta) * c + theta) / std::sqrt(mixed_norm_sq);
    };
    double below = 0.0, above = 1.0;  // the cosine grows with θ from c to 1: bisect
    for (int i = 0; i < kBlendBisections; ++i) {
      const double mid = 0.5 * (below + above);
      (cosine(mid) >= options.advanced.eta ? above : below) = mid;
    }
    NM_PETSC(VecAXPBY(delta, -above * delta_over_s, 1.0 - above, s));  // δ̃'s storage
    rec.eta = cosine(above);
    rec.blended = true;
  }

  void use_antigradient(IterationRecord& rec) {
    solve_riesz(rec);
    NM_PETSC(VecAXPBY(delta, -1.0, 0.0, s));
    rec.used_s = true;
    if (!rec.delta_solved || rec.delta_failed) rec.eta = 1.0;
  }

  // Armijo backtracking: the largest σ = 0.5^j with F(x + σδ) finite and
  // F(x) − F(x + σδ) ≥ β σ (−gᵀδ), where x + σδ has its sliding vertices projected back onto
  // the boundary (to first order in σ the same point). Leaves the accepted point in `trial`.
  bool line_search(Vec x, IterationRecord& rec, double& new_energy, double& sigma) {
    Stopwatch watch(times.line_search);
    const double predicted = -dot(gradient, delta);
    int halvings = 0;
    // Only −s has no natural length (L's scale); a (quasi-)Newton step's σ = 1 is its own.
    if (rec.used_s && options.advanced.max_trial_move > 0.0) {
      const double move = max_relative_move(1.0);
      while (halvings < options.advanced.max_halvings &&
             std::ldexp(move, -halvings) > options.advanced.max_trial_move)
        ++halvings;
    }
    sigma = std::ldexp(1.0, -halvings);
    for (; halvings <= options.advanced.max_halvings; ++halvings, sigma *= 0.5) {
      NM_PETSC(VecWAXPY(trial, sigma, delta, x));
      functional->project_onto_boundary(trial);  // sliding vertices back onto the boundary
      new_energy = functional->value(trial);
      ++rec.trials;
      rec.armijo_steps = halvings;
      if (!std::isfinite(new_energy)) continue;
      // Below round-off the test compares noise (docs/method.md §4): take the step.
      const bool roundoff = sigma * predicted <= options.energy_roundoff;
      if (!roundoff && energy - new_energy < options.advanced.armijo_beta * sigma * predicted)
        continue;
      // The barrier last: it costs more than F (a certificate per cell).
      if (options.admissible && !options.admissible(trial)) {
        ++rec.inadmissible_trials;
        continue;
      }
      rec.roundoff_step = roundoff;
      return true;
    }
    return false;
  }

  // The largest move σ δ of a vertex coordinate over its cell size; overwrites `trial`.
  double max_relative_move(double sigma) {
    NM_PETSC(VecPointwiseDivide(trial, delta, cell_size));
    double m = 0.0;
    NM_PETSC(VecNorm(trial, NORM_INFINITY, &m));
    return std::abs(sigma) * m;
  }

  // The defect stalled (it fell by less than half over the window: no Newton convergence, the
  // kinks of a discrete surface block it) and the window's steps gained a negligible part of
  // the fall of F since the start. `defects` holds each step's starting defect.
  bool settled() const {
    const auto w = static_cast<std::size_t>(options.settle_window);
    const double rtol = options.settle_rtol_for(constraints->view.surface);
    if (rtol <= 0 || energies.size() <= w) return false;
    const std::size_t last = energies.size() - 1;
    const double window_gain = energies[last - w] - energies[last];
    const double total_gain = start_energy - energies[last];
    return defect > 0.5 * defects[last - w + 1] && total_gain > 0 &&
           window_gain < rtol * total_gain;
  }

  std::optional<StopReason> defect_stop() const {
    if (defect <= options.defect_atol) return StopReason::DefectAbsolute;
    if (defect <= options.defect_rtol * initial_defect) return StopReason::DefectRelative;
    if (k >= options.max_iterations) return StopReason::MaxIterations;
    if (past_deadline(options.deadline, functional->dofs().comm())) return StopReason::TimeLimit;
    return std::nullopt;
  }

  IterationRecord step(Vec x) {
    IterationRecord rec;
    rec.k = ++k;
    rec.defect = defect;
    rec.alpha = alpha;
    // A surface's cells are seen in their frames where the step starts (docs/method.md, "Surface
    // cells"): F and its gradient here are those of the frames the step keeps.
    if (functional->refresh_frames(x)) {
      evaluate_gradient(x);
      rec.defect = defect;
    }

    if (options.advanced.riesz == RieszLaplacian::CurrentMesh || laplacian_pending)
      assemble_laplacian(x);
    else if (functional->slides() && !laplacian_fresh)
      update_laplacian_tangents(x);
    laplacian_fresh = false;
    const bool antigradient_step = antigradient_left > 0;
    if (antigradient_step || !estimates_angle()) solve_riesz(rec);
    const bool take_delta = !antigradient_step && quasi_newton_direction(x, rec);
    if (!take_delta) use_antigradient(rec);
    rec.direction_norm = norm(delta);

    double new_energy = energy, sigma = 0.0;
    bool decreased = line_search(x, rec, new_energy, sigma);
    if (!decreased && rec.blended) {
      // A blend can fail where −s, the thesis' choice, does not (a sliding vertex crossing a
      // corner of a discrete boundary, say): go along −s instead.
      rec.blended = false;
      use_antigradient(rec);
      rec.direction_norm = norm(delta);
      decreased = line_search(x, rec, new_energy, sigma);
    }
    barrier_cuts = rec.inadmissible_trials > 0 ? barrier_cuts + 1 : 0;
    if (!decreased) {
      stop = rec.inadmissible_trials > 0 ? StopReason::OnBarrier : StopReason::LineSearchFailed;
      rec.energy = energy;
      rec.seconds = MPI_Wtime() - start_time;
      return rec;
    }
    NM_PETSC(VecCopy(trial, x));
    rec.max_move = max_relative_move(sigma);  // over `trial`, now copied
    const double old_energy = energy;
    evaluate_gradient(x);
    rec.energy = energy;

    // α for the next iteration (docs/method.md §4, "α indexing").
    if (antigradient_left > 0) --antigradient_left;
    if (rec.delta_failed)
      alpha = 0.1 * alpha;
    else if (antigradient_left == 0)
      alpha = std::min(1.0, alpha * alpha_factor(rec.defect / previous_defect));
    previous_defect = rec.defect;

    const double energy_change =
        std::abs(old_energy - energy) / std::max(std::abs(old_energy), 1e-300);
    // Near the minimum a full Newton step estimates the distance to it, and the step after it
    // would move the vertices by about its square (docs/method.md §6).
    const bool full_newton_step = rec.delta_solved && !rec.used_s && !rec.blended &&
                                  !rec.delta_truncated && rec.armijo_steps == 0 && rec.alpha >= 1.0;
    energies.push_back(energy);
    defects.push_back(rec.defect);
    // A step the barrier cut short moves little because of the barrier, not because the minimum
    // is near: it does not count as the energy and vertices settling.
    if (options.practical && rec.inadmissible_trials == 0 &&
        ((energy_change < options.energy_rtol && rec.max_move < options.move_rtol) ||
         (full_newton_step && rec.max_move < options.newton_move_rtol) || settled()))
      stop = StopReason::Practical;
    if (barrier_cuts >= kBarrierIterations) stop = StopReason::OnBarrier;
    rec.seconds = MPI_Wtime() - start_time;
    return rec;
  }
};

QuasiNewton::QuasiNewton(const Functional& functional, const QuasiNewtonOptions& options,
                         Vec cell_size)
    : impl_(std::make_unique<Impl>(functional, options, cell_size)) {}
QuasiNewton::~QuasiNewton() = default;

void QuasiNewton::restart(Vec x) {
  restart(x, *impl_->functional);
}

void QuasiNewton::restart(Vec x, const Functional& functional) {
  // The Functional of the last start may be gone: only its constraints, held here, count.
  if (functional.problem().constraints != impl_->constraints)
    fail("internal error: a quasi-Newton restart on other constraints");
  impl_->functional = &functional;
  impl_->evaluate_gradient(x);
  impl_->start_energy = impl_->energy;
  impl_->energies.clear();
  impl_->defects.clear();
  if (impl_->initial_defect < 0) {
    impl_->initial_defect = impl_->defect;
    // Warm, the first α update has no defect before to compare with: α stays where it was
    // (against the thesis' start value 10, a defect of 33 took α from 1 to 0.21 on the annulus
    // triangles, and the Newton regime took 6 more iterations to come back).
    if (impl_->options.warm_alpha) impl_->previous_defect = impl_->defect;
  }
  impl_->laplacian_pending = true;
  // Warm, x is near the minimum already: antigradient steps would only lose Newton's pace.
  impl_->antigradient_left = impl_->options.warm_alpha ? 0 : impl_->options.advanced.kmin;
  impl_->stop.reset();
  impl_->barrier_cuts = 0;
}

std::optional<StopReason> QuasiNewton::stop_reason() const {
  if (impl_->stop) return impl_->stop;
  return impl_->defect_stop();
}

IterationRecord QuasiNewton::step(Vec x) {
  return impl_->step(x);
}
double QuasiNewton::energy() const {
  return impl_->energy;
}
double QuasiNewton::defect() const {
  return impl_->defect;
}
const PhaseTimes& QuasiNewton::times() const {
  return impl_->times;
}

SolverRun minimize(const Functional& functional, Vec x, const QuasiNewtonOptions& options,
                   Vec cell_size, const std::function<void(const IterationRecord&)>& observe) {
  QuasiNewton method(functional, options, cell_size);
  method.restart(x);
  SolverRun result;
  result.initial_energy = method.energy();
  result.initial_defect = method.defect();
  while (!method.stop_reason()) {
    result.history.push_back(method.step(x));
    if (observe) observe(result.history.back());
  }
  result.reason = *method.stop_reason();
  result.final_energy = method.energy();
  result.final_defect = method.defect();
  result.times = method.times();
  return result;
}

OwnedVec local_cell_size(const MeshView& view, const DofMap& dofs,
                         std::span<const double> desired_volumes) {
  const int d = view.dim;
  const double power = 1.0 / view.cell_dim();        // a surface cell's size from its area
  std::vector<double> size(desired_volumes.size());  // on every thread; the sums below in order
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < size.size(); ++c) size[c] = std::pow(desired_volumes[c], power);
  std::vector<double> size_sum(view.coords.size(), 0.0), count(view.coords.size(), 0.0);
  for (const CellBlock& block : view.blocks) {
    const int nv = block.nodes();
    for (PetscInt c = 0; c < block.size(); ++c) {
      const double h = size[block.first_cell + c];
      for (int i = 0; i < nv; ++i)
        for (int j = 0; j < d; ++j) {
          size_sum[block.cell(c)[i] * d + j] += h;
          count[block.cell(c)[i] * d + j] += 1.0;
        }
    }
  }
  OwnedVec sum = dofs.create_global_vector(), n = dofs.create_global_vector();
  dofs.add_local_to_global(size_sum, sum);
  dofs.add_local_to_global(count, n);
  NM_PETSC(VecPointwiseDivide(sum, sum, n));
  return sum;
}

}  // namespace neomesh
