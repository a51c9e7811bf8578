// `neomesh smooth IN -o OUT`: every cell towards an ideal cell of its desired volume
// (thesis chapter 5), boundary vertices sliding along the boundary (fixed with --thesis).
#include <filesystem>
#include <memory>

#include "app/method_options.hpp"
#include "app/optimization.hpp"
#include "app/subcommand.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "solver/desired_volumes.hpp"
#include "solver/quality_guard.hpp"

namespace neomesh::app {

namespace {

struct SmoothOptions {
  std::string input, output, sizes = "smoothed";
  bool force = false, no_guard = false, no_untangle = false;
  MethodOptions method;
  RunOutputs outputs;
};

// The quality guard (solver/quality_guard.hpp): no cell of the output worse than the input's
// worst. Returns its record for the JSON report; F in `result` is updated if it moved vertices.
nlohmann::json apply_quality_guard(OptimizationRun& run, Vec input, QuasiNewtonResult& result) {
  const QualityGuardResult guard =
      guard_worst_quality(run.view(), run.dofs(), input, run.x(),
                          [&](Vec x) { run.functional().project_onto_boundary(x); });
  if (guard.gave_up)
    say("quality guard: pulling cells back toward the input made the worst cell worse; the "
        "optimized mesh is kept (min scaled Jacobian {:.4f}; input {:.4f})\n",
        guard.min_before, guard.input_min);
  if (guard.vertices_moved > 0) {
    result.final_energy = run.functional().value(run.x());
    say("quality guard: {} vertices pulled back toward the input so that no cell is worse than "
        "the input's worst (min scaled Jacobian {:.4f} -> {:.4f}; input {:.4f})\n",
        guard.vertices_moved, guard.min_before, guard.min_after, guard.input_min);
  }
  return {{"quality_guard",
           {{"input_min_scaled_jacobian", guard.input_min},
            {"min_scaled_jacobian_before", guard.min_before},
            {"min_scaled_jacobian_after", guard.min_after},
            {"vertices_moved", guard.vertices_moved},
            {"gave_up", guard.gave_up},
            {"rounds", guard.rounds}}}};
}

void smooth(SmoothOptions& o) {
  finalize(o.method);
  const SizeMode sizes = parse_size_mode(o.method.thesis ? "uniform" : o.sizes);
  check_output_path(o.input, o.output, o.force);
  // Every output is checked before the run, so that a typo does not cost a long run.
  check_run_outputs(o.outputs);

  OptimizationRun run(o.input, o.method,
                      o.no_untangle ? InvertedCells::Refuse : InvertedCells::Keep);
  check_run_outputs(o.outputs, run.view().dim);  // pictures of a 3D mesh: before the run
  run.set_desired_volumes(desired_volumes(sizes, run.view(), run.dofs(), run.input_volumes()));
  run.print_problem();
  if (!o.outputs.picture_before.empty())
    run.draw(o.outputs.picture_before, o.outputs.picture_field, "input: " + o.input);
  // The guard's promise is about the input: a tangled input's worst cell is inverted, so any
  // untangled output keeps it.
  OwnedVec input;
  NM_PETSC(VecDuplicate(run.x(), input.out()));
  NM_PETSC(VecCopy(run.x(), input));
  nlohmann::json report = run.untangle(o.outputs.progress_lines);
  QuasiNewtonResult result = minimize(run.functional(), run.x(), o.method.solver, run.cell_size(),
                                      run.table_printer(o.outputs.progress_lines));
  if (!(o.no_guard || o.method.thesis)) report.update(apply_quality_guard(run, input, result));
  run.finish(result, o.output, o.outputs, report);
}

}  // namespace

Subcommand add_smooth(CLI::App& app) {
  auto o = std::make_shared<SmoothOptions>();
  // The worst cells of real meshes touch the boundary, and only sliding vertices can fix them
  // (box_with_hole: min scaled Jacobian 0.024 fixed, 0.151 sliding); the boundary stays on the
  // input's facets, corners and group borders stay put (docs/boundary.md).
  o->method.boundary = "slide";
  CLI::App* cmd = app.add_subcommand(
      "smooth",
      "Improve the shape of every cell. Moves the vertices (the connectivity stays; boundary\n"
      "vertices slide along the boundary, corners stay) to minimize the Neo-Hookean energy with\n"
      "the quasi-Newton method of the thesis; prints one row per iteration and the quality\n"
      "before and after. A mesh with inverted cells is untangled first.");
  cmd->add_option("input", o->input, "mesh to smooth (.msh Gmsh 2.2/4.1, .xml FEAT3)")->required();
  cmd->add_option("-o,--output", o->output, "smoothed mesh (.vtu with quality fields, or .msh)")
      ->required();
  cmd->add_flag("--force", o->force, "allow the output to overwrite the input file (default: off)");
  cmd->add_flag("--no-guard", o->no_guard,
                "keep the energy's optimum even where a cell ends up worse than the input's worst "
                "cell (default: off, i.e. such cells' vertices are pulled back; --thesis implies "
                "it)");
  cmd->add_flag("--no-untangle", o->no_untangle,
                "refuse a mesh with inverted cells instead of untangling it first (default: off, "
                "i.e. inverted cells are untangled, then the mesh is smoothed)");
  cmd->add_option("--sizes", o->sizes,
                  "desired cell volumes: smoothed (input volumes averaged over neighbours: keeps "
                  "the grading), input (each cell's own volume) or uniform (all equal, the thesis)")
      ->check(CLI::IsMember({"smoothed", "input", "uniform"}))
      ->capture_default_str();
  add_run_output_options(*cmd, o->outputs, "scaled_jacobian");
  add_method_options(*cmd, o->method);
  return {cmd, [o] { smooth(*o); }};
}

}  // namespace neomesh::app
