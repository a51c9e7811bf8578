// `neomesh smooth IN -o OUT`: every cell towards an ideal cell of its desired volume
// (thesis chapter 5), boundary vertices sliding along the boundary (fixed with --thesis).
#include <filesystem>
#include <memory>

#include "app/checks.hpp"
#include "app/method_options.hpp"
#include "app/optimization.hpp"
#include "app/subcommand.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "report/run_report.hpp"

namespace neomesh::app {

namespace {

struct SmoothCommand {
  std::vector<std::string> inputs;  // the mesh, with a FEAT3 mesh's chart files
  std::string output;
  bool force = false;
  TaskOptions<SmoothOptions> options;
  RunOutputs outputs;
};

void smooth(SmoothCommand& o) {
  const SmoothOptions options = o.options.resolve();
  check_output_path(o.inputs, o.output, o.force);
  // Every output is checked before the run, so that a typo does not cost a long run.
  check_run_outputs(o.outputs);

  OptimizationRun run(o.inputs, options.untangle ? InvertedCells::Keep : InvertedCells::Refuse);
  const RunSettings settings{options.energy, options.solver, options.boundary};
  const auto picture_before = [&] {
    if (!o.outputs.picture_before.empty())
      run.draw(o.outputs.picture_before, o.outputs.picture_field,
               "input: " + input_label(o.inputs));
  };
  const Result result = run.optimizer().smooth(
      options, run.observer(settings, o.outputs.progress_lines, picture_before));
  run.finish(result, settings, o.output, o.outputs, smooth_report(options, result));
}

}  // namespace

Subcommand add_smooth(CLI::App& app) {
  auto o = std::make_shared<SmoothCommand>();
  CLI::App* cmd = app.add_subcommand(
      "smooth",
      "Improve the shape of every cell. Moves the vertices (the connectivity stays; boundary\n"
      "vertices slide along the boundary, corners stay) to minimize the Neo-Hookean energy with\n"
      "the quasi-Newton method of the thesis; prints one row per iteration and the quality\n"
      "before and after. A mesh with inverted cells is untangled first.");
  cmd->add_option("input", o->inputs, input_mesh_help("mesh to smooth"))->required();
  cmd->add_option("-o,--output", o->output, fmt::format("smoothed mesh ({})", kMeshOutputs))
      ->required();
  cmd->add_flag("--force", o->force, "allow the output to overwrite the input file (default: off)");
  o->options.add(*cmd, "");
  add_run_output_options(*cmd, o->outputs, "scaled_jacobian");
  o->options.add_remaining(*cmd);
  return {cmd, [o] { smooth(*o); }};
}

}  // namespace neomesh::app
