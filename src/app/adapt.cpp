// `neomesh adapt IN -o OUT --circle cx,cy,r ...`: r-adaptivity (thesis chapter 6). Cells
// crowd where the size field is small; the desired volumes are recomputed from the moving
// mesh in Picard iterations. docs/adaptivity.md explains the defaults and how they differ
// from the thesis (`--thesis`).
#include <filesystem>
#include <memory>

#include "adapt/picard.hpp"
#include "adapt/size_field.hpp"
#include "adapt/volume_ratio.hpp"
#include "app/checks.hpp"
#include "app/method_options.hpp"
#include "app/optimization.hpp"
#include "app/subcommand.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace neomesh::app {

namespace {

struct AdaptOptions {
  std::string input, output, levelset, sizes_file;
  std::vector<double> circle, sphere, plane, box;
  bool force = false;
  SizeFieldOptions sizes;
  PicardOptions picard;
  MethodOptions method;
  RunOutputs outputs;
};

SizeField make_size_field(const AdaptOptions& o) {
  const int given = !o.circle.empty() + !o.sphere.empty() + !o.plane.empty() + !o.box.empty() +
                    !o.levelset.empty() + !o.sizes_file.empty();
  if (given != 1)
    fail("give exactly one size field: --circle, --sphere, --plane, --box, --levelset or --sizes");
  auto split = [](const std::vector<double>& v, std::size_t first) {
    return std::pair{std::vector<double>(v.begin(), v.begin() + first),
                     std::vector<double>(v.begin() + first, v.end())};
  };
  if (!o.circle.empty()) return SizeField::sphere({o.circle[0], o.circle[1]}, o.circle[2]);
  if (!o.sphere.empty())
    return SizeField::sphere({o.sphere[0], o.sphere[1], o.sphere[2]}, o.sphere[3]);
  if (!o.plane.empty()) {
    auto [point, normal] = split(o.plane, o.plane.size() / 2);
    return SizeField::plane(point, normal);
  }
  if (!o.box.empty()) {
    auto [lower, upper] = split(o.box, o.box.size() / 2);
    return SizeField::box(lower, upper);
  }
  if (!o.levelset.empty()) return SizeField::level_set(o.levelset);
  return SizeField::read_cell_values(o.sizes_file);
}

// The thesis' scheme (§6.1): the raw field, shape-dominated energy (λ = 1, μ = 10), fixed
// boundary vertices, full updates when σ‖δ‖ < 1e-6 or every 8 iterations, 7 updates.
void use_thesis_scheme(AdaptOptions& o) {
  o.sizes.max_ratio = SizeFieldOptions::thesis().max_ratio;
  o.sizes.smoothing_passes = SizeFieldOptions::thesis().smoothing_passes;
  o.method.energy.lambda = 1.0;
  o.method.energy.mu = 10.0;
  o.method.boundary = "fixed";
  o.picard = {.min_updates = 7,
              .update_every = 8,
              .update_move = 0.0,
              .update_step_norm = 1e-6,
              .relaxation = 1.0};
}

void check(const AdaptOptions& o) {
  check_option("--power", o.sizes.power, o.sizes.power > 0, "positive");
  check_option("--floor", o.sizes.floor, o.sizes.floor >= 0, "0 or more");
  check_option("--max-ratio", o.sizes.max_ratio, o.sizes.max_ratio == 0 || o.sizes.max_ratio > 1,
               "above 1, or 0 for no bound");
  check_option("--smooth-sizes", o.sizes.smoothing_passes, o.sizes.smoothing_passes >= 0,
               "0 or more");
  check_option("--min-updates", o.picard.min_updates, o.picard.min_updates >= 0, "0 or more");
  check_option("--update-every", o.picard.update_every, o.picard.update_every >= 1, "at least 1");
  check_option("--update-move", o.picard.update_move, o.picard.update_move >= 0, "0 or more");
  check_option("--update-step", o.picard.update_step_norm, o.picard.update_step_norm >= 0,
               "0 or more");
  check_option("--relaxation", o.picard.relaxation,
               o.picard.relaxation > 0 && o.picard.relaxation <= 1, "in (0, 1]");
  check_finite("--circle", o.circle);
  check_finite("--sphere", o.sphere);
  check_finite("--plane", o.plane);
  check_finite("--box", o.box);
}

void adapt(AdaptOptions& o) {
  if (o.method.thesis) use_thesis_scheme(o);
  finalize(o.method);
  check(o);
  const SizeField field = make_size_field(o);
  check_output_path(o.input, o.output, o.force);
  // Every output is checked before the run, so that a typo does not cost a long run.
  check_run_outputs(o.outputs);

  OptimizationRun run(o.input, o.method);
  check_run_outputs(o.outputs, run.view().dim);  // pictures of a 3D mesh: before the run
  say("size field: {}\n", field.description());
  run.print_problem();
  const auto target_volumes =
      size_field_volumes(field, o.sizes, run.view(), run.dofs(), run.mesh_volume());
  if (!o.outputs.picture_before.empty()) {
    run.set_desired_volumes(target_volumes(run.x()));
    run.draw(o.outputs.picture_before, o.outputs.picture_field, "input: " + o.input);
  }
  const auto table = run.table_printer(o.outputs.progress_lines);
  PicardObserver observe{.iteration = table, .update = [](int k, int update) {
                           say("  -- desired volumes updated after iteration {} (update {})\n", k,
                               update);
                         }};
  const PicardResult result = picard(
      run.functional(), run.view(), run.x(), target_volumes,
      [&run](const std::vector<double>& v) { run.set_desired_volumes(v); }, o.picard,
      o.method.solver, observe);

  const VolumeRatioStats q =
      volume_ratio_stats(run.functional().cell_fields(run.x()).volume_ratio, run.dofs().comm());
  always(
      "adaptation: {} updates of the desired volumes (after iterations {}); Q = actual/desired "
      "volume in [0.5, 2] for {:.1f}% of the cells, min {:.3g}, median {:.3g}, max {:.3g}\n",
      result.update_iterations.size(), fmt::join(result.update_iterations, ", "), 100 * q.within,
      q.min, q.median, q.max);
  run.finish(result.run, o.output, o.outputs,
             {{"size_field", field.description()},
              {"size_options",
               {{"floor", o.sizes.floor},
                {"power", o.sizes.power},
                {"max_ratio", o.sizes.max_ratio},
                {"smoothing_passes", o.sizes.smoothing_passes}}},
              {"picard",
               {{"min_updates", o.picard.min_updates},
                {"update_every", o.picard.update_every},
                {"update_move", o.picard.update_move},
                {"update_step_norm", o.picard.update_step_norm},
                {"relaxation", o.picard.relaxation},
                {"update_iterations", result.update_iterations}}},
              {"volume_ratio", to_json(q)}});
}

}  // namespace

Subcommand add_adapt(CLI::App& app) {
  auto o = std::make_shared<AdaptOptions>();
  // Adaptation wants volumes met, not only shapes: λ = 4 μ, and boundary vertices that slide
  // so that the cells at the boundary can grade too (docs/adaptivity.md).
  o->method.energy.lambda = 4.0;
  o->method.energy.mu = 1.0;
  o->method.boundary = "slide";
  CLI::App* cmd = app.add_subcommand(
      "adapt",
      "Move the vertices so that cells are small near a surface (circle, sphere, plane, box, "
      "level set) or follow given sizes: desired volume v = floor + d^p for the distance d of "
      "the cell's centre, recomputed from the moving mesh in Picard iterations (thesis §6).");
  cmd->add_option("input", o->input, "mesh to adapt (.msh Gmsh 2.2/4.1, .xml FEAT3)")->required();
  cmd->add_option("-o,--output", o->output,
                  "adapted mesh (.vtu with per-cell energy, Q and quality fields, or .msh)")
      ->required();
  cmd->add_flag("--force", o->force, "allow the output to overwrite the input file");

  const char* field = "Size field (exactly one)";
  cmd->add_option("--circle", o->circle, "cx,cy,r: distance to a circle")
      ->delimiter(',')
      ->expected(3)
      ->group(field);
  cmd->add_option("--sphere", o->sphere, "cx,cy,cz,r: distance to a sphere")
      ->delimiter(',')
      ->expected(4)
      ->group(field);
  cmd->add_option("--plane", o->plane, "px,py[,pz],nx,ny[,nz]: distance to a line/plane")
      ->delimiter(',')
      ->expected(4, 6)
      ->group(field);
  cmd->add_option("--box", o->box, "lx,ly[,lz],ux,uy[,uz]: distance to the surface of a box")
      ->delimiter(',')
      ->expected(4, 6)
      ->group(field);
  cmd->add_option("--levelset", o->levelset,
                  "signed distance φ(x, y, z) as an expression (muparser), d = |φ|")
      ->group(field);
  cmd->add_option("--sizes", o->sizes_file,
                  "file with one relative volume per cell, in the mesh's cell order")
      ->group(field);
  cmd->add_option("--power", o->sizes.power, "p in v = floor + d^p")
      ->capture_default_str()
      ->group(field);
  cmd->add_option("--floor", o->sizes.floor, "floor in v = floor + d^p")
      ->capture_default_str()
      ->group(field);
  cmd->add_option("--max-ratio", o->sizes.max_ratio,
                  "largest over smallest desired volume; smaller ones are raised (0: no bound)")
      ->capture_default_str()
      ->group(field);
  cmd->add_option("--smooth-sizes", o->sizes.smoothing_passes,
                  "passes of averaging log(desired volume) over neighbouring cells")
      ->capture_default_str()
      ->group(field);

  const char* picard = "Picard iteration (thesis §6)";
  cmd->add_option("--min-updates", o->picard.min_updates,
                  "updates of the desired volumes before the run may stop")
      ->capture_default_str()
      ->group(picard);
  cmd->add_option("--update-every", o->picard.update_every,
                  "update the desired volumes at least every this many iterations")
      ->capture_default_str()
      ->group(picard);
  cmd->add_option("--update-move", o->picard.update_move,
                  "update once a quasi-Newton step moved no vertex more than this times its "
                  "local cell size")
      ->capture_default_str()
      ->group(picard);
  cmd->add_option("--update-step", o->picard.update_step_norm,
                  "update once the step's Euclidean norm σ‖δ‖ is below this (thesis: 1e-6; 0: off)")
      ->capture_default_str()
      ->group(picard);
  cmd->add_option("--relaxation", o->picard.relaxation,
                  "ω in v ← (1−ω) v_old + ω v(centroids), in (0, 1]")
      ->capture_default_str()
      ->group(picard);

  add_run_output_options(*cmd, o->outputs, "Q");
  add_method_options(*cmd, o->method);
  return {cmd, [o] { adapt(*o); }};
}

}  // namespace neomesh::app
