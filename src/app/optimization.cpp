#include "app/optimization.hpp"

#include <mpi.h>
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>

#include "api/memory_check.hpp"
#include "api/thread_count.hpp"
#include "app/checks.hpp"
#include "core/atomic_file.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/memory.hpp"
#include "core/petsc.hpp"
#include "report/canvas.hpp"
#include "report/history_plot.hpp"
#include "report/iteration_table.hpp"
#include "report/render.hpp"
#include "report/run_report.hpp"

namespace neomesh::app {

void check_output_path(const std::vector<std::string>& inputs, const std::filesystem::path& output,
                       bool force) {
  collectively(PETSC_COMM_WORLD, [&] {
    // Fail now, not after a long run.
    check_output_file("-o/--output", output.string(), OutputKind::Mesh);
    std::error_code ignored;
    for (const std::string& input : inputs)
      if (!force && std::filesystem::equivalent(input, output, ignored))
        fail("output {} is the input file; choose another name or pass --force to overwrite it",
             output.string());
  });
}

namespace {

struct PeakMemory {
  double max_rank_mib = 0.0, sum_mib = 0.0;
};

// Peak resident set size of this process (getrusage), the largest and the sum over ranks.
PeakMemory peak_memory(MPI_Comm comm) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double mine = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
  PeakMemory m;
  MPI_Allreduce(&mine, &m.max_rank_mib, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(&mine, &m.sum_mib, 1, MPI_DOUBLE, MPI_SUM, comm);
  return m;
}

// The thread count of a run on this mesh (api/thread_count.hpp).
void share_cores(const Mesh& mesh) {
  if (const int threads = run_thread_count(mesh); threads > 0) omp_set_num_threads(threads);
}

// The memory the run will use (its estimate, api/memory_check.hpp), faulted in at once by all
// threads and kept from then on (core/memory.hpp): square-midpoint 1024² 11.6 → 10.4 s,
// 2048² 68.9 → 58.3–62.2 s (docs/benchmarks.md, "Where the time goes"). Not where there is
// less than 512 MiB to fault: there the estimate's excess over the run's own peak costs more
// than the threads save (hexes 40³ faulted 276 MiB in, peak 349 MiB instead of 230 and 0.4-2 s
// slower; square-midpoint 512², 286 MiB: 1.5-1.9 s slower), nor where it would take more than
// three quarters of the memory available: it is for speed, and an estimate above the run's own
// peak must not be what takes a machine to its limit (square-midpoint 4096² on 24 GiB).
void fault_in_the_run(const Mesh& mesh) {
  constexpr double kWorthIt = 512.0 * 1024 * 1024;
  const int ranks = mpi_size(mesh.comm());
  const std::int64_t vertices = mesh.num_vertices() / ranks, cells = mesh.num_cells() / ranks;
  // The whole program is this run: what it holds now is its own.
  const double more =
      std::max(0.0, estimated_peak_bytes(mesh.dim(), vertices, cells) - resident_bytes());
  if (node_sum(mesh.comm(), more) > 0.75 * available_bytes()) return;
  if (more >= kWorthIt) keep_and_fault_in(more);
}

// --verbose: the linear solves of one iteration.
void print_solver_details(const IterationRecord& rec) {
  const std::string delta =
      !rec.delta_solved
          ? std::string("not solved (antigradient step)")
          : fmt::format("{} Krylov iterations, residual {:.2e}{}", rec.krylov_delta,
                        rec.residual_delta,
                        rec.delta_failed      ? ", did not converge: alpha cut to 0.1 alpha"
                        : rec.delta_truncated ? ", negative curvature: CG iterate used"
                                              : "");
  detail("  k={}: delta~ {}; s: {}; step 0.5^{}; largest move {:.2e} cell sizes\n", rec.k, delta,
         rec.s_solved ? fmt::format("{} Krylov iterations", rec.krylov_s)
                      : std::string("not solved (angle test estimated with one V-cycle)"),
         rec.armijo_steps, rec.max_move);
}

// The problem as the Optimizer set it up, and the settings it runs with.
void print_problem(const Mesh& mesh, const ProblemSummary& problem, const RunSettings& s) {
  const int ranks = mpi_size(mesh.comm());
  say("{}: {} cells, {} vertices, {} free coordinates{}\n", mesh.name(), mesh.num_cells(),
      mesh.num_vertices(), problem.free_coordinates,
      ranks > 1 ? fmt::format(" on {} processes", ranks) : "");
  say("lambda {}, mu {}, alpha0 {}, eta {}, kmin {}, linear solver {}, boundary {}\n",
      s.energy.lambda, s.energy.mu, problem.alpha0, s.solver.advanced.eta, s.solver.advanced.kmin,
      name(s.solver.linear_solver), name(s.boundary.mode));
  say("{}", targets_lines(problem.targets));
  const BoundarySummary& b = problem.boundary;
  if (s.boundary.mode == BoundaryMode::Slide) {
    say("sliding boundary: {} patches, {} ridges; {} corners fixed, {} ridge and {} surface "
        "vertices slide\n",
        b.patches, b.ridges, b.corners, b.ridge_vertices, b.surface_vertices);
    for (const std::string& g : b.patch_geometry) detail("  {}\n", g);
    if (b.moved_onto_charts > 0)
      say("charts: {} boundary vertices moved onto their charts first (farthest by {:.3g})\n",
          b.moved_onto_charts, b.max_move_onto_charts);
  }
  detail(
      "quasi-Newton system H(alpha) delta~ = -g (options -hess_*): {}, or residual <= f x "
      "defect, f = defect / first defect within [{:g}, {:g}]\n",
      problem.hessian_solver, s.solver.advanced.hessian_defect_factor,
      std::max(s.solver.advanced.hessian_defect_factor, s.solver.advanced.hessian_forcing_max));
  detail("Riesz representative L s = g (options -riesz_*): {}\n", problem.riesz_solver);
  // The first iteration assembles the matrices and builds the preconditioners: on a large
  // mesh the longest wait before the first row of the table.
  say("assembling the matrices and setting up the linear solvers ...\n");
}

}  // namespace

struct OptimizationRun::Impl {
  double start = MPI_Wtime();  // before the mesh is read
  double read_seconds = 0.0, prepare_seconds = 0.0;
  Mesh mesh;
  Optimizer optimizer;

  Impl(const std::vector<std::string>& input, InvertedCells inverted)
      : mesh(read(input, inverted)), optimizer(mesh) {
    read_seconds = MPI_Wtime() - start;
    share_cores(mesh);
    fault_in_the_run(mesh);
  }

  static Mesh read(const std::vector<std::string>& input, InvertedCells inverted) {
    const int ranks = mpi_size(PETSC_COMM_WORLD);
    say("reading {}{} ...\n", input_label(input),
        ranks > 1 ? fmt::format(" and distributing it over {} processes", ranks) : "");
    const Activity reading("reading " + input_label(input));
    return Mesh::read(input_paths(input), PETSC_COMM_WORLD, inverted);
  }

  // The cell fields of the outputs at the mesh's coordinates: the optimizer's and the quality.
  std::vector<Field> cell_fields() const {
    std::vector<Field> fields = optimizer.cell_fields();
    const std::vector<Field> metrics = mesh.quality_by_cell();
    fields.insert(fields.end(), metrics.begin(), metrics.end());
    return fields;
  }
};

OptimizationRun::OptimizationRun(const std::vector<std::string>& input, InvertedCells inverted)
    : impl_(std::make_unique<Impl>(input, inverted)) {}
OptimizationRun::~OptimizationRun() = default;

Mesh& OptimizationRun::mesh() {
  return impl_->mesh;
}
Optimizer& OptimizationRun::optimizer() {
  return impl_->optimizer;
}

Observer OptimizationRun::observer(const RunSettings& settings, bool progress_only,
                                   std::function<void()> before_run) {
  // The table of a run that untangles first names each phase (round) above its rows.
  struct Table {
    bool header_printed = false;
    int round = 0;
  };
  auto table = std::make_shared<Table>();
  Impl& r = *impl_;
  return {
      .started =
          [&r, settings, before_run](const ProblemSummary& problem) {
            r.prepare_seconds = MPI_Wtime() - r.start - r.read_seconds;
            print_problem(r.mesh, problem, settings);
            if (before_run) before_run();
          },
      .untangling =
          [table](std::int64_t inverted) {
            say("{} cells are inverted: untangling them first\n", inverted);
            table->round = -1;
          },
      .untangled = [](const UntanglingSummary& u) { say("{}", untangled_line(u)); },
      .iteration =
          [table, progress_only](const IterationRecord& rec) {
            if (rec.untangling_round != table->round) {
              say("{}\n", untangling_phase_line(rec));
              table->round = rec.untangling_round;
            }
            if (progress_only) {
              say("{}\n", progress_line(rec));
            } else {
              if (!table->header_printed) say("{}\n", iteration_table_header());
              table->header_printed = true;
              say("{}\n", iteration_table_row(rec));
            }
            print_solver_details(rec);
          },
      .volumes_updated =
          [](int k, int update) {
            say("  -- desired volumes updated after iteration {} (update {})\n", k, update);
          },
      .fitting =
          [](const std::string& level_set) { say("fitting the mesh to {} = 0 ...\n", level_set); }};
}

namespace {
const std::vector<std::string> kPictureFields = {"Q",
                                                 "energy",
                                                 "scaled_jacobian",
                                                 "min_angle",
                                                 "max_angle",
                                                 "edge_ratio",
                                                 "inverse_mean_ratio",
                                                 "volume",
                                                 "desired_volume",
                                                 "det_G_min"};
}

void add_run_output_options(CLI::App& cmd, RunOutputs& o, const std::string& picture_field) {
  o.picture_field = picture_field;
  cmd.add_option("--report", o.report,
                 "write parameters, history, timings and quality as JSON to this file (default: "
                 "none)")
      ->check(kOutputPath);
  cmd.add_option("--plot-history", o.history_plot,
                 "draw the Newton defect and F per iteration to this .png or .svg (default: none)")
      ->check(kOutputPath);
  cmd.add_flag("--no-table", o.progress_lines,
               "one progress line per iteration (with elapsed time) instead of the iteration "
               "table (default: table)");
  cmd.add_option(
         "--picture-before", o.picture_before,
         "draw the input mesh coloured by --picture-field (.png or .svg; a 3D mesh's boundary "
         "in perspective; default: none)")
      ->check(kOutputPath);
  cmd.add_option("--picture", o.picture_after,
                 "draw the result coloured by --picture-field (.png or .svg; a 3D mesh's boundary "
                 "in perspective; default: none)")
      ->check(kOutputPath);
  cmd.add_option("--picture-field", o.picture_field, "cell field the pictures are coloured by")
      ->check(CLI::IsMember(kPictureFields))
      ->capture_default_str();
}

void check_run_outputs(const RunOutputs& o) {
  collectively(PETSC_COMM_WORLD, [&] {
    if (!o.report.empty()) check_output_file("--report", o.report, OutputKind::Json);
    const std::pair<const char*, const std::string&> pictures[] = {
        {"--plot-history", o.history_plot},
        {"--picture-before", o.picture_before},
        {"--picture", o.picture_after}};
    for (const auto& [option, path] : pictures)
      if (!path.empty()) check_output_file(option, path, OutputKind::Picture);
  });
}

void OptimizationRun::draw(const std::filesystem::path& path, const std::string& field,
                           const std::string& title) const {
  for (const Field& f : impl_->cell_fields())
    if (f.name == field) {
      RenderOptions options;
      options.title = title;
      options.field_name = field;
      render_mesh(impl_->mesh, f.values, path, options);
      always("wrote {}\n", path.string());
      return;
    }
  fail("--picture-field: unknown field '{}'", field);
}

void OptimizationRun::snapshot(const std::filesystem::path& output) const {
  const Activity writing("writing " + output.string());
  const Optimizer& o = impl_->optimizer;
  impl_->mesh.write(output, o.cell_fields(), o.vertex_fields(), o.facet_groups());
}

void OptimizationRun::finish(const Result& result, const RunSettings& settings,
                             const std::filesystem::path& output, const RunOutputs& outputs,
                             const nlohmann::json& extra) {
  Impl& r = *impl_;
  // The summary lines of the report's parts, in the table's order.
  const RunRecord record{.result = result,
                         .mesh = &r.mesh,
                         .boundary_slides = settings.boundary.mode == BoundaryMode::Slide};
  for (const ReportPart& part : report_parts())
    if (part.summary)
      if (const std::string lines = part.summary(record); !lines.empty()) {
        if (part.summary_always)
          always("{}", lines);
        else
          say("{}", lines);
      }

  const double write_start = MPI_Wtime();
  snapshot(output);
  const double write_seconds = MPI_Wtime() - write_start;
  always("wrote {} ({:.2f} s)\n", output.string(), MPI_Wtime() - r.start);

  if (!outputs.report.empty()) {
    const PeakMemory memory = peak_memory(r.mesh.comm());
    const CommandLineRecord command_line{.input = r.mesh.name(),
                                         .output = output.string(),
                                         .threads = omp_get_max_threads(),
                                         .read_seconds = r.read_seconds,
                                         .prepare_seconds = r.prepare_seconds,
                                         .write_seconds = write_seconds,
                                         .peak_rss_mib = memory.max_rank_mib,
                                         .peak_rss_mib_all_ranks = memory.sum_mib,
                                         .seconds = MPI_Wtime() - r.start};
    nlohmann::json json = result_report(result, r.mesh);
    add_report_parts(json, ReportScope::CommandLine,
                     {.result = result, .command_line = &command_line});
    if (extra.is_object()) json.update(extra);
    on_root(r.mesh.comm(), [&] { write_json(json, outputs.report); });
  }
  if (!outputs.history_plot.empty())
    on_root(r.mesh.comm(), [&] {
      plot_history(
          result.history, result.initial_energy, result.initial_defect, outputs.history_plot,
          {.width = 1000, .height = 700, .title = "", .final_defect = result.final_defect});
    });
  if (!outputs.picture_after.empty())
    draw(outputs.picture_after, outputs.picture_field, "result: " + output.string());
}

}  // namespace neomesh::app
