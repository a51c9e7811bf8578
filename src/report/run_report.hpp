// The machine-readable record of a run (`--report FILE.json`): parameters, the iteration
// history, timings per phase, the stop reason and the quality before and after.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include <neomesh/mesh.hpp>
#include <neomesh/options.hpp>
#include <neomesh/result.hpp>

namespace neomesh {

nlohmann::json to_json(const IterationRecord& rec);
nlohmann::json to_json(const PhaseTimes& times);
// The options of a run: every option of the task's table (src/api/option_table.hpp) under
// its field's name, in the object of its part ("energy_options", "solver_options",
// "boundary_options"; a smoothing's own in "smooth_options"; an adaptation's "size_options",
// "picard" and "adapt_options"), and the boundary mode as "boundary".
nlohmann::json to_json(const SmoothOptions& options);
nlohmann::json to_json(const AdaptOptions& options);
// The run's iterations, stop reason, energies, defects and phase times (not its quality).
nlohmann::json to_json(const Result& result);
nlohmann::json to_json(const UntanglingSummary& untangling);
nlohmann::json to_json(const CornerPhaseSummary& phase);
nlohmann::json to_json(const IdealRetrySummary& retry);
nlohmann::json to_json(const WorstCellRepairSummary& repair);
nlohmann::json to_json(const QualityGuardResult& guard);

nlohmann::json to_json(const FitSummary& fit);

// The part of a run's report that its Result and mesh make (the command line adds its files,
// timings and memory; Python's Result.to_dict() is this): the mesh's size, the free
// coordinates, the boundary's change, the run, the quality before and after, the targets and
// the optional phases. Collective.
nlohmann::json result_report(const Result& result, const Mesh& mesh);
// What a smoothing adds: its options as the run used them (α₀ as a number, also where it was
// "auto").
nlohmann::json smooth_report(const SmoothOptions& options, const Result& result);
// What an adaptation adds: its options as the run used them (α₀ and the volume bound as
// numbers), the Picard updates, the size field's description, Q's distribution and the fit.
nlohmann::json adapt_report(const AdaptOptions& options, const Result& result,
                            const std::string& size_field);

// Writes `report` (pretty-printed) atomically; rank 0 only.
void write_json(const nlohmann::json& report, const std::filesystem::path& path);

}  // namespace neomesh
