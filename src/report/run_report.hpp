// The machine-readable record of a run (`--report FILE.json`): parameters, the iteration
// history, timings per phase, the stop reason and the quality before and after.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "solver/quasi_newton.hpp"
#include "solver/untangle.hpp"

namespace neomesh {

nlohmann::json to_json(const IterationRecord& rec);
nlohmann::json to_json(const PhaseTimes& times);
nlohmann::json to_json(const QuasiNewtonOptions& options);
nlohmann::json to_json(const EnergyOptions& options);
nlohmann::json to_json(const QuasiNewtonResult& result);
nlohmann::json to_json(const UntangleResult& result);

// Writes `report` (pretty-printed) atomically; rank 0 only.
void write_json(const nlohmann::json& report, const std::filesystem::path& path);

}  // namespace neomesh
