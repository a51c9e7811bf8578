// The machine-readable record of a run (`--report FILE.json`): parameters, the iteration
// history, timings per phase, the stop reason and the quality before and after.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

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
nlohmann::json to_json(const WorstCellRepairSummary& repair);
nlohmann::json to_json(const QualityGuardResult& guard);

// Writes `report` (pretty-printed) atomically; rank 0 only.
void write_json(const nlohmann::json& report, const std::filesystem::path& path);

}  // namespace neomesh
