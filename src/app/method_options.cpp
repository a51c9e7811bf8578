#include "app/method_options.hpp"

#include <functional>
#include <map>
#include <string_view>
#include <utility>

#include "core/error.hpp"

namespace neomesh::app {

void add_method_options(CLI::App& cmd, MethodOptions& o) {
  const char* energy = "Energy (thesis §4)";
  cmd.add_option("--lambda", o.energy.lambda,
                 "λ > 0: weight of (log det G)², resists volume change")
      ->capture_default_str()
      ->group(energy);
  cmd.add_option("--mu", o.energy.mu, "μ > 0: weight of the shape terms")
      ->capture_default_str()
      ->group(energy);
  cmd.add_option("--kappa", o.energy.kappa,
                 "κ > 0: penalty on cells grown beyond e^(μ/λ+1) × their desired volume "
                 "(default: λ)")
      ->group(energy);
  cmd.add_option("--gauss", o.energy.gauss_points,
                 "Gauss points per direction on quadrilaterals/hexahedra/wedges/pyramids (1-5; "
                 "--thesis: 3)")
      ->capture_default_str()
      ->group(energy);

  const char* method = "Quasi-Newton method (thesis §5.1)";
  cmd.add_option("--alpha0", o.solver.alpha0,
                 "initial α in H(α) = B1 + α B2 + B3, in (0, 1]; auto: 1, or 0.3 where "
                 "vertices slide on a curved or oblique boundary (--thesis: 0.3)")
      ->default_str("auto")
      ->group(method);
  cmd.add_option("--eta", o.solver.eta,
                 "angle test: accept the quasi-Newton direction if η_k ≥ η, η in (0, 1)")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--rejected-direction", o.rejected_direction,
                 "when the quasi-Newton direction fails the angle test: blend (turn it towards "
                 "the antigradient just enough to pass) or antigradient (the thesis)")
      ->check(CLI::IsMember(choice_names<RejectedDirection>()))
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--kmin", o.solver.kmin, "initial antigradient steps before quasi-Newton steps")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--max-iter", o.solver.max_iterations, "maximum number of iterations")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--time-limit", o.solver.time_limit,
                 "end the run after this many seconds with the best mesh so far (0: no limit)")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--tol", o.solver.defect_atol, "stop when the Newton defect ‖g‖ is below this")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--rtol", o.solver.defect_rtol,
                 "stop when the Newton defect fell by this factor from its start")
      ->capture_default_str()
      ->group(method);
  cmd.add_flag("--no-practical", o.no_practical,
               "iterate to the defect tolerance even after the mesh stopped changing (default: "
               "stop on the practical criterion too)")
      ->group(method);
  cmd.add_option("--energy-rtol", o.solver.energy_rtol,
                 "practical criterion: relative energy decrease per iteration below this ...")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--move-rtol", o.solver.move_rtol,
                 "... and no vertex moved more than this times its local cell size")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--newton-move-rtol", o.solver.newton_move_rtol,
                 "practical criterion: or a full Newton step (alpha 1, sigma 1) moved no vertex "
                 "more than this times its local cell size (0: off)")
      ->capture_default_str()
      ->group(method);
  cmd.add_option("--max-trial-move", o.max_trial_move,
                 "line search along the antigradient: the first trial step moves no vertex more "
                 "than this times its local cell size (the halving sequence from 1 is kept; 0: "
                 "start at 1, as with --thesis)")
      ->default_str(fmt::format("{:g}", SolverOptions{}.max_trial_move))
      ->group(method);
  cmd.add_option("--alpha-start-defect", o.solver.initial_previous_defect,
                 "defect assumed before the first iteration for the α update (thesis: 10)")
      ->capture_default_str()
      ->group(method);

  const char* linear = "Linear solvers (PETSc prefixes -hess_ and -riesz_)";
  cmd.add_option("--linear-solver", o.linear_solver,
                 "amg (CG + hypre BoomerAMG), jacobi (the thesis' PCG) or direct (Cholesky, MUMPS)")
      ->check(CLI::IsMember(choice_names<LinearSolverKind>()))
      ->capture_default_str()
      ->group(linear);
  cmd.add_option("--riesz", o.riesz,
                 "Laplacian of the Riesz representative: optimal (over the optimal cells, the "
                 "thesis') or current (stiffness of the current mesh)")
      ->check(CLI::IsMember(choice_names<RieszLaplacian>()))
      ->capture_default_str()
      ->group(linear);
  cmd.add_option("--hess-rtol", o.solver.hessian_rtol,
                 "relative tolerance of the loose quasi-Newton solve")
      ->capture_default_str()
      ->group(linear);
  cmd.add_option("--hess-forcing-max", o.hessian_forcing_max,
                 "far from the minimum the quasi-Newton solve may stop at a residual of up to "
                 "this times the defect, the closer the tighter (0: the thesis' solve throughout, "
                 "as with --thesis)")
      ->default_str(fmt::format("{:g}", SolverOptions{}.hessian_forcing_max))
      ->group(linear);
  cmd.add_option("--hess-pc", o.hess_pc,
                 "amg: precondition the quasi-Newton solve with the Riesz solve's AMG hierarchy "
                 "of the Laplacian (laplacian: more CG iterations, cheaper ones, no hierarchy "
                 "of H(alpha) built or stored) or with a hierarchy of H(alpha) (hessian)")
      ->check(CLI::IsMember(choice_names<HessianPreconditioner>()))
      ->capture_default_str()
      ->group(linear);
  cmd.add_option(
         "--hess-pc-reuse", o.solver.hessian_pc_reuse,
         "--hess-pc hessian: keep the AMG hierarchy of H(alpha) while the solve needs at most this "
         "many times the iterations it needed when built (0: rebuild every iteration)")
      ->capture_default_str()
      ->group(linear);
  cmd.add_option("--riesz-rtol", o.riesz_rtol,
                 fmt::format("relative tolerance of the Riesz solve (default: {:g}, with --thesis "
                             "{:g})",
                             SolverOptions{}.riesz_rtol, SolverOptions::kThesisRieszRtol))
      ->group(linear);
  cmd.add_flag("--riesz-every-step", o.riesz_every_step,
               "solve the Riesz system every iteration (default: in quasi-Newton steps only when "
               "the angle test, estimated with one AMG V-cycle, needs s; always with --thesis)")
      ->group(linear);
  const char* boundary = "Boundary (docs/boundary.md)";
  cmd.add_option("--boundary", o.boundary,
                 "fixed (boundary vertices stay put, the thesis) or slide (they move along the "
                 "input's boundary, curved or flat; corners stay put, ridge vertices slide along "
                 "their ridge)")
      ->check(CLI::IsMember(choice_names<BoundaryMode>()))
      ->capture_default_str()
      ->group(boundary);
  cmd.add_option("--shape", o.shapes,
                 "with --boundary slide: boundary part PART (physical group or FEAT3 mesh part) "
                 "lies exactly on a shape: PART=circle:cx,cy,r | line:px,py,nx,ny | "
                 "sphere:cx,cy,cz,r | plane:px,py,pz,nx,ny,nz | cylinder:px,py,pz,ax,ay,az,r | "
                 "levelset:EXPR (repeatable; default: FEAT3 charts, flat faces, else the input's "
                 "own facets)")
      ->group(boundary);
  cmd.add_option("--feature-angle", o.feature_angle,
                 "with --boundary slide: the boundary has a corner (2D) or ridge (3D) where it "
                 "turns by more than this many degrees; corners stay put, ridge vertices slide "
                 "along the ridge")
      ->capture_default_str()
      ->group(boundary);
  cmd.add_flag("--thesis", o.thesis,
               "the thesis' conventions: uniform desired volumes, fixed boundary vertices, no "
               "practical stopping criterion (iterate to the defect tolerance), Riesz solve to "
               "1e-8, 3 Gauss points per direction, antigradient steps where the angle test "
               "fails; default: off")
      ->group(method);
}

std::string cli_message(const std::string& message) {
  static const std::map<std::string, std::string, std::less<>> kNames = {
      {"energy.lambda", "--lambda"},
      {"energy.mu", "--mu"},
      {"energy.kappa", "--kappa"},
      {"energy.gauss_points", "--gauss"},
      {"solver.alpha0", "--alpha0"},
      {"solver.eta", "--eta"},
      {"solver.kmin", "--kmin"},
      {"solver.max_iterations", "--max-iter"},
      {"solver.time_limit", "--time-limit"},
      {"solver.defect_atol", "--tol"},
      {"solver.defect_rtol", "--rtol"},
      {"solver.energy_rtol", "--energy-rtol"},
      {"solver.move_rtol", "--move-rtol"},
      {"solver.newton_move_rtol", "--newton-move-rtol"},
      {"solver.initial_previous_defect", "--alpha-start-defect"},
      {"solver.max_trial_move", "--max-trial-move"},
      {"solver.hessian_rtol", "--hess-rtol"},
      {"solver.hessian_forcing_max", "--hess-forcing-max"},
      {"solver.hessian_pc_reuse", "--hess-pc-reuse"},
      {"solver.riesz_rtol", "--riesz-rtol"},
      {"boundary.feature_angle", "--feature-angle"},
      {"boundary.shapes", "--shape"},
      {"sizes.power", "--power"},
      {"sizes.floor", "--floor"},
      {"sizes.max_ratio", "--max-ratio"},
      {"sizes.smoothing_passes", "--smooth-sizes"},
      {"picard.min_updates", "--min-updates"},
      {"picard.update_every", "--update-every"},
      {"picard.update_move", "--update-move"},
      {"picard.update_step_norm", "--update-step"},
      {"picard.relaxation", "--relaxation"},
      {"warm_updates", "--step-updates"},
      {"solver.linear_solver", "--linear-solver"},
      {"fit", "--fit"}};
  const std::size_t end = message.find_first_of(" :");
  if (end == std::string::npos) return message;
  const auto it = kNames.find(message.substr(0, end));
  return it != kNames.end() ? it->second + message.substr(end) : message;
}

void resolve(const MethodOptions& o, EnergyOptions& energy, SolverOptions& solver,
             BoundaryOptions& boundary) {
  energy = o.energy;
  solver = o.solver;
  solver.linear_solver = parse_linear_solver(o.linear_solver);
  solver.riesz = parse_riesz_laplacian(o.riesz);
  solver.hessian_pc = parse_hessian_preconditioner(o.hess_pc);
  solver.rejected_direction = parse_rejected_direction(o.rejected_direction);
  solver.practical = !o.no_practical;
  solver.lazy_riesz = !o.riesz_every_step;
  boundary.mode = parse_boundary_mode(o.boundary);
  boundary.feature_angle = o.feature_angle;
  boundary.shapes.clear();
  for (const std::string& shape : o.shapes) {
    const auto equals = shape.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == shape.size())
      fail("--shape '{}': expected PART=SHAPE, e.g. hole=circle:0,0,0.5", shape);
    boundary.shapes.emplace_back(shape.substr(0, equals), shape.substr(equals + 1));
  }
  if (!o.shapes.empty() && (boundary.mode != BoundaryMode::Slide || o.thesis))
    fail("--shape needs --boundary slide (with fixed boundary vertices nothing slides on it)");
}

}  // namespace neomesh::app
