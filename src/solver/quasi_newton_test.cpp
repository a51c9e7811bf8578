// The chapter-5 cases of the thesis (docs/cases.md) as tests of the quasi-Newton method.
#include "solver/quasi_newton.hpp"

#include <cmath>
#include <functional>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "generate/generate.hpp"
#include "solver/testing/thesis_problem.hpp"

namespace neomesh {
namespace {

std::string e2(double x) {
  return fmt::format("{:.2E}", x);
}
std::string f2(double x) {
  return fmt::format("{:.2f}", x);
}

// Largest distance of a vertex from the uniform n×n grid on [0,1]² (after undoing a rotation).
double distance_to_uniform_grid(const ThesisProblem& p, int n, double degrees = 0.0) {
  const double a = -degrees * M_PI / 180.0;
  VecReadView x(p.x);
  double worst = 0.0;
  for (PetscInt v = 0; v < p.view.num_vertices; ++v) {
    const double px = std::cos(a) * x[2 * v] - std::sin(a) * x[2 * v + 1];
    const double py = std::sin(a) * x[2 * v] + std::cos(a) * x[2 * v + 1];
    worst = std::max({worst, std::abs(px * n - std::round(px * n)) / n,
                      std::abs(py * n - std::round(py * n)) / n});
  }
  return worst;
}

// Thesis Table 5.1, the rows printed while the defect is above 1e-8.
void expect_table_5_1(const SolverRun& r) {
  const std::vector<std::string> defect = {"1.16E+01", "3.12E+00", "7.85E-01", "3.17E-01",
                                           "8.36E-02", "1.15E-02", "3.76E-06"};
  const std::vector<std::string> delta = {"2.11E+00", "4.50E-01", "1.40E-01",
                                          "3.94E-02", "8.06E-03", "8.78E-04"};
  const std::vector<std::string> energy = {"2.18E-01", "1.74E-02", "2.29E-03", "1.48E-04",
                                           "2.64E-06"};
  const std::vector<std::string> eta = {"0.77", "0.96", "1.00", "1.00", "1.00", "1.00"};
  const std::vector<std::string> alpha = {"0.30", "0.27", "0.38", "0.55", "0.74", "1.00"};
  ASSERT_GE(r.history.size(), defect.size());
  for (size_t k = 0; k < defect.size(); ++k) {
    SCOPED_TRACE(fmt::format("iteration {}", k + 1));
    const IterationRecord& rec = r.history[k];
    EXPECT_EQ(e2(rec.defect), defect[k]);
    if (k < delta.size()) {
      EXPECT_EQ(e2(rec.direction_norm), delta[k]);
    }
    if (k < energy.size()) {
      EXPECT_EQ(e2(rec.energy), energy[k]);
    }
    if (k < eta.size()) {
      EXPECT_EQ(f2(rec.eta), eta[k]);
    }
    if (k < alpha.size()) {
      EXPECT_EQ(f2(rec.alpha), alpha[k]);
    }
    EXPECT_EQ(rec.armijo_steps, 0);
    EXPECT_FALSE(rec.used_s);
  }
}

TEST(SquareMidpoint, ReproducesThesisTable51WithDirectSolver) {
  ThesisProblem p(square_midpoint(16));
  const SolverRun r = p.minimize(p.thesis_options());
  expect_table_5_1(r);
  EXPECT_EQ(r.history.size(), 7u) << "defect < 1e-10 after 7 iterations";
  EXPECT_LT(r.final_defect, 1e-10);
  EXPECT_LT(distance_to_uniform_grid(p, 16), 1e-8);
}

TEST(SquareMidpoint, RotatedBy27DegreesGivesTheSameTable) {
  MeshData mesh = square_midpoint(16);
  rotate(mesh, 27.0);
  ThesisProblem p(std::move(mesh));
  const SolverRun r = p.minimize(p.thesis_options());
  expect_table_5_1(r);
  EXPECT_LT(r.final_defect, 1e-10);
  EXPECT_LT(distance_to_uniform_grid(p, 16, 27.0), 1e-8);
}

// Thesis Table 5.6 reports one PCG(Jacobi) iteration per δ̃, each gaining four digits;
// no textbook Jacobi-CG does that (FEAT3 must count or measure differently), so this checks
// what the loose rule promises: the same Newton iterations ±1, every δ̃ solve stopped at
// ‖r‖ ≤ 1e-3 ‖g‖, and far cheaper than the tight Riesz solve.
TEST(SquareMidpoint, JacobiPcgWithLooseRuleKeepsTheNewtonIterations) {
  ThesisProblem p(square_midpoint(16));
  QuasiNewtonOptions o = p.thesis_options();
  o.linear_solver = LinearSolverKind::Jacobi;
  const SolverRun r = p.minimize(o);
  EXPECT_LT(r.final_defect, 1e-10);
  EXPECT_NEAR(static_cast<double>(r.history.size()), 7.0, 1.0);
  for (const auto& rec : r.history) {
    ASSERT_TRUE(rec.delta_solved);
    EXPECT_LE(rec.residual_delta, 1e-3 * rec.defect * (1 + 1e-12));
    EXPECT_LT(rec.krylov_delta, rec.krylov_s);
    EXPECT_FALSE(rec.used_s);
  }
}

// Thesis Tables 5.9-5.12 vary k_min at 1024²; at 128² (thesis level 6) neomesh needs
// 8, 7 and 9 iterations for k_min = 0, 2, 4.
TEST(SquareMidpoint, ConvergesForEveryKminAt128x128) {
  for (int kmin : {0, 2, 4}) {
    SCOPED_TRACE(fmt::format("kmin {}", kmin));
    ThesisProblem p(square_midpoint(128));
    QuasiNewtonOptions o = p.thesis_options();
    o.advanced.kmin = kmin;
    o.linear_solver = LinearSolverKind::Amg;
    const SolverRun r = p.minimize(o);
    EXPECT_LT(r.final_defect, 1e-10);
    EXPECT_LE(r.history.size(), 12u);
    for (int k = 0; k < kmin; ++k) EXPECT_TRUE(r.history[k].used_s);
    RecordProperty(fmt::format("iterations_kmin_{}", kmin), static_cast<int>(r.history.size()));
  }
}

TEST(SquareMidpoint, DoesNotStallOnRoundOffAt64x64) {
  ThesisProblem p(square_midpoint(64));
  QuasiNewtonOptions o = p.thesis_options();
  o.linear_solver = LinearSolverKind::Amg;
  const SolverRun r = p.minimize(o);
  EXPECT_EQ(r.reason, StopReason::DefectAbsolute);
  EXPECT_LT(r.final_defect, 1e-10);
  EXPECT_LT(r.history.size(), 20u);
}

// --hess-pc laplacian: CG on H(α) preconditioned by the Riesz solve's AMG hierarchy of L.
// Same grid, iterations within one of the H(α) hierarchy's, and no hierarchy of H built.
TEST(SquareMidpoint, LaplacianPreconditionerReachesTheGrid) {
  std::vector<std::size_t> iterations;
  for (auto pc : {HessianPreconditioner::Hessian, HessianPreconditioner::Laplacian}) {
    ThesisProblem p(square_midpoint(64));
    QuasiNewtonOptions o = p.thesis_options();
    o.linear_solver = LinearSolverKind::Amg;
    o.advanced.hessian_pc = pc;
    const SolverRun r = p.minimize(o);
    EXPECT_LT(r.final_defect, 1e-10);
    EXPECT_LT(distance_to_uniform_grid(p, 64), 1e-8);
    for (const IterationRecord& rec : r.history) {
      SCOPED_TRACE(fmt::format("k {}", rec.k));
      if (pc == HessianPreconditioner::Laplacian) {
        EXPECT_FALSE(rec.hessian_pc_built);
      }
      if (rec.delta_solved && !rec.delta_truncated) {
        EXPECT_LE(rec.residual_delta, 1e-3 * rec.defect * (1 + 1e-12));
      }
    }
    iterations.push_back(r.history.size());
  }
  EXPECT_LE(iterations[1], iterations[0] + 1);
}

TEST(CubeMidpoint, ReproducesThesisTable518) {
  ThesisProblem p(cube_midpoint(16));
  const SolverRun r = p.minimize(p.thesis_options());
  const std::vector<std::string> defect = {"1.77E+00", "6.31E-01", "2.19E-01",
                                           "5.02E-02", "4.12E-03", "5.98E-07"};
  const std::vector<std::string> alpha = {"0.30", "0.44", "0.61", "0.84", "1.00"};
  ASSERT_GE(r.history.size(), defect.size());
  for (size_t k = 0; k < defect.size(); ++k) {
    SCOPED_TRACE(fmt::format("iteration {}", k + 1));
    EXPECT_EQ(e2(r.history[k].defect), defect[k]);
    if (k < alpha.size()) {
      EXPECT_EQ(f2(r.history[k].alpha), alpha[k]);
    }
    EXPECT_EQ(r.history[k].armijo_steps, 0);
  }
  EXPECT_EQ(r.history.size(), 6u);
}

TEST(SquareRandom, ConvergesToTheUniformGrid) {
  ThesisProblem p(square_random(16, 0.2, 1));
  QuasiNewtonOptions o = p.thesis_options();
  o.advanced.kmin = 2;  // thesis Table 5.13
  const SolverRun r = p.minimize(o);
  EXPECT_LT(r.final_defect, 1e-10);
  EXPECT_LE(r.history.size(), 12u);
  EXPECT_LT(distance_to_uniform_grid(p, 16), 1e-8);
}

// The practical criterion (docs/method.md §6) stops where the mesh has stopped changing: on a
// jittered grid the run that stops on it ends within 1e-6 cell widths of the grid that the
// run to defect 1e-10 reaches, and its last step is either a full Newton step (α = 1, δ̃ as
// solved, σ = 1) that moved no vertex more than 1e-3 of its cell size, or a step below the
// energy and move thresholds. Without its Newton half the run takes at least one more step.
TEST(SquareRandom, PracticalCriterionStopsWhereTheMeshStoppedChanging) {
  const int n = 32;
  QuasiNewtonOptions base;
  base.linear_solver = LinearSolverKind::Amg;

  std::vector<SolverRun> runs;
  for (const double newton_move : {1e-3, 0.0}) {
    ThesisProblem p(square_random(n, 0.2, 1));
    QuasiNewtonOptions o = base;
    o.newton_move_rtol = newton_move;
    runs.push_back(p.minimize(o));
    const SolverRun& r = runs.back();
    SCOPED_TRACE(fmt::format("newton_move_rtol {}", newton_move));
    EXPECT_LT(distance_to_uniform_grid(p, n), 1e-6 / n);
    if (newton_move == 0) continue;  // it may reach the defect tolerance first
    ASSERT_EQ(r.reason, StopReason::Practical);
    const IterationRecord& last = r.history.back();
    const bool full_newton_step = last.delta_solved && !last.used_s && !last.blended &&
                                  !last.delta_truncated && last.armijo_steps == 0 &&
                                  last.alpha == 1.0;
    if (last.max_move >= o.move_rtol) {
      EXPECT_TRUE(full_newton_step);
      EXPECT_LT(last.max_move, newton_move);
    } else {
      EXPECT_LT(last.max_move, o.move_rtol);
    }
  }
  EXPECT_LT(runs[0].history.size(), runs[1].history.size());
}

// Minimizes on the jittered 32² grid with AMG and `configure`'s options: the practical
// criterion stops the run within 1e-6 cell widths of the grid.
SolverRun reach_the_grid(const std::function<void(QuasiNewtonOptions&)>& configure) {
  const int n = 32;
  ThesisProblem p(square_random(n, 0.2, 1));
  QuasiNewtonOptions o;
  o.linear_solver = LinearSolverKind::Amg;
  configure(o);
  SolverRun r = p.minimize(o);
  EXPECT_EQ(r.reason, StopReason::Practical);
  EXPECT_LT(distance_to_uniform_grid(p, n), 1e-6 / n);
  return r;
}

// The δ̃ solve loosened far from the minimum (SolverOptions::Advanced::hessian_forcing_max): the
// same quasi-Newton iterations to the same mesh (within 1e-6 cell widths, as the practical
// criterion promises), with fewer Krylov iterations than the thesis' fixed tolerance.
TEST(SquareRandom, LooserQuasiNewtonSolvesFarFromTheMinimumSaveKrylovIterations) {
  std::vector<SolverRun> runs;
  for (const double forcing_max : {0.0, 1e-2}) {
    SCOPED_TRACE(fmt::format("hessian_forcing_max {}", forcing_max));
    runs.push_back(reach_the_grid(
        [&](QuasiNewtonOptions& o) { o.advanced.hessian_forcing_max = forcing_max; }));
  }
  const auto krylov = [](const SolverRun& r) {
    int sum = 0;
    for (const IterationRecord& rec : r.history) sum += rec.krylov_delta;
    return sum;
  };
  EXPECT_EQ(runs[1].history.size(), runs[0].history.size());
  EXPECT_LT(krylov(runs[1]), krylov(runs[0]));
}

// Along −s the line search skips the trial steps that would move a vertex by more than
// max_trial_move cell sizes: the same σ in every iteration, fewer energies evaluated.
TEST(SquareMidpoint, AntigradientTrialStepsBeyondTheMoveBoundAreSkipped) {
  std::vector<SolverRun> runs;
  for (const double bound : {0.0, 64.0}) {
    ThesisProblem p(square_midpoint(64));
    QuasiNewtonOptions o;
    o.linear_solver = LinearSolverKind::Amg;
    o.advanced.max_trial_move = bound;
    runs.push_back(p.minimize(o));
  }
  ASSERT_EQ(runs[1].history.size(), runs[0].history.size());
  int trials[2] = {0, 0};
  for (std::size_t i = 0; i < runs[0].history.size(); ++i) {
    EXPECT_EQ(runs[1].history[i].armijo_steps, runs[0].history[i].armijo_steps) << "k " << i + 1;
    // From σ = 1 every halving is a trial.
    EXPECT_EQ(runs[0].history[i].trials, runs[0].history[i].armijo_steps + 1) << "k " << i + 1;
    for (int r : {0, 1}) trials[r] += runs[r].history[i].trials;
  }
  EXPECT_LT(trials[1], trials[0]);  // 15 and 10 when written
}

// α₀ = 1 bets that H(1) is positive definite once the quasi-Newton steps start. Without the
// antigradient steps (k_min = 0), square-midpoint's first δ̃ solve meets negative curvature at
// α = 1: the run then goes on from the thesis' α₀, the solve repeated, and no δ̃ is truncated.
// An α₀ the caller gave is kept, truncated δ̃ and all.
TEST(SquareMidpoint, NegativeCurvatureInTheFirstSolveFallsBackToTheThesisAlpha0) {
  for (const bool given : {false, true}) {
    SCOPED_TRACE(given ? "alpha0 = 1 given" : "alpha0 automatic");
    ThesisProblem p(square_midpoint(32));
    QuasiNewtonOptions o;
    o.linear_solver = LinearSolverKind::Amg;
    o.advanced.kmin = 0;
    if (given) o.advanced.alpha0 = 1.0;
    const SolverRun r = p.minimize(o);
    ASSERT_GE(r.history.size(), 2u);
    const IterationRecord& first = r.history.front();
    EXPECT_TRUE(first.delta_solved);
    EXPECT_EQ(first.alpha, given ? 1.0 : SolverOptions::Advanced::kThesisAlpha0);
    EXPECT_EQ(first.delta_truncated, given);
    EXPECT_EQ(first.used_s, given);  // the truncated δ̃ fails the angle test here
    // From 0.3, α grows by the thesis' rule; it is never cut again.
    EXPECT_GE(r.history[1].alpha, first.alpha);
    EXPECT_LT(r.final_defect, 1e-5);
  }
}

// SolverOptions::Advanced::lazy_riesz: the quasi-Newton steps take the angle test from one V-cycle
// of L's hierarchy instead of the Riesz solve. The same directions are taken in the same iterations
// to the same grid; the estimated cosine is within 0.03 of the one with s; no quasi-Newton step
// solved s (every η here is far above the √2 η margin); the antigradient steps still do.
TEST(SquareRandom, AngleTestWithoutTheRieszSolveTakesTheSameSteps) {
  std::vector<SolverRun> runs;
  for (const bool lazy : {false, true}) {
    SCOPED_TRACE(fmt::format("lazy_riesz {}", lazy));
    runs.push_back(reach_the_grid([&](QuasiNewtonOptions& o) { o.advanced.lazy_riesz = lazy; }));
  }
  const std::vector<IterationRecord>& every = runs[0].history;
  const std::vector<IterationRecord>& lazy = runs[1].history;
  ASSERT_EQ(lazy.size(), every.size());
  int riesz[2] = {0, 0};
  for (std::size_t i = 0; i < every.size(); ++i) {
    SCOPED_TRACE(fmt::format("k {}", i + 1));
    EXPECT_EQ(lazy[i].used_s, every[i].used_s);
    EXPECT_EQ(lazy[i].blended, every[i].blended);
    EXPECT_EQ(lazy[i].armijo_steps, every[i].armijo_steps);
    EXPECT_TRUE(every[i].s_solved);
    EXPECT_EQ(lazy[i].s_solved, lazy[i].used_s);
    if (!lazy[i].used_s) {
      EXPECT_NEAR(lazy[i].eta, every[i].eta, 0.03);  // 0.951 and 0.946, 0.970 and 0.960
    }
    riesz[0] += every[i].krylov_s;
    riesz[1] += lazy[i].krylov_s;
  }
  EXPECT_LT(riesz[1], riesz[0]);
}

// The cases whose meshes the thesis does not specify fully (generate.hpp documents the
// meshes built here): each converges to defect < 1e-10 without stalling, with k_min = 2.
// Where the mesh turned out to be the thesis' (transition and circle at level 4: 1280
// cells), the final F matches its tables to the printed digits; the curved triangle mesh
// is FEAT3's unit-axe-tria as best we could rebuild it and ends at F 2.8331, not 2.9987.
struct QualitativeCase {
  const char* name;
  MeshData (*mesh)();
  size_t max_iterations;
  const char* thesis_energy = nullptr;  // final F as printed in the thesis, if comparable
};

class ThesisQualitativeCase : public ::testing::TestWithParam<QualitativeCase> {};

TEST_P(ThesisQualitativeCase, ConvergesWithoutStalling) {
  ThesisProblem p(GetParam().mesh());
  QuasiNewtonOptions o = p.thesis_options();
  o.advanced.kmin = 2;
  o.linear_solver = LinearSolverKind::Amg;
  const SolverRun r = p.minimize(o);
  EXPECT_EQ(r.reason, StopReason::DefectAbsolute) << describe(r.reason);
  EXPECT_LT(r.final_defect, 1e-10);
  EXPECT_LE(r.history.size(), GetParam().max_iterations);
  EXPECT_LT(r.final_energy, r.initial_energy);
  if (GetParam().thesis_energy) {
    EXPECT_EQ(fmt::format("{:.4f}", r.final_energy), GetParam().thesis_energy);
  }
  RecordProperty("final_energy", fmt::format("{:.6f}", r.final_energy));
  RecordProperty("iterations", static_cast<int>(r.history.size()));
}

INSTANTIATE_TEST_SUITE_P(
    Chapter5, ThesisQualitativeCase,
    ::testing::Values(QualitativeCase{"transition", [] { return transition(4); }, 12, "3.0730"},
                      QualitativeCase{"circle_quad", [] { return circle_quad(4); }, 12, "6.9492"},
                      QualitativeCase{"triangle_equilateral",
                                      [] { return triangle_equilateral(4, 1); }, 30},
                      QualitativeCase{"triangle_curved", [] { return triangle_curved(3); }, 40}),
    [](const auto& info) { return std::string(info.param.name); });

// The barrier (QuasiNewtonOptions::admissible, curved meshes' certificate): a trial point it
// refuses is halved, and never taken.
TEST(SquareMidpoint, ABarrierThatRefusesEveryPointStopsTheRunWhereItStarted) {
  ThesisProblem p(square_midpoint(8));
  QuasiNewtonOptions o = p.thesis_options();
  o.admissible = [](Vec) { return false; };
  const OwnedVec start = copy_of(p.x);
  const SolverRun r = p.minimize(o);
  EXPECT_EQ(r.reason, StopReason::OnBarrier);
  ASSERT_EQ(r.history.size(), 1u);
  EXPECT_GT(r.history[0].inadmissible_trials, 0);
  EXPECT_EQ(r.final_energy, r.initial_energy);
  NM_PETSC(VecAXPY(start, -1.0, p.x));
  double moved = 0.0;
  NM_PETSC(VecNorm(start, NORM_INFINITY, &moved));
  EXPECT_EQ(moved, 0.0);
}

TEST(SquareMidpoint, ABarrierShortOfTheMinimumIsPressedAgainstAndNeverCrossed) {
  // Admissible: no vertex farther from where it started than half the minimum's farthest (the
  // unbarred run's). The run descends to the barrier, whose cuts then stop it there.
  const auto farthest_from = [](Vec a, Vec b) {
    const OwnedVec d = copy_of(a);
    NM_PETSC(VecAXPY(d, -1.0, b));
    double farthest = 0.0;
    NM_PETSC(VecNorm(d, NORM_INFINITY, &farthest));
    return farthest;
  };
  ThesisProblem free(square_midpoint(8));
  const OwnedVec start = copy_of(free.x);
  free.minimize(free.thesis_options());
  const double reach = 0.5 * farthest_from(free.x, start);

  ThesisProblem p(square_midpoint(8));
  QuasiNewtonOptions o = p.thesis_options();
  int refused = 0;
  o.admissible = [&](Vec trial) {
    const bool inside = farthest_from(trial, start) <= reach;
    refused += !inside;
    return inside;
  };
  const SolverRun r = p.minimize(o);
  int counted = 0;
  for (const IterationRecord& rec : r.history) counted += rec.inadmissible_trials;
  EXPECT_GT(refused, 0);
  EXPECT_EQ(counted, refused);
  EXPECT_EQ(r.reason, StopReason::OnBarrier);
  EXPECT_LT(r.final_energy, r.initial_energy);
  EXPECT_LE(farthest_from(p.x, start), reach);
  EXPECT_GT(farthest_from(p.x, start), 0.9 * reach);  // pressed against it
}

}  // namespace
}  // namespace neomesh
