// The machine-readable record of a run (`--report FILE.json`): parameters, the iteration
// history, timings per phase, the stop reason and the quality before and after.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include <neomesh/mesh.hpp>
#include <neomesh/options.hpp>
#include <neomesh/result.hpp>

namespace neomesh {

nlohmann::json to_json(const IterationRecord& rec);
nlohmann::json to_json(const PhaseTimes& times);
// The options of a run: every option of the task's table (src/api/option_table.hpp) under
// its field's name, in the object of its part ("energy_options", "solver_options",
// "boundary_options"; a smoothing's own in "smooth_options"; an adaptation's "field_options",
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
nlohmann::json to_json(const CurvedSmoothingSummary& curved);

nlohmann::json to_json(const FitSummary& fit);

// The parts of a run's report: each top-level key of the `--report` file is declared once, in
// report_parts() (run_report.cpp), with its description, how it is written and what the
// command line prints of it. Besides them the report has the option objects of the option
// tables (to_json(SmoothOptions), to_json(AdaptOptions)).

// Which reports have a part.
enum class ReportScope {
  Run,          // every run (result_report(); Python's Result.to_dict())
  Adaptation,   // adapt (adapt_report())
  CommandLine,  // the command line's (its files, threads, wall times and memory)
};

// What the command line adds to a run's report.
struct CommandLineRecord {
  std::string input, output;
  int threads = 0;
  double read_seconds = 0.0, prepare_seconds = 0.0, write_seconds = 0.0;  // wall times
  double peak_rss_mib = 0.0, peak_rss_mib_all_ranks = 0.0;                // largest process's, sum
  double seconds = 0.0;  // the whole run's wall time
};

// What the parts are written from: the run, and what the scopes beyond it add.
struct RunRecord {
  const Result& result;
  const Mesh* mesh = nullptr;        // ReportScope::Run
  std::string_view size_field = {};  // ReportScope::Adaptation: the size field's description
  const CommandLineRecord* command_line = nullptr;  // ReportScope::CommandLine
  bool boundary_slides = false;  // the summary of the boundary's change is printed only then
};

// One top-level key of the report.
struct ReportPart {
  std::string_view key;
  ReportScope scope;
  std::string_view description;  // one line, for the docs' table
  // The part's JSON; nullopt: this run has none (the key is left out).
  std::optional<nlohmann::json> (*json)(const RunRecord&);
  // What the command line prints of it once the run is done (empty: nothing; say(), or always()
  // with `summary_always`, even with --quiet).
  std::string (*summary)(const RunRecord&) = nullptr;
  bool summary_always = false;
};

// Every part, in the order of the docs' table and of the command line's summary lines.
const std::vector<ReportPart>& report_parts();

// Writes the parts of `scope` that `record` has into `report`.
void add_report_parts(nlohmann::json& report, ReportScope scope, const RunRecord& record);

// The table of the report's keys in docs/user-guide.md (`neomesh smooth --report-markdown`):
// the parts, then the option objects of the option tables.
std::string report_markdown();

// The lines the command line prints as a run goes, worded next to their parts' entries: the
// targets when the problem is set up (empty for ideal targets asked for), and how untangling went.
std::string targets_lines(const TargetSummary& targets);
std::string untangled_line(const UntanglingSummary& untangling);

// The report's parts of ReportScope::Run (the command line adds its files, timings and memory;
// Python's Result.to_dict() is this): the mesh's size, the free coordinates, the boundary's
// change, the run, the quality before and after, the targets and the optional phases.
// Collective.
nlohmann::json result_report(const Result& result, const Mesh& mesh);
// What a smoothing adds: its options as the run used them (α₀ as a number, also where it was
// "auto").
nlohmann::json smooth_report(const SmoothOptions& options, const Result& result);
// What an adaptation adds: its options as the run used them (α₀ and the volume bound as
// numbers), the Picard updates, and the parts of ReportScope::Adaptation (the size field's
// description, Q's distribution and the fit).
nlohmann::json adapt_report(const AdaptOptions& options, const Result& result,
                            const std::string& size_field);

// Writes `report` (pretty-printed) atomically; rank 0 only.
void write_json(const nlohmann::json& report, const std::filesystem::path& path);

}  // namespace neomesh
