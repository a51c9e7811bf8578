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
  std::string output, levelset, volumes_file, time, metric, metric_data, metric_file;
  std::vector<double> circle, sphere, plane, box, stretch;
  bool force = false;
  bool fit = false;
  TaskOptions<AdaptOptions> options;
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

// An error in an option's arguments, named by the option.
template <typename Make>
SizeField option(const char* flag, Make make) {
  try {
    return make();
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", flag, e.what()));
  }
}

// --metric "m11;m12;m22": the entries.
std::vector<std::string> metric_entries(const std::string& text) {
  std::vector<std::string> entries;
  for (std::size_t start = 0;;) {
    const std::size_t end = text.find(';', start);
    entries.push_back(text.substr(start, end - start));
    if (end == std::string::npos) return entries;
    start = end + 1;
  }
}

// The distance field of --circle, --sphere, --plane, --box, --levelset, or --volumes' values.
SizeField distance_field(const AdaptCommand& o) {
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
  return SizeField::read_cell_values(o.volumes_file);
}

// The size field of the command line, stretched with --stretch. A metric per vertex
// (--metric-data, --metric-file) needs the mesh: none while `mesh` is null.
std::optional<SizeField> make_size_field(const AdaptCommand& o, const Mesh* mesh) {
  const int given = !o.circle.empty() + !o.sphere.empty() + !o.plane.empty() + !o.box.empty() +
                    !o.levelset.empty() + !o.volumes_file.empty() + !o.metric.empty() +
                    !o.metric_data.empty() + !o.metric_file.empty();
  if (given != 1)
    fail(
        "give exactly one size field: --circle, --sphere, --plane, --box, --levelset, --volumes, "
        "--metric, --metric-data or --metric-file");
  if (!o.metric_data.empty() || !o.metric_file.empty()) {
    if (!o.stretch.empty()) fail("--stretch stretches a distance field, not a given metric");
    if (!mesh) return std::nullopt;
    if (!o.metric_file.empty())
      return option("--metric-file",
                    [&] { return SizeField::read_vertex_metric(*mesh, o.metric_file); });
    return option("--metric-data", [&] { return SizeField::vertex_metric(*mesh, o.metric_data); });
  }
  if (!o.metric.empty())
    return option("--metric", [&] { return SizeField::metric(metric_entries(o.metric)); });
  SizeField field = distance_field(o);
  if (o.stretch.empty()) return field;
  return option("--stretch", [&] {
    Stretch s{.normal = o.stretch[0], .tangent = o.stretch[1], .width = o.stretch[2]};
    if (o.stretch.size() > 3) s.grading = o.stretch[3];
    return field.stretched(s);
  });
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
  AdaptOptions options = o.options.resolve();
  if (o.fit) options.quality_guard = false;  // the interface's vertices must stay on it
  check_finite("--circle", o.circle);
  check_finite("--sphere", o.sphere);
  check_finite("--plane", o.plane);
  check_finite("--box", o.box);
  check_finite("--stretch", o.stretch);
  std::optional<SizeField> field = make_size_field(o, nullptr);
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

  OptimizationRun run(o.inputs, options.untangle ? InvertedCells::Keep : InvertedCells::Refuse);
  const Mesh& mesh = run.mesh();
  // Every time's interface must exist and lie inside the domain: fail before any output.
  if (phi)
    for (double t : times.empty() ? std::vector<double>{0.0} : times) {
      phi->set_time(t);
      mesh.interface(*phi);
    }
  if (!field) field = make_size_field(o, &mesh);
  say("size field: {}\n", field->description());
  if (!times.empty()) {
    adapt_in_time(o, options, *field, run, times, phi ? &*phi : nullptr);
    return;
  }
  const RunSettings settings{options.energy, options.solver, options.boundary};
  const auto picture_before = [&] {
    if (!o.outputs.picture_before.empty())
      run.draw(o.outputs.picture_before, o.outputs.picture_field,
               "input: " + input_label(o.inputs));
  };
  const Observer observe = run.observer(settings, o.outputs.progress_lines, picture_before);
  const Result result = phi ? run.optimizer().adapt(*field, *phi, options, observe)
                            : run.optimizer().adapt(*field, options, observe);
  if (result.fit) always("{}; {} iterations\n", describe(*result.fit), result.fit->iterations);

  const VolumeRatioStats& q = result.volume_ratio;
  always(
      "adaptation: {} updates of the desired volumes (after iterations {}); Q = actual/desired "
      "volume in [0.5, 2] for {:.1f}% of the cells, min {:.3g}, median {:.3g}, max {:.3g}\n",
      result.update_iterations.size(), fmt::join(result.update_iterations, ", "), 100 * q.within,
      q.min, q.median, q.max);
  run.finish(result, settings, o.output, o.outputs,
             adapt_report(options, result, field->description()));
}

}  // namespace

Subcommand add_adapt(CLI::App& app) {
  auto o = std::make_shared<AdaptCommand>();
  CLI::App* cmd = app.add_subcommand(
      "adapt",
      "Move the vertices so that cells are small near a surface (circle, sphere, plane, box, "
      "level set) or follow given relative volumes: desired volume v = floor + d^p for the "
      "distance d of "
      "the cell's centre, recomputed from the moving mesh in Picard iterations (thesis §6).");
  cmd->add_option("input", o->inputs, input_mesh_help("mesh to adapt"))->required();
  cmd->add_option("-o,--output", o->output, fmt::format("adapted mesh ({})", kMeshOutputs))
      ->required();
  cmd->add_flag("--force", o->force, "allow the output to overwrite the input file");
  o->options.add(*cmd, "");

  const std::string field(kSizeFieldGroup);
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
  cmd->add_option("--volumes", o->volumes_file,
                  "file with one relative volume per cell, in the mesh's cell order")
      ->group(field);
  cmd->add_option("--metric", o->metric,
                  "\"m11;m12;m22\" (2D) or \"m11;m12;m13;m22;m23;m33\" (3D): an anisotropic "
                  "metric M(x, y, z) as expressions (muparser); cells aim at size 1/sqrt(λ) along "
                  "each eigenvector of M")
      ->group(field);
  cmd->add_option("--stretch", o->stretch,
                  "HN,HT,W[,G]: make the distance field anisotropic: cells of size HN across the "
                  "surface and HT along it within W of it, the size across growing by G (4) per "
                  "unit distance beyond")
      ->delimiter(',')
      ->expected(3, 4)
      ->group(field);
  cmd->add_option("--metric-data", o->metric_data,
                  "NAME: the metric per vertex in the input's point data NAME (3 components in 2D: "
                  "m11, m12, m22; 6 in 3D: m11, m12, m13, m22, m23, m33), interpolated over the "
                  "input mesh")
      ->group(field);
  cmd->add_option("--metric-file", o->metric_file,
                  "FILE: the same from a text file of one metric per line, in the input's vertex "
                  "order")
      ->group(field);
  o->options.add(*cmd, kSizeFieldGroup);
  o->options.add(*cmd, kPicardGroup);

  const std::string time(kTimeGroup);
  cmd->add_option("--time", o->time,
                  "START:END:STEPS: adapt at STEPS times from START to END (t in --levelset), each "
                  "step starting from the one before; -o OUT.pvd writes OUT-0000.vtu ... and "
                  "ParaView's collection, -o OUT.msh writes OUT-0000.msh ...")
      ->group(time);
  o->options.add(*cmd, kTimeGroup);

  cmd->add_flag("--fit", o->fit,
                "fit a chain of edges (2D) / surface of faces (3D) to the zero set of the level "
                "set (--levelset, --circle, --sphere, --plane): its vertices end on it exactly, "
                "written as the facet group 'interface' (.msh) and the fields inside, interface "
                "and phi (.vtu); with --time at every step")
      ->group(time);
  add_run_output_options(*cmd, o->outputs, "Q");
  o->options.add_remaining(*cmd);
  return {cmd, [o] { adapt(*o); }};
}

}  // namespace neomesh::app
