// `neomesh smooth IN -o OUT`: every cell towards an ideal cell of its desired volume
// (thesis chapter 5), boundary vertices fixed.
#include <filesystem>
#include <memory>

#include "app/method_options.hpp"
#include "app/optimization.hpp"
#include "app/subcommand.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "solver/desired_volumes.hpp"

namespace neomesh::app {

namespace {

struct SmoothOptions {
  std::string input, output, report, plot_history, sizes = "smoothed";
  bool force = false, no_table = false;
  MethodOptions method;
};

void smooth(SmoothOptions& o) {
  finalize(o.method);
  const SizeMode sizes = parse_size_mode(o.method.thesis ? "uniform" : o.sizes);
  check_output_path(o.input, o.output, o.force);

  OptimizationRun run(o.input, o.method);
  run.set_desired_volumes(desired_volumes(sizes, run.view(), run.dofs(), run.input_volumes()));
  run.print_problem();
  const QuasiNewtonResult result = minimize(run.functional(), run.x(), o.method.solver,
                                            run.cell_size(), run.table_printer(o.no_table));
  run.finish(result, o.output, o.report, o.plot_history);
}

}  // namespace

Subcommand add_smooth(CLI::App& app) {
  auto o = std::make_shared<SmoothOptions>();
  CLI::App* cmd = app.add_subcommand(
      "smooth",
      "Improve the shape of every cell, keeping the mesh's connectivity and its boundary "
      "vertices: minimizes the Neo-Hookean energy with the quasi-Newton method of the thesis.");
  cmd->add_option("input", o->input, "mesh to smooth (.msh Gmsh 2.2/4.1, .xml FEAT3)")->required();
  cmd->add_option("-o,--output", o->output, "smoothed mesh (.vtu with quality fields, or .msh)")
      ->required();
  cmd->add_flag("--force", o->force, "allow the output to overwrite the input file");
  cmd->add_option("--sizes", o->sizes,
                  "desired cell volumes: smoothed (input volumes averaged over neighbours: keeps "
                  "the grading), input (each cell's own volume) or uniform (all equal, the thesis)")
      ->capture_default_str();
  cmd->add_option("--report", o->report, "write parameters, history, timings and quality as JSON");
  cmd->add_option("--plot-history", o->plot_history,
                  "draw the Newton defect and F per iteration (.png or .svg)");
  cmd->add_flag("--no-table", o->no_table,
                "one progress line per iteration instead of the iteration table");
  add_method_options(*cmd, o->method);
  return {cmd, [o] { smooth(*o); }};
}

}  // namespace neomesh::app
