#include "app/optimization.hpp"

#include <mpi.h>
#include <omp.h>
#include <sys/resource.h>
#include <cstdlib>

#include "app/checks.hpp"
#include "boundary/interface.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "geometry/quality.hpp"
#include "mesh/collective_error.hpp"
#include "mesh/mesh_io.hpp"
#include "report/canvas.hpp"
#include "report/history_plot.hpp"
#include "report/iteration_table.hpp"
#include "report/render.hpp"
#include "report/run_report.hpp"

namespace neomesh::app {

void check_output_path(const std::filesystem::path& input, const std::filesystem::path& output,
                       bool force) {
  collectively(PETSC_COMM_WORLD, [&] {
    // Fail now, not after a long run.
    check_output_file("-o/--output", output.string(), OutputKind::Mesh);
    std::error_code ignored;
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

// Unless OMP_NUM_THREADS says otherwise, the ranks on a node share its cores: P ranks times
// T threads must not oversubscribe them (each rank would start one thread per core).
void share_cores(MPI_Comm comm) {
  if (std::getenv("OMP_NUM_THREADS")) return;
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks = 1;
  MPI_Comm_size(node, &ranks);
  MPI_Comm_free(&node);
  omp_set_num_threads(std::max(1, omp_get_num_procs() / ranks));
}

}  // namespace

struct OptimizationRun::Impl {
  MethodOptions& method;
  double start = MPI_Wtime();  // before the mesh is read
  double read_seconds = 0.0, prepare_seconds = 0.0;
  Mesh mesh;
  OwnedVec x;
  std::vector<double> input_volumes;
  double mesh_volume = 0.0;
  QualitySummary quality_before;
  std::unique_ptr<Boundary> boundary;
  std::unique_ptr<Functional> functional;
  OwnedVec cell_size;
  bool untangled = false;  // untangle() ran: the table names the phases
  MeshFields extra_outputs;

  Impl(const std::filesystem::path& input, MethodOptions& m, InvertedCells inverted)
      : method(m), mesh(load(input, inverted)), x(mesh.coordinates()) {
    read_seconds = MPI_Wtime() - start;
    share_cores(mesh.comm());
    const MeshView& view = mesh.view();
    const CellQuality quality = cell_quality(view, view.coords);
    quality_before = summarize(quality, mesh.comm());
    if (inverted == InvertedCells::Refuse &&
        (quality_before.inverted > 0 || quality_before.degenerate > 0))
      fail("{} has {} inverted and {} degenerate cells; `neomesh smooth` untangles them",
           input.string(), quality_before.inverted, quality_before.degenerate);
    input_volumes = quality.volume;
    double local = 0.0;
    for (double v : input_volumes) local += v;
    MPI_Allreduce(&local, &mesh_volume, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
    boundary = std::make_unique<Boundary>(view, mesh.dofs(), method.boundary_options);
    functional = std::make_unique<Functional>(view, mesh.dofs(), method.energy,
                                              boundary->fixed_dofs(), boundary->sliding_vertices());
    boundary->project(x);  // onto given shapes and charts: they pass within 1e-6 h
    method.solver.energy_roundoff = energy_roundoff(method.energy, view.dim, mesh_volume);
    prepare_seconds = MPI_Wtime() - start - read_seconds;
  }

  static Mesh load(const std::filesystem::path& input, InvertedCells inverted) {
    const int ranks = mpi_size(PETSC_COMM_WORLD);
    say("reading {}{} ...\n", input.string(),
        ranks > 1 ? fmt::format(" and distributing it over {} processes", ranks) : "");
    const Activity reading("reading " + input.string());
    return Mesh::load(input, PETSC_COMM_WORLD, inverted);
  }

  std::pair<CellQuality, QualitySummary> move_mesh_and_check();

  // At the current coordinates (view.coords and x agree before the run and after finish()).
  MeshFields output_fields() const {
    return output_fields(cell_quality(mesh.view(), mesh.view().coords));
  }

  MeshFields output_fields(const CellQuality& quality) const {
    const CellFields energy = functional->cell_fields(x);
    MeshFields fields;
    fields.cell = {
        {"energy", energy.energy},          {"det_G_min", energy.min_det},
        {"Q", energy.volume_ratio},         {"desired_volume", functional->desired_volumes()},
        {"volume", quality.volume},         {"scaled_jacobian", quality.scaled_jacobian},
        {"min_angle", quality.min_angle},   {"max_angle", quality.max_angle},
        {"edge_ratio", quality.edge_ratio}, {"inverse_mean_ratio", quality.inverse_mean_ratio}};
    fields.cell.insert(fields.cell.end(), extra_outputs.cell.begin(), extra_outputs.cell.end());
    fields.vertex = extra_outputs.vertex;
    fields.facet_groups = extra_outputs.facet_groups;
    return fields;
  }
};

OptimizationRun::OptimizationRun(const std::filesystem::path& input, MethodOptions& method,
                                 InvertedCells inverted)
    : impl_(std::make_unique<Impl>(input, method, inverted)) {}
OptimizationRun::~OptimizationRun() = default;

const MeshView& OptimizationRun::view() const {
  return impl_->mesh.view();
}
const DofMap& OptimizationRun::dofs() const {
  return impl_->mesh.dofs();
}
Vec OptimizationRun::x() const {
  return impl_->x;
}
const std::vector<double>& OptimizationRun::input_volumes() const {
  return impl_->input_volumes;
}
double OptimizationRun::mesh_volume() const {
  return impl_->mesh_volume;
}
const Functional& OptimizationRun::functional() const {
  return *impl_->functional;
}
const Functional& OptimizationRun::constrain(SlidingVertices extra) {
  Impl& r = *impl_;
  const std::vector<double> volumes = r.functional->desired_volumes();
  r.functional =
      std::make_unique<Functional>(view(), dofs(), r.method.energy, r.boundary->fixed_dofs(),
                                   join(r.boundary->sliding_vertices(), std::move(extra)));
  if (!volumes.empty()) r.functional->set_desired_volumes(volumes);
  return *r.functional;
}
void OptimizationRun::set_extra_outputs(MeshFields extra) {
  impl_->extra_outputs = std::move(extra);
}
Vec OptimizationRun::cell_size() const {
  return impl_->cell_size;
}

void OptimizationRun::set_desired_volumes(std::vector<double> volumes) {
  impl_->functional->set_desired_volumes(volumes);
  impl_->cell_size = local_cell_size(view(), dofs(), volumes);
}

namespace {

// "KSP cg, PC hypre boomeramg, rtol 0.0001, at most 10000 iterations": what PETSc will run,
// after the -hess_/-riesz_ options of the command line.
std::string describe(const LinearSolver& solver) {
  KSPType ksp_type = nullptr;
  PC pc = nullptr;
  PCType pc_type = nullptr;
  NM_PETSC(KSPGetType(solver.ksp(), &ksp_type));
  NM_PETSC(KSPGetPC(solver.ksp(), &pc));
  NM_PETSC(PCGetType(pc, &pc_type));
  std::string pc_name = pc_type ? pc_type : "none";
  if (pc_name == PCHYPRE) {
    const char* hypre = nullptr;
    NM_PETSC(PCHYPREGetType(pc, &hypre));
    pc_name += fmt::format(" {}", hypre ? hypre : "");
  } else if (pc_name == PCCHOLESKY || pc_name == PCLU) {
    MatSolverType package = nullptr;
    NM_PETSC(PCFactorGetMatSolverType(pc, &package));
    pc_name += fmt::format(" ({})", package ? package : "petsc");
  }
  double rtol = 0.0;
  PetscInt max_it = 0;
  NM_PETSC(KSPGetTolerances(solver.ksp(), &rtol, nullptr, nullptr, &max_it));
  return fmt::format("KSP {}, PC {}, rtol {:g}, at most {} iterations", ksp_type, pc_name, rtol,
                     max_it);
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
  detail(
      "  k={}: delta~ {}; s: {} Krylov iterations; step 0.5^{}; largest move {:.2e} cell "
      "sizes\n",
      rec.k, delta, rec.krylov_s, rec.armijo_steps, rec.max_move);
}

}  // namespace

void OptimizationRun::print_problem() const {
  const Mesh& mesh = impl_->mesh;
  const int ranks = mpi_size(mesh.comm());
  double free = 0.0;
  NM_PETSC(VecSum(impl_->functional->free_mask(), &free));
  say("{}: {} cells, {} vertices, {} free coordinates{}\n", mesh.source(), mesh.global_num_cells(),
      mesh.global_num_vertices(), static_cast<long>(free),
      ranks > 1 ? fmt::format(" on {} processes", ranks) : "");
  say("lambda {}, mu {}, alpha0 {}, eta {}, kmin {}, linear solver {}, boundary {}\n",
      impl_->method.energy.lambda, impl_->method.energy.mu, impl_->method.solver.alpha0,
      impl_->method.solver.eta, impl_->method.solver.kmin, name(impl_->method.solver.linear_solver),
      name(impl_->method.boundary_options.mode));
  const BoundarySummary& b = impl_->boundary->summary();
  if (impl_->method.boundary_options.mode == BoundaryMode::Slide) {
    say("sliding boundary: {} patches, {} ridges; {} corners fixed, {} ridge and {} surface "
        "vertices slide\n",
        b.patches, b.ridges, b.corners, b.ridge_vertices, b.surface_vertices);
    for (const std::string& g : b.patch_geometry) detail("  {}\n", g);
  }
  if (verbosity() == Verbosity::Verbose) {
    const QuasiNewtonOptions& o = impl_->method.solver;
    detail(
        "quasi-Newton system H(alpha) delta~ = -g (options -hess_*): {}, or residual <= {:g} "
        "x defect\n",
        describe(LinearSolver(mesh.comm(), o.linear_solver, "hess_", mesh.dim(), o.hessian_rtol)),
        o.hessian_defect_factor);
    detail(
        "Riesz representative L s = g (options -riesz_*): {}\n",
        describe(LinearSolver(mesh.comm(), o.linear_solver, "riesz_", mesh.dim(), o.riesz_rtol)));
  }
  // The first iteration assembles the matrices and builds the preconditioners: on a large
  // mesh the longest wait before the first row of the table.
  say("assembling the matrices and setting up the linear solvers ...\n");
}

std::function<void(const IterationRecord&)> OptimizationRun::table_printer(
    bool progress_only) const {
  auto header_printed = std::make_shared<bool>(false);
  // The table of a run that untangled first names each phase (round) above its rows.
  auto round = std::make_shared<int>(impl_->untangled ? -1 : 0);
  return [header_printed, round, progress_only](const IterationRecord& rec) {
    if (rec.untangling_round != *round) {
      say("{}\n", untangling_phase_line(rec));
      *round = rec.untangling_round;
    }
    if (progress_only) {
      say("{}\n", progress_line(rec));
    } else {
      if (!*header_printed) say("{}\n", iteration_table_header());
      *header_printed = true;
      say("{}\n", iteration_table_row(rec));
    }
    print_solver_details(rec);
  };
}

nlohmann::json OptimizationRun::untangle(bool progress_only) {
  Impl& r = *impl_;
  const Inversion inverted = r.functional->inversion(r.x);
  if (inverted.count == 0) return {};
  say("{} cells are inverted: untangling them first\n", inverted.count);
  r.untangled = true;
  const UntangleResult result = neomesh::untangle(*r.functional, r.x, r.method.solver, r.cell_size,
                                                  {}, table_printer(progress_only));
  if (result.after.count > 0) {
    std::string cells;
    for (PetscInt c : result.after.cells)
      cells += fmt::format("{}{}", cells.empty() ? "" : ", ", c);
    fail(
        "{}: the mesh cannot be untangled with its boundary as it is: {} of {} inverted cells are "
        "still inverted after {} iterations (cells {}{}; 0-based, in input order); nothing was "
        "written",
        r.mesh.source(), result.after.count, result.before.count, result.history.size(), cells,
        result.after.count > static_cast<PetscInt>(result.after.cells.size()) ? ", ..." : "");
  }
  say("untangled {} cells in {} iterations ({:.2f} s)\n", result.before.count,
      result.history.size(), result.seconds);
  return {{"untangling", to_json(result)}};
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
         "2D: draw the input mesh coloured by --picture-field (.png or .svg; default: none)")
      ->check(kOutputPath);
  cmd.add_option("--picture", o.picture_after,
                 "2D: draw the result coloured by --picture-field (.png or .svg; default: none)")
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

void check_run_outputs(const RunOutputs& o, int dim) {
  if (dim == 2) return;
  for (const std::string& picture : {o.picture_before, o.picture_after})
    if (!picture.empty())
      fail(
          "--picture{} {}: pictures are drawn of 2D meshes only; for this {}D mesh write a .vtu "
          "output and open it in ParaView",
          picture == o.picture_before ? "-before" : "", picture, dim);
}

void OptimizationRun::draw(const std::filesystem::path& path, const std::string& field,
                           const std::string& title) const {
  const MeshFields fields = impl_->output_fields();
  for (const Field& f : fields.cell)
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

// The mesh moved to x, its cells' quality, and their summary. The energy is infinite for an
// inverted cell, so the method cannot produce one; the check guards the promise that no
// output file ever contains one.
std::pair<CellQuality, QualitySummary> OptimizationRun::Impl::move_mesh_and_check() {
  mesh.set_coordinates(x);
  const MeshView& view = mesh.view();
  CellQuality quality = cell_quality(view, view.coords);
  const QualitySummary summary = summarize(quality, mesh.comm());
  if (summary.inverted > 0 || summary.degenerate > 0)
    fail(
        "the optimized mesh has {} inverted and {} degenerate cells; nothing was written "
        "(please report this with the input mesh)",
        summary.inverted, summary.degenerate);
  return {std::move(quality), summary};
}

QualitySummary OptimizationRun::snapshot(const std::filesystem::path& output) {
  const auto [quality, summary] = impl_->move_mesh_and_check();
  const Activity writing("writing " + output.string());
  write_mesh(impl_->mesh, output, impl_->output_fields(quality));
  return summary;
}

void OptimizationRun::finish(const QuasiNewtonResult& result, const std::filesystem::path& output,
                             const RunOutputs& outputs, const nlohmann::json& extra) {
  Impl& r = *impl_;
  const auto [quality, after] = r.move_mesh_and_check();

  always("stopped after {} iterations: {}\nF {:.6g} -> {:.6g}, Newton defect {:.3e} -> {:.3e}\n",
         result.history.size(), describe(result.reason), result.initial_energy, result.final_energy,
         result.initial_defect, result.final_defect);
  say("\nquality before:\n{}\nquality after:\n{}\n", format_table(r.quality_before),
      format_table(after));

  // How much the domain changed: zero with fixed boundary vertices; with sliding ones bounded
  // by the input's discretization (vertices stay on its facets or on the given shapes).
  double volume_after = 0.0;
  for (double v : quality.volume) volume_after += v;
  MPI_Allreduce(MPI_IN_PLACE, &volume_after, 1, MPI_DOUBLE, MPI_SUM, r.mesh.comm());
  const nlohmann::json boundary_change = {
      {"max_distance_from_input_boundary", r.boundary->max_distance_from_input(r.x)},
      {"relative_volume_change", (volume_after - r.mesh_volume) / r.mesh_volume}};
  if (r.method.boundary_options.mode == BoundaryMode::Slide)
    say("boundary: largest distance of a boundary vertex from the input's boundary {:.3g}, "
        "domain volume change {:+.3g}%\n",
        boundary_change["max_distance_from_input_boundary"].get<double>(),
        100 * boundary_change["relative_volume_change"].get<double>());

  const double write_start = MPI_Wtime();
  {
    const Activity writing("writing " + output.string());
    write_mesh(r.mesh, output, r.output_fields(quality));
  }
  const double write_seconds = MPI_Wtime() - write_start;
  always("wrote {} ({:.2f} s)\n", output.string(), MPI_Wtime() - r.start);

  if (!outputs.report.empty()) {
    double free = 0.0;
    NM_PETSC(VecSum(r.functional->free_mask(), &free));
    const PeakMemory memory = peak_memory(r.mesh.comm());
    nlohmann::json json = {
        {"input", r.mesh.source()},
        {"output", output.string()},
        {"processes", mpi_size(r.mesh.comm())},
        {"cells", r.mesh.global_num_cells()},
        {"vertices", r.mesh.global_num_vertices()},
        {"free_dofs", static_cast<std::int64_t>(free)},
        {"energy_options", to_json(r.method.energy)},
        {"solver_options", to_json(r.method.solver)},
        {"boundary", std::string(name(r.method.boundary_options.mode))},
        {"boundary_change", boundary_change},
        {"result", to_json(result)},
        {"quality_before", to_json(r.quality_before)},
        {"quality_after", to_json(after)},
        {"times",
         {{"read", r.read_seconds}, {"prepare", r.prepare_seconds}, {"write", write_seconds}}},
        {"peak_rss_mib", memory.max_rank_mib},
        {"peak_rss_mib_all_ranks", memory.sum_mib},
        {"seconds", MPI_Wtime() - r.start}};
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
