#include "report/run_report.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include <neomesh/options.hpp>

#include "api/option_table.hpp"

#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "core/petsc.hpp"
#include "report/quality_report.hpp"

namespace neomesh {

namespace {
// The report's key of the boundary mode, besides the option objects.
constexpr std::string_view kBoundaryModeKey = "boundary";
// The option object of the Picard iteration, and what an adaptation adds to it.
constexpr std::string_view kPicardObject = "picard", kUpdateIterationsKey = "update_iterations";

// JSON has no infinity; an infinite or NaN value (which a finished run never reports,
// but a failed line search might) becomes null.
nlohmann::json number(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nullptr;
}
}  // namespace

nlohmann::json to_json(const IterationRecord& r) {
  nlohmann::json row = {{"k", r.k},
                        {"armijo_steps", r.armijo_steps},
                        {"trials", r.trials},
                        {"inadmissible_trials", r.inadmissible_trials},
                        {"defect", number(r.defect)},
                        {"direction_norm", number(r.direction_norm)},
                        {"energy", number(r.energy)},
                        {"eta", number(r.eta)},
                        {"alpha", r.alpha},
                        {"krylov_delta", r.krylov_delta},
                        {"residual_delta", number(r.residual_delta)},
                        {"delta_solved", r.delta_solved},
                        {"delta_failed", r.delta_failed},
                        {"delta_truncated", r.delta_truncated},
                        {"krylov_s", r.krylov_s},
                        {"s_solved", r.s_solved},
                        {"used_s", r.used_s},
                        {"blended", r.blended},
                        {"roundoff_step", r.roundoff_step},
                        {"hessian_pc_built", r.hessian_pc_built},
                        {"max_move", number(r.max_move)},
                        {"seconds", r.seconds}};
  if (r.untangling_round > 0)
    row.update({{"untangling_round", r.untangling_round},
                {"epsilon", r.epsilon},
                {r.lifting_flat_corners ? "nearly_flat" : "inverted", r.inverted}});
  return row;
}

nlohmann::json to_json(const UntanglingSummary& result) {
  nlohmann::json history = nlohmann::json::array();
  for (const IterationRecord& rec : result.history) history.push_back(to_json(rec));
  return {{"inverted_before", result.inverted_before},
          {"inverted_after", result.inverted_after},
          {"min_det_before", result.min_det_before},
          {"min_det_after", result.min_det_after},
          {"iterations", result.history.size()},
          {"rounds", result.rounds},
          {"seconds", result.seconds},
          {"boundary_fixed", result.boundary_fixed},
          {"equal_volumes", result.equal_volumes},
          {"history", history}};
}

nlohmann::json to_json(const PhaseTimes& t) {
  return {{"setup", t.setup},
          {"gradient", t.gradient},
          {"hessian_assembly", t.hessian_assembly},
          {"hessian_setup", t.hessian_setup},
          {"hessian_solve", t.hessian_solve},
          {"riesz_setup", t.riesz_setup},
          {"riesz_solve", t.riesz_solve},
          {"line_search", t.line_search}};
}

namespace {

// The field of `spec` in `o` as the report shows it.
template <typename Options>
nlohmann::json option_value(const OptionSpec<Options>& spec, const Options& o) {
  if (spec.reported) return spec.reported(o);
  return std::visit(
      [&](const auto& access) -> nlohmann::json {
        if constexpr (std::is_same_v<std::decay_t<decltype(access)>, Preset>) {
          return nullptr;
        } else {
          const auto& value = get(access, o);
          using T = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<T, std::optional<double>>)
            return value ? nlohmann::json(*value) : nlohmann::json("auto");
          else if constexpr (std::is_enum_v<T>)
            return std::string(name(value));
          else
            return value;
        }
      },
      spec.field);
}

template <typename Options>
nlohmann::json options_json(const OptionTable<Options>& table, const Options& o) {
  nlohmann::json report = nlohmann::json::object();
  for (const OptionSpec<Options>& spec : table) {
    if (spec.report_object.empty()) continue;  // --thesis: a preset, no value of its own
    const std::string_view key =
        !spec.report_key.empty() ? spec.report_key : spec.path.substr(spec.path.rfind('.') + 1);
    report[std::string(spec.report_object)][std::string(key)] = option_value(spec, o);
  }
  report[std::string(kBoundaryModeKey)] = std::string(name(o.boundary.mode));
  return report;
}

}  // namespace

nlohmann::json to_json(const SmoothOptions& o) {
  return options_json(smooth_option_table(), o);
}

nlohmann::json to_json(const AdaptOptions& o) {
  return options_json(adapt_option_table(), o);
}

nlohmann::json to_json(const Result& r) {
  nlohmann::json history = nlohmann::json::array();
  for (const auto& rec : r.history) history.push_back(to_json(rec));
  return {{"iterations", r.history.size()},
          {"stop_reason", describe(r.reason)},
          {"initial_energy", number(r.initial_energy)},
          {"final_energy", number(r.final_energy)},
          {"initial_defect", number(r.initial_defect)},
          {"final_defect", number(r.final_defect)},
          {"times", to_json(r.times)},
          {"history", history}};
}

nlohmann::json to_json(const WorstCellRepairSummary& repair) {
  return {{"min_scaled_jacobian_before", repair.min_scaled_jacobian_before},
          {"min_scaled_jacobian_after", repair.min_scaled_jacobian_after},
          {"vertices_moved", repair.vertices_moved},
          {"sweeps", repair.sweeps}};
}

nlohmann::json to_json(const CornerPhaseSummary& phase) {
  return {{"min_scaled_jacobian_before", phase.min_scaled_jacobian_before},
          {"min_scaled_jacobian_after", phase.min_scaled_jacobian_after},
          {"iterations", phase.iterations},
          {"gave_up", phase.gave_up}};
}

nlohmann::json to_json(const IdealRetrySummary& retry) {
  return {{"min_scaled_jacobian_kept", retry.min_scaled_jacobian_kept},
          {"min_scaled_jacobian_ideal", retry.min_scaled_jacobian_ideal},
          {"iterations", retry.iterations},
          {"ideal_kept", retry.ideal_kept}};
}

nlohmann::json to_json(const CurvedSmoothingSummary& curved) {
  return {{"cells", curved.cells},
          {"nodes", curved.nodes},
          {"min_scaled_jacobian_before", curved.min_scaled_jacobian_before},
          {"min_scaled_jacobian_optimum", curved.min_scaled_jacobian_optimum},
          {"not_valid_optimum", curved.not_valid_optimum},
          {"input_returned", curved.input_returned}};
}

nlohmann::json to_json(const QualityGuardResult& guard) {
  nlohmann::json j = {{"input_min_scaled_jacobian", guard.input_min},
                      {"min_scaled_jacobian_before", guard.min_before},
                      {"min_scaled_jacobian_after", guard.min_after},
                      {"vertices_moved", guard.vertices_moved},
                      {"gave_up", guard.gave_up},
                      {"rounds", guard.rounds},
                      {"input_mean_scaled_jacobian", guard.input_mean},
                      {"mean_scaled_jacobian_optimum", guard.mean_optimum},
                      {"input_returned", guard.input_returned}};
  if (guard.input_mean_inverse_mean_ratio)  // a surface mesh
    j.update({{"input_mean_inverse_mean_ratio", *guard.input_mean_inverse_mean_ratio},
              {"mean_inverse_mean_ratio_optimum", *guard.mean_inverse_mean_ratio_optimum}});
  return j;
}

nlohmann::json to_json(const FitSummary& f) {
  return {{"level_set", f.level_set},
          {"facets", f.facets},
          {"vertices", f.vertices},
          {"max_distance", f.max_distance},
          {"stages", f.stages},
          {"undone", f.undone},
          {"cells_moved_across", f.cells_moved_across},
          {"iterations", f.iterations}};
}

// --- The report's parts. Each entry declares one top-level key; the lines the command line
// prints of a part are worded next to it.

std::string targets_lines(const TargetSummary& t) {
  std::string lines;
  if (t.ideal_because_tangled)
    lines += "targets ideal: the input has inverted cells, its cells are no design to keep\n";
  else if (t.ideal_because_sizes)
    lines +=
        "targets ideal: --sizes uniform replaces the input's design (its cells' sizes and "
        "proportions)\n";
  else if (t.mode == "metric")
    lines += "targets metric: every cell aims at the unit cell of the metric at its centroid\n";
  else if (!t.mode.empty() && t.mode != "ideal")
    lines += fmt::format("targets {}: {} cells keep their input cell, {} in part, {} are ideal\n",
                         t.mode, t.input, t.blended, t.ideal);
  if (t.uniform_because_folded)
    lines += fmt::format(
        "sizes uniform: the input's cells cover its domain {:.3g} times, folded over itself "
        "throughout: its cell volumes are no sizes\n",
        t.coverage);
  return lines;
}

namespace {

std::optional<nlohmann::json> targets_json(const RunRecord& r) {
  const TargetSummary& targets = r.result.problem.targets;
  if (targets.mode.empty()) return std::nullopt;
  if (targets.mode == "metric")
    return nlohmann::json{{"mode", "metric"}};  // the metric's cells, none of the input's
  return nlohmann::json{{"mode", targets.mode},
                        {"cells_input", targets.input},
                        {"cells_blended", targets.blended},
                        {"cells_ideal", targets.ideal},
                        {"ideal_because_tangled", targets.ideal_because_tangled},
                        {"ideal_because_sizes", targets.ideal_because_sizes},
                        {"coverage", targets.coverage},
                        {"uniform_because_folded", targets.uniform_because_folded}};
}

}  // namespace

std::string untangled_line(const UntanglingSummary& u) {
  return fmt::format(
      "untangled {} cells in {} iterations ({:.2f} s){}{}\n", u.inverted_before, u.history.size(),
      u.seconds,
      u.boundary_fixed ? "; with the boundary sliding it stalled, so the boundary was kept fixed "
                         "while untangling"
                       : "",
      u.equal_volumes
          ? "; towards the desired volumes it stalled, so it aimed at equal cell volumes"
          : "");
}

namespace {

// The part `member` of the Result, where the run has it.
template <auto member>
std::optional<nlohmann::json> optional_part(const RunRecord& r) {
  const auto& part = r.result.*member;
  if (!part) return std::nullopt;
  return to_json(*part);
}

// What the worst-cell phase did, if it ran (docs/method.md, "Corners").
std::string corner_phase_summary(const RunRecord& r) {
  if (!r.result.corner_phase) return {};
  const CornerPhaseSummary& phase = *r.result.corner_phase;
  if (phase.gave_up)
    return fmt::format(
        "worst cells: the optimum left a corner nearly flat (min scaled Jacobian {:.3g}); lifting "
        "it failed after {} iterations, the optimum is kept\n",
        phase.min_scaled_jacobian_before, phase.iterations);
  return fmt::format(
      "worst cells: the optimum left a corner nearly flat (min scaled Jacobian {:.3g}); {} more "
      "iterations with the corners in the energy lifted it to {:.3g}\n",
      phase.min_scaled_jacobian_before, phase.iterations, phase.min_scaled_jacobian_after);
}

// What the local repair of the worst cells did, if it moved a vertex (docs/method.md, "Worst
// cells").
std::string worst_cell_repair_summary(const RunRecord& r) {
  if (!r.result.worst_cell_repair || r.result.worst_cell_repair->vertices_moved == 0) return {};
  const WorstCellRepairSummary& repair = *r.result.worst_cell_repair;
  const bool curved = r.result.curved.has_value();
  return fmt::format(
      "worst cells: {} {} moved to lift the worst cells around them (min {}scaled Jacobian "
      "{:.4f} -> {:.4f})\n",
      repair.vertices_moved, curved ? "nodes" : "interior vertices", curved ? "curved " : "",
      repair.min_scaled_jacobian_before, repair.min_scaled_jacobian_after);
}

// What the quality guard did, if anything.
std::string quality_guard_summary(const RunRecord& r) {
  if (!r.result.quality_guard) return {};
  const QualityGuardResult& guard = *r.result.quality_guard;
  std::string lines;
  if (guard.vertices_moved > 0)
    lines += fmt::format(
        "quality guard: {} vertices pulled back toward the input so that no cell has a scaled "
        "Jacobian below {:.4f} (min {:.4f} -> {:.4f})\n",
        guard.vertices_moved, guard.input_min, guard.min_before, guard.min_after);
  if (guard.input_returned &&
      guard.mean_optimum < guard.input_mean - QualityGuardResult::kMeanSlack)
    lines += fmt::format(
        "quality guard: the energy's optimum lowers the mean scaled Jacobian ({:.4f} -> {:.4f}): "
        "the input is returned instead\n",
        guard.input_mean, guard.mean_optimum);
  else if (guard.input_returned)
    lines += fmt::format(
        "quality guard: the energy's optimum raises the mean inverse mean ratio ({:.4f} -> "
        "{:.4f}): the input is returned instead\n",
        *guard.input_mean_inverse_mean_ratio, *guard.mean_inverse_mean_ratio_optimum);
  return lines;
}

// Whether smoothing towards ideal cells won, if the cells kept from the input stayed flat
// (docs/method.md, "Corners").
std::string ideal_retry_summary(const RunRecord& r) {
  if (!r.result.ideal_retry) return {};
  const IdealRetrySummary& retry = *r.result.ideal_retry;
  return fmt::format(
      "worst cells: smoothed again from the input towards ideal cells ({} iterations): min scaled "
      "Jacobian {:.4f} against {:.4f} with the cells kept from the input; the {} run is kept\n",
      retry.iterations, retry.min_scaled_jacobian_ideal, retry.min_scaled_jacobian_kept,
      retry.ideal_kept ? "ideal" : "first");
}

// What smoothing a curved mesh found, and whether it kept the optimum.
std::string curved_summary(const RunRecord& r) {
  if (!r.result.curved) return {};
  const CurvedSmoothingSummary& curved = *r.result.curved;
  std::string line = fmt::format(
      "curved cells: {} nodes of {} cells optimized; min curved scaled Jacobian {:.4f} -> {:.4f}",
      curved.nodes, curved.cells, curved.min_scaled_jacobian_before,
      curved.min_scaled_jacobian_optimum);
  if (curved.not_valid_optimum > 0)
    line += fmt::format(", {} cells not certified valid", curved.not_valid_optimum);
  if (curved.input_returned) line += ": the input is returned instead";
  return line + "\n";
}

std::string result_summary(const RunRecord& r) {
  const Result& result = r.result;
  return fmt::format(
      "stopped after {} iterations: {}\nF {:.6g} -> {:.6g}, Newton defect {:.3e} -> {:.3e}\n",
      result.history.size(), describe(result.reason), result.initial_energy, result.final_energy,
      result.initial_defect, result.final_defect);
}

// How much the domain changed: zero with fixed boundary vertices; with sliding ones bounded by
// the input's discretization (vertices stay on its facets or on the given shapes).
nlohmann::json boundary_change_json(const Result& result) {
  return {{"max_distance_from_input_boundary", result.boundary_distance},
          {"relative_volume_change", result.volume_change},
          {"moved_onto_charts", result.problem.boundary.moved_onto_charts},
          {"max_move_onto_charts", result.problem.boundary.max_move_onto_charts}};
}

std::string boundary_change_summary(const RunRecord& r) {
  if (!r.boundary_slides) return {};
  return fmt::format(
      "boundary: largest distance of a boundary vertex from the input's boundary {:.3g}, domain "
      "volume change {:+.3g}%\n",
      r.result.boundary_distance, 100 * r.result.volume_change);
}

const CommandLineRecord& cli(const RunRecord& r) {
  return *r.command_line;
}

}  // namespace

const std::vector<ReportPart>& report_parts() {
  using S = ReportScope;
  using J = std::optional<nlohmann::json>;
  static const std::vector<ReportPart> parts = {
      {"processes", S::Run, "MPI processes of the run",
       [](const RunRecord& r) -> J { return mpi_size(r.mesh->comm()); }},
      {"cells", S::Run, "cells of the mesh",
       [](const RunRecord& r) -> J { return r.mesh->num_cells(); }},
      {"vertices", S::Run, "vertices of the mesh",
       [](const RunRecord& r) -> J { return r.mesh->num_vertices(); }},
      {"free_dofs", S::Run, "coordinates the optimization moves (fixed vertices' are not)",
       [](const RunRecord& r) -> J { return r.result.problem.free_coordinates; }},
      {"targets", S::Run,
       "the cells' targets: their mode, how many cells keep their input cell, in part or not, and "
       "why they are ideal or the sizes uniform where the options asked otherwise (not for "
       "adaptation to an isotropic size field)",
       targets_json},
      {"untangling", S::Run,
       "untangling, where cells were inverted: inverted cells and the smallest det G before and "
       "after, its iterations",
       optional_part<&Result::untangling>},
      {"corner_phase", S::Run,
       "lifting corners the optimum left nearly flat, where it did: the worst such cell before "
       "and after, iterations",
       optional_part<&Result::corner_phase>, corner_phase_summary},
      {"worst_cell_repair", S::Run,
       "the local repair of the worst cells (unless switched off): the min scaled Jacobian "
       "before and after (of a curved mesh: the least curved scaled Jacobian, below −2 while a "
       "cell is not certified valid), vertices (nodes) moved, sweeps",
       optional_part<&Result::worst_cell_repair>, worst_cell_repair_summary},
      {"quality_guard", S::Run,
       "the quality guard (unless switched off; adapt: not for a metric): the threshold, vertices "
       "pulled back, the mean scaled Jacobian of the input and of the optimum, whether the input "
       "was returned",
       optional_part<&Result::quality_guard>, quality_guard_summary},
      {"ideal_retry", S::Run,
       "smoothing once more towards ideal cells, where cells kept from the input stayed flat: "
       "both runs' worst cells, which was kept",
       optional_part<&Result::ideal_retry>, ideal_retry_summary},
      {"curved", S::Run,
       "smoothing a mesh of curved cells: cells, nodes, the min curved scaled Jacobian of the "
       "input and of the optimum, cells of the optimum not certified valid, whether the input "
       "was returned",
       optional_part<&Result::curved>, curved_summary},
      {"result", S::Run,
       "the iterations: their count, the stop reason, F and the Newton defect before and after, "
       "wall time per phase, and one record per iteration (`history`)",
       [](const RunRecord& r) -> J { return to_json(r.result); }, result_summary, true},
      {"quality_before", S::Run, "the quality of the input: cell counts, min/mean/max per metric",
       [](const RunRecord& r) -> J { return to_json(r.result.quality_before); },
       [](const RunRecord& r) {
         return fmt::format("\nquality before:\n{}\n", format_table(r.result.quality_before));
       }},
      {"quality_after", S::Run, "the quality of the result, as `quality_before`",
       [](const RunRecord& r) -> J { return to_json(r.result.quality_after); },
       [](const RunRecord& r) {
         return fmt::format("quality after:\n{}\n", format_table(r.result.quality_after));
       }},
      {"boundary_change", S::Run,
       "the largest distance of a boundary vertex from the input's boundary, the relative change "
       "of the domain's volume, the vertices moved onto FEAT3 charts first",
       [](const RunRecord& r) -> J { return boundary_change_json(r.result); },
       boundary_change_summary},
      {"size_field", S::Adaptation, "the size field, described",
       [](const RunRecord& r) -> J { return std::string(r.size_field); }},
      {"volume_ratio", S::Adaptation,
       "Q = volume / desired volume at the end: its distribution over the cells",
       [](const RunRecord& r) -> J { return to_json(r.result.volume_ratio); }},
      {"fit", S::Adaptation,
       "fitting to a level set's zero set (null without): the interface, its distance from φ = "
       "0, stages, iterations",
       [](const RunRecord& r) -> J {
         return r.result.fit ? to_json(*r.result.fit) : nlohmann::json();
       }},
      {"input", S::CommandLine, "the input mesh",
       [](const RunRecord& r) -> J { return cli(r).input; }},
      {"output", S::CommandLine, "the output mesh",
       [](const RunRecord& r) -> J { return cli(r).output; }},
      {"threads", S::CommandLine, "OpenMP threads per process",
       [](const RunRecord& r) -> J { return cli(r).threads; }},
      {"times", S::CommandLine, "wall time reading, preparing and writing, seconds",
       [](const RunRecord& r) -> J {
         return nlohmann::json{{"read", cli(r).read_seconds},
                               {"prepare", cli(r).prepare_seconds},
                               {"write", cli(r).write_seconds}};
       }},
      {"peak_rss_mib", S::CommandLine, "peak resident memory of the largest process, MiB",
       [](const RunRecord& r) -> J { return cli(r).peak_rss_mib; }},
      {"peak_rss_mib_all_ranks", S::CommandLine, "peak resident memory summed over processes, MiB",
       [](const RunRecord& r) -> J { return cli(r).peak_rss_mib_all_ranks; }},
      {"seconds", S::CommandLine, "wall time of the whole run",
       [](const RunRecord& r) -> J { return cli(r).seconds; }},
  };
  return parts;
}

void add_report_parts(nlohmann::json& report, ReportScope scope, const RunRecord& record) {
  for (const ReportPart& part : report_parts())
    if (part.scope == scope)
      if (std::optional<nlohmann::json> value = part.json(record))
        report[std::string(part.key)] = std::move(*value);
}

nlohmann::json result_report(const Result& result, const Mesh& mesh) {
  nlohmann::json report = nlohmann::json::object();
  add_report_parts(report, ReportScope::Run, {.result = result, .mesh = &mesh});
  return report;
}

nlohmann::json smooth_report(const SmoothOptions& options, const Result& result) {
  SmoothOptions reported = options;
  reported.solver.advanced.alpha0 = result.problem.alpha0;
  return to_json(reported);
}

nlohmann::json adapt_report(const AdaptOptions& options, const Result& result,
                            const std::string& size_field) {
  AdaptOptions reported = options;
  reported.solver.advanced.alpha0 = result.problem.alpha0;
  reported.field.max_ratio = options.field.ratio(result.fit.has_value());
  nlohmann::json report = to_json(reported);
  report[std::string(kPicardObject)][std::string(kUpdateIterationsKey)] = result.update_iterations;
  add_report_parts(report, ReportScope::Adaptation, {.result = result, .size_field = size_field});
  return report;
}

namespace {

// "smooth, adapt" for an option object both tasks' reports have.
template <typename Options>
void add_option_objects(std::vector<std::pair<std::string, std::string>>& objects,
                        const OptionTable<Options>& table, const std::string& task) {
  const auto add = [&](std::string_view key) {
    const auto at =
        std::find_if(objects.begin(), objects.end(), [&](const auto& o) { return o.first == key; });
    if (at == objects.end())
      objects.emplace_back(key, task);
    else if (at->second.find(task) == std::string::npos)
      at->second += ", " + task;
  };
  for (const OptionSpec<Options>& spec : table)
    if (!spec.report_object.empty()) add(spec.report_object);
  add(kBoundaryModeKey);
}

}  // namespace

std::string report_markdown() {
  std::string table = "| key | written by | what it holds |\n|---|---|---|\n";
  const auto scope_text = [](ReportScope scope) {
    switch (scope) {
      case ReportScope::Run:
        return "every run";
      case ReportScope::Adaptation:
        return "adapt";
      case ReportScope::CommandLine:
        return "the command line";
    }
    return "";
  };
  for (const ReportPart& part : report_parts())
    table +=
        fmt::format("| `{}` | {} | {} |\n", part.key, scope_text(part.scope), part.description);
  std::vector<std::pair<std::string, std::string>> objects;
  add_option_objects(objects, smooth_option_table(), "smooth");
  add_option_objects(objects, adapt_option_table(), "adapt");
  for (const auto& [key, tasks] : objects) {
    std::string what = key == kBoundaryModeKey
                           ? "the boundary mode (`boundary.mode`)"
                           : "options of the tables above, under their fields' names";
    if (key == kPicardObject)
      what += fmt::format(", and `{}`: the iterations after which the desired volumes were updated",
                          kUpdateIterationsKey);
    table += fmt::format("| `{}` | {} | {} |\n", key, tasks, what);
  }
  return table;
}

void write_json(const nlohmann::json& report, const std::filesystem::path& path) {
  if (!is_root_rank()) return;
  AtomicFile file(path);
  file.stream() << report.dump(2) << '\n';
  file.commit();
}

}  // namespace neomesh
