#include "report/run_report.hpp"

#include <neomesh/options.hpp>

#include "api/option_table.hpp"

#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "core/petsc.hpp"
#include "report/quality_report.hpp"

namespace neomesh {

namespace {
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
  report["boundary"] = std::string(name(o.boundary.mode));
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

nlohmann::json to_json(const QualityGuardResult& guard) {
  return {{"input_min_scaled_jacobian", guard.input_min},
          {"min_scaled_jacobian_before", guard.min_before},
          {"min_scaled_jacobian_after", guard.min_after},
          {"vertices_moved", guard.vertices_moved},
          {"gave_up", guard.gave_up},
          {"rounds", guard.rounds},
          {"input_mean_scaled_jacobian", guard.input_mean},
          {"mean_scaled_jacobian_optimum", guard.mean_optimum},
          {"input_returned", guard.input_returned}};
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

nlohmann::json result_report(const Result& result, const Mesh& mesh) {
  // How much the domain changed: zero with fixed boundary vertices; with sliding ones bounded
  // by the input's discretization (vertices stay on its facets or on the given shapes).
  const nlohmann::json boundary_change = {
      {"max_distance_from_input_boundary", result.boundary_distance},
      {"relative_volume_change", result.volume_change},
      {"moved_onto_charts", result.problem.boundary.moved_onto_charts},
      {"max_move_onto_charts", result.problem.boundary.max_move_onto_charts}};
  nlohmann::json json = {{"processes", mpi_size(mesh.comm())},
                         {"cells", mesh.num_cells()},
                         {"vertices", mesh.num_vertices()},
                         {"free_dofs", result.problem.free_coordinates},
                         {"boundary_change", boundary_change},
                         {"result", to_json(result)},
                         {"quality_before", to_json(result.quality_before)},
                         {"quality_after", to_json(result.quality_after)}};
  const TargetSummary& targets = result.problem.targets;
  if (targets.mode == "metric")
    json["targets"] = {{"mode", "metric"}};  // the metric's cells, none of the input's
  else if (!targets.mode.empty())
    json["targets"] = {{"mode", targets.mode},
                       {"cells_input", targets.input},
                       {"cells_blended", targets.blended},
                       {"cells_ideal", targets.ideal},
                       {"ideal_because_tangled", targets.ideal_because_tangled},
                       {"ideal_because_sizes", targets.ideal_because_sizes},
                       {"coverage", targets.coverage},
                       {"uniform_because_folded", targets.uniform_because_folded}};
  if (result.untangling) json["untangling"] = to_json(*result.untangling);
  if (result.corner_phase) json["corner_phase"] = to_json(*result.corner_phase);
  if (result.ideal_retry) json["ideal_retry"] = to_json(*result.ideal_retry);
  if (result.worst_cell_repair) json["worst_cell_repair"] = to_json(*result.worst_cell_repair);
  if (result.quality_guard) json["quality_guard"] = to_json(*result.quality_guard);
  return json;
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
  reported.sizes.max_ratio = options.sizes.ratio(result.fit.has_value());
  nlohmann::json report = to_json(reported);
  report["picard"]["update_iterations"] = result.update_iterations;
  report.update({{"size_field", size_field},
                 {"volume_ratio", to_json(result.volume_ratio)},
                 {"fit", result.fit ? to_json(*result.fit) : nlohmann::json()}});
  return report;
}

void write_json(const nlohmann::json& report, const std::filesystem::path& path) {
  if (!is_root_rank()) return;
  AtomicFile file(path);
  file.stream() << report.dump(2) << '\n';
  file.commit();
}

}  // namespace neomesh
