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

namespace neomesh::app {

namespace {

struct SmoothCommand {
  std::vector<std::string> inputs;  // the mesh, with a FEAT3 mesh's chart files
  std::string output;
  std::string sizes{name(SmoothOptions().sizes)}, targets{name(SmoothOptions().targets)};
  bool force = false, no_guard = false, no_untangle = false;
  MethodOptions method;
  RunOutputs outputs;
};

void smooth(SmoothCommand& o) {
  SmoothOptions options;
  options.sizes = parse_size_mode(o.sizes);
  options.targets = parse_target_mode(o.targets);
  options.untangle = !o.no_untangle;
  options.quality_guard = !o.no_guard;
  options = resolve(o.method, options);
  check_output_path(o.inputs, o.output, o.force);
  // Every output is checked before the run, so that a typo does not cost a long run.
  check_run_outputs(o.outputs);

  OptimizationRun run(o.inputs, o.no_untangle ? InvertedCells::Refuse : InvertedCells::Keep);
  check_run_outputs(o.outputs, run.mesh().dim());  // pictures of a 3D mesh: before the run
  const RunSettings settings{options.energy, options.solver, options.boundary};
  const auto picture_before = [&] {
    if (!o.outputs.picture_before.empty())
      run.draw(o.outputs.picture_before, o.outputs.picture_field,
               "input: " + input_label(o.inputs));
  };
  const Result result = run.optimizer().smooth(
      options, run.observer(settings, o.outputs.progress_lines, picture_before));
  run.finish(result, settings, o.output, o.outputs);
}

}  // namespace

Subcommand add_smooth(CLI::App& app) {
  auto o = std::make_shared<SmoothCommand>();
  // The worst cells of real meshes touch the boundary, and only sliding vertices can fix them
  // (box_with_hole: min scaled Jacobian 0.024 fixed, 0.151 sliding); the boundary stays on the
  // input's facets, corners and group borders stay put (docs/boundary.md).
  o->method.boundary = name(SmoothOptions().boundary.mode);
  o->method.energy = SmoothOptions().energy;
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
  cmd->add_flag("--no-guard", o->no_guard,
                "keep the energy's optimum even where a cell ends up worse than the input's worst "
                "cell or with a corner nearly flat (default: off, i.e. flat corners are lifted "
                "and such cells' vertices are pulled back; --thesis implies it)");
  cmd->add_flag("--no-untangle", o->no_untangle,
                "refuse a mesh with inverted cells instead of untangling it first (default: off, "
                "i.e. inverted cells are untangled, then the mesh is smoothed)");
  cmd->add_option("--sizes", o->sizes,
                  "desired cell volumes: smoothed (input volumes averaged over neighbours: keeps "
                  "the grading), input (each cell's own volume) or uniform (all equal, the thesis)")
      ->check(CLI::IsMember(choice_names<SizeMode>()))
      ->capture_default_str();
  cmd->add_option("--targets", o->targets,
                  "the cell each cell is pulled towards: smoothed (the input's own cell where its "
                  "neighbourhood is stretched on purpose, as boundary layers and graded meshes "
                  "are; the ideal cell where the stretching is noise), ideal (square, cube, "
                  "equilateral simplex, ... of the desired volume: the thesis) or input (the input "
                  "cell: only untangle and repair the worst cells)")
      ->check(CLI::IsMember(choice_names<TargetMode>()))
      ->capture_default_str();
  add_run_output_options(*cmd, o->outputs, "scaled_jacobian");
  add_method_options(*cmd, o->method);
  return {cmd, [o] { smooth(*o); }};
}

}  // namespace neomesh::app
