// `neomesh adapt IN -o OUT --circle cx,cy,r ...`: r-adaptivity (thesis chapter 6). Cells
// crowd where the size field is small; the desired volumes are recomputed from the moving
// mesh in Picard iterations. docs/adaptivity.md explains the defaults and how they differ
// from the thesis (`--thesis`).
#include <filesystem>
#include <memory>
#include <optional>

#include "app/checks.hpp"
#include "app/method_options.hpp"
#include "app/optimization.hpp"
#include "app/subcommand.hpp"
#include "app/time_series.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "report/quality_report.hpp"
#include "report/run_report.hpp"

namespace neomesh::app {

namespace {

struct AdaptCommand {
  std::vector<std::string> inputs;  // the mesh, with a FEAT3 mesh's chart files
  std::string output, levelset, sizes_file, time;
  int step_updates = 1;  // Picard updates before a time step after the first may stop
  std::vector<double> circle, sphere, plane, box;
  bool force = false;
  bool fit = false;
  bool no_untangle = false, no_guard = false;
  SizeFieldOptions sizes;
  PicardOptions picard;
  MethodOptions method;
  RunOutputs outputs;
};

// --circle/--sphere cx,cy[,cz],r: the centre.
std::vector<double> centre(const std::vector<double>& v) {
  return {v.begin(), v.end() - 1};
}
// --plane p,n and --box lower,upper: the two halves.
std::pair<std::vector<double>, std::vector<double>> halves(const std::vector<double>& v) {
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  return {{v.begin(), middle}, {middle, v.end()}};
}

// The size field of the command line; an error in its arguments names the option.
SizeField make_size_field(const AdaptCommand& o) {
  const int given = !o.circle.empty() + !o.sphere.empty() + !o.plane.empty() + !o.box.empty() +
                    !o.levelset.empty() + !o.sizes_file.empty();
  if (given != 1)
    fail("give exactly one size field: --circle, --sphere, --plane, --box, --levelset or --sizes");
  auto option = [](const char* flag, auto make) {
    try {
      return make();
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", flag, e.what()));
    }
  };
  if (!o.circle.empty())
    return option("--circle", [&] { return SizeField::sphere(centre(o.circle), o.circle.back()); });
  if (!o.sphere.empty())
    return option("--sphere", [&] { return SizeField::sphere(centre(o.sphere), o.sphere.back()); });
  if (!o.plane.empty()) {
    auto [point, normal] = halves(o.plane);
    return option("--plane", [&] { return SizeField::plane(point, normal); });
  }
  if (!o.box.empty()) {
    auto [lower, upper] = halves(o.box);
    return option("--box", [&] { return SizeField::box(lower, upper); });
  }
  if (!o.levelset.empty())
    return option("--levelset", [&] { return SizeField::level_set(o.levelset); });
  return SizeField::read_cell_values(o.sizes_file);
}

// The surface --fit fits the mesh to: the zero set of --levelset, or of the signed distance to
// --circle, --sphere or --plane.
LevelSet fit_level_set(const AdaptCommand& o) {
  if (!o.levelset.empty()) return LevelSet::expression(o.levelset);
  if (!o.circle.empty()) return LevelSet::sphere(centre(o.circle), o.circle.back());
  if (!o.sphere.empty()) return LevelSet::sphere(centre(o.sphere), o.sphere.back());
  if (!o.plane.empty()) {
    auto [point, normal] = halves(o.plane);
    return LevelSet::plane(point, normal);
  }
  fail("--fit fits the mesh to a level set: give --levelset, --circle, --sphere or --plane");
}

std::string describe(const FitSummary& f) {
  return fmt::format(
      "fit: {} interface facets, {} vertices within {:.1e} of the zero set, {} stages ({} undone, "
      "{} cells moved across)",
      f.facets, f.vertices, f.max_distance, f.stages, f.undone, f.cells_moved_across);
}

// A geometry that moves: the size field at each time of `times` in turn, every step warm-started
// from the mesh and desired volumes of the one before; one mesh file, summary line (and
// picture) per step, and a ParaView collection for an .pvd output.
void adapt_in_time(const AdaptCommand& o, const AdaptOptions& options, SizeField& field,
                   OptimizationRun& run, const std::vector<double>& times, LevelSet* phi) {
  const std::filesystem::path output = o.output;
  std::vector<std::filesystem::path> members;
  nlohmann::json steps = nlohmann::json::array();
  const RunSettings settings{options.energy, options.solver, options.boundary};
  const double start = MPI_Wtime();
  for (std::size_t i = 0; i < times.size(); ++i) {
    field.set_time(times[i]);
    const double step_start = MPI_Wtime();
    // The problem is printed once; then one summary line per step.
    Observer observe;
    if (i == 0) observe.started = run.observer(settings, true).started;
    std::string fitted;
    nlohmann::json fit_record;
    Result result;
    if (phi) {
      phi->set_time(times[i]);
      result = run.optimizer().adapt(field, *phi, options, observe);
      const FitSummary& f = *result.fit;
      fitted = "; " + describe(f);
      fit_record = {{"max_distance", f.max_distance},
                    {"iterations", f.iterations},
                    {"facets", f.facets},
                    {"stages", f.stages},
                    {"undone", f.undone}};
    } else {
      result = run.optimizer().adapt(field, options, observe);
    }
    const double seconds = MPI_Wtime() - step_start;
    members.push_back(series_member(output, static_cast<int>(i)));
    run.snapshot(members.back());
    const VolumeRatioStats& q = result.volume_ratio;
    const double min_sj = result.quality_after.scaled_jacobian.min;
    always(
        "step {}/{}, t = {:.4g}: {} iterations, {} updates, {}; Q in [0.5, 2] for {:.1f}% of "
        "the cells; min scaled Jacobian {:.3f}{}; {:.2f} s; wrote {}\n",
        i + 1, times.size(), times[i], result.history.size(), result.update_iterations.size(),
        describe(result.reason), 100 * q.within, min_sj, fitted, seconds, members.back().string());
    if (!o.outputs.picture_after.empty())
      run.draw(numbered_path("--picture", o.outputs.picture_after, static_cast<int>(i)),
               o.outputs.picture_field,
               fmt::format("{}, t = {:.4g}", input_label(o.inputs), times[i]));
    steps.push_back({{"time", times[i]},
                     {"file", members.back().string()},
                     {"iterations", result.history.size()},
                     {"updates", result.update_iterations.size()},
                     {"stop", describe(result.reason)},
                     {"volume_ratio", to_json(q)},
                     {"min_scaled_jacobian", min_sj},
                     {"inverted", result.quality_after.inverted},
                     {"seconds", seconds}});
    if (phi) steps.back()["fit"] = fit_record;
  }
  const MPI_Comm comm = run.mesh().comm();
  if (output.extension() == ".pvd") {
    on_root(comm, [&] { write_pvd(output, times, members); });
    always("wrote {}: {} steps ({:.2f} s)\n", output.string(), times.size(), MPI_Wtime() - start);
  }
  if (!o.outputs.report.empty())
    on_root(comm, [&] {
      const nlohmann::json report = {{"input", input_label(o.inputs)},
                                     {"output", o.output},
                                     {"size_field", field.description()},
                                     {"steps", steps},
                                     {"seconds", MPI_Wtime() - start}};
      write_json(report, o.outputs.report);
    });
}

void adapt(AdaptCommand& o) {
  AdaptOptions options;
  options.sizes = o.sizes;
  options.picard = o.picard;
  options.warm_updates = o.step_updates;
  options.untangle = !o.no_untangle;
  options.quality_guard = !o.no_guard && !o.fit;
  options = resolve(o.method, options);
  check_finite("--circle", o.circle);
  check_finite("--sphere", o.sphere);
  check_finite("--plane", o.plane);
  check_finite("--box", o.box);
  SizeField field = make_size_field(o);
  const std::vector<double> times =
      o.time.empty() ? std::vector<double>{} : parse_time_steps(o.time);
  const std::filesystem::path output = o.output;
  if (times.empty() && output.extension() == ".pvd")
    fail("-o {}: a ParaView collection (.pvd) holds a time series; give --time", o.output);
  check_output_path(o.inputs, times.empty() ? output : series_member(output, 0), o.force);
  // Every output is checked before the run, so that a typo does not cost a long run.
  check_run_outputs(o.outputs);
  if (!times.empty()) {
    if (!o.outputs.picture_after.empty()) numbered_path("--picture", o.outputs.picture_after, 0);
    if (!o.outputs.history_plot.empty() || !o.outputs.picture_before.empty())
      fail(
          "--plot-history and --picture-before draw one run; with --time use --picture with a "
          "pattern");
  }

  std::optional<LevelSet> phi;
  if (o.fit) phi.emplace(fit_level_set(o));

  OptimizationRun run(o.inputs, o.no_untangle ? InvertedCells::Refuse : InvertedCells::Keep);
  const Mesh& mesh = run.mesh();
  // Every time's interface must exist and lie inside the domain: fail before any output.
  if (phi)
    for (double t : times.empty() ? std::vector<double>{0.0} : times) {
      phi->set_time(t);
      mesh.interface(*phi);
    }
  check_run_outputs(o.outputs, mesh.dim());  // pictures of a 3D mesh: before the run
  say("size field: {}\n", field.description());
  if (!times.empty()) {
    adapt_in_time(o, options, field, run, times, phi ? &*phi : nullptr);
    return;
  }
  const RunSettings settings{options.energy, options.solver, options.boundary};
  const auto picture_before = [&] {
    if (!o.outputs.picture_before.empty())
      run.draw(o.outputs.picture_before, o.outputs.picture_field,
               "input: " + input_label(o.inputs));
  };
  const Observer observe = run.observer(settings, o.outputs.progress_lines, picture_before);
  const Result result = phi ? run.optimizer().adapt(field, *phi, options, observe)
                            : run.optimizer().adapt(field, options, observe);
  nlohmann::json fit_report;
  if (result.fit) {
    const FitSummary& f = *result.fit;
    always("{}; {} iterations\n", describe(f), f.iterations);
    fit_report = {{"level_set", f.level_set},
                  {"facets", f.facets},
                  {"vertices", f.vertices},
                  {"max_distance", f.max_distance},
                  {"stages", f.stages},
                  {"undone", f.undone},
                  {"cells_moved_across", f.cells_moved_across},
                  {"iterations", f.iterations}};
  }

  const VolumeRatioStats& q = result.volume_ratio;
  always(
      "adaptation: {} updates of the desired volumes (after iterations {}); Q = actual/desired "
      "volume in [0.5, 2] for {:.1f}% of the cells, min {:.3g}, median {:.3g}, max {:.3g}\n",
      result.update_iterations.size(), fmt::join(result.update_iterations, ", "), 100 * q.within,
      q.min, q.median, q.max);
  run.finish(result, settings, o.output, o.outputs,
             {{"size_field", field.description()},
              {"size_options",
               {{"floor", options.sizes.floor},
                {"power", options.sizes.power},
                {"max_ratio", options.sizes.ratio(o.fit)},
                {"smoothing_passes", options.sizes.smoothing_passes}}},
              {"picard",
               {{"min_updates", options.picard.min_updates},
                {"update_every", options.picard.update_every},
                {"update_move", options.picard.update_move},
                {"update_step_norm", options.picard.update_step_norm},
                {"relaxation", options.picard.relaxation},
                {"update_iterations", result.update_iterations}}},
              {"volume_ratio", to_json(q)},
              {"fit", fit_report}});
}

}  // namespace

Subcommand add_adapt(CLI::App& app) {
  auto o = std::make_shared<AdaptCommand>();
  // Adaptation wants volumes met, not only shapes: λ = 4 μ, and boundary vertices that slide
  // so that the cells at the boundary can grade too (docs/adaptivity.md).
  o->method.energy = AdaptOptions().energy;
  o->method.boundary = name(AdaptOptions().boundary.mode);
  CLI::App* cmd = app.add_subcommand(
      "adapt",
      "Move the vertices so that cells are small near a surface (circle, sphere, plane, box, "
      "level set) or follow given sizes: desired volume v = floor + d^p for the distance d of "
      "the cell's centre, recomputed from the moving mesh in Picard iterations (thesis §6).");
  cmd->add_option("input", o->inputs, input_mesh_help("mesh to adapt"))->required();
  cmd->add_option("-o,--output", o->output, fmt::format("adapted mesh ({})", kMeshOutputs))
      ->required();
  cmd->add_flag("--force", o->force, "allow the output to overwrite the input file");
  cmd->add_flag("--no-guard", o->no_guard,
                "keep the adaptation's optimum even where a cell ends up worse than the input's "
                "worst cell or with a corner nearly flat (default: off, i.e. flat corners are "
                "lifted and such cells' vertices are pulled back; not with --fit; --thesis "
                "implies it)");
  cmd->add_flag("--no-untangle", o->no_untangle,
                "refuse a mesh with inverted cells instead of untangling it first (default: off, "
                "i.e. inverted cells are untangled towards the size field's volumes, then the mesh "
                "is adapted)");

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
                  "largest over smallest desired volume; smaller ones are raised (0: no bound; "
                  "default 32, with --fit 16)")
      ->default_str("auto")
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

  const char* time = "A geometry that moves, and fitting the mesh to it";
  cmd->add_option("--time", o->time,
                  "START:END:STEPS: adapt at STEPS times from START to END (t in --levelset), each "
                  "step starting from the one before; -o OUT.pvd writes OUT-0000.vtu ... and "
                  "ParaView's collection, -o OUT.msh writes OUT-0000.msh ...")
      ->group(time);
  cmd->add_option("--step-updates", o->step_updates,
                  "Picard updates before a time step after the first may stop (the first step "
                  "uses --min-updates)")
      ->capture_default_str()
      ->group(time);

  cmd->add_flag("--fit", o->fit,
                "fit a chain of edges (2D) / surface of faces (3D) to the zero set of the level "
                "set (--levelset, --circle, --sphere, --plane): its vertices end on it exactly, "
                "written as the facet group 'interface' (.msh) and the fields inside, interface "
                "and phi (.vtu); with --time at every step")
      ->group(time);
  add_run_output_options(*cmd, o->outputs, "Q");
  add_method_options(*cmd, o->method);
  return {cmd, [o] { adapt(*o); }};
}

}  // namespace neomesh::app
