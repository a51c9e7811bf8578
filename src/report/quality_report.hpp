// The quality of a mesh as people and programs read it: the table `quality`, `smooth` and
// `adapt` print, and the JSON of the reports; likewise the volume ratio Q of an adapted mesh.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include <neomesh/quality.hpp>

namespace neomesh {

// Cell counts, min/mean/max of each metric, inverted and degenerate cells; for a curved mesh
// also its curved cells' counts, validity and curved scaled Jacobian.
std::string format_table(const QualitySummary& summary);
nlohmann::json to_json(const QualitySummary& summary);
nlohmann::json to_json(const VolumeRatioStats& stats);

}  // namespace neomesh
