#include "report/run_report.hpp"

#include <neomesh/options.hpp>

#include "api/option_table.hpp"

#include "core/atomic_file.hpp"
#include "core/log.hpp"

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

void write_json(const nlohmann::json& report, const std::filesystem::path& path) {
  if (!is_root_rank()) return;
  AtomicFile file(path);
  file.stream() << report.dump(2) << '\n';
  file.commit();
}

}  // namespace neomesh
