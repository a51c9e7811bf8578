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
nlohmann::json to_json(const SolverOptions& options);
nlohmann::json to_json(const EnergyOptions& options);
// The run's iterations, stop reason, energies, defects and phase times (not its quality).
nlohmann::json to_json(const Result& result);
nlohmann::json to_json(const UntanglingSummary& untangling);
nlohmann::json to_json(const CornerPhaseSummary& phase);
nlohmann::json to_json(const QualityGuardResult& guard);

// Writes `report` (pretty-printed) atomically; rank 0 only.
void write_json(const nlohmann::json& report, const std::filesystem::path& path);

}  // namespace neomesh
