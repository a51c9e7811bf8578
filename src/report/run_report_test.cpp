#include "report/run_report.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include <neomesh/generate.hpp>
#include <neomesh/mesh.hpp>

namespace neomesh {
namespace {

std::set<std::string> keys(const nlohmann::json& object) {
  std::set<std::string> names;
  for (const auto& [key, value] : object.items()) names.insert(key);
  return names;
}

// Every top-level key of a report that has every part (an adaptation with a fit, every phase,
// from the command line) is a part of the table or an option object, and every part is in it.
TEST(ReportParts, EveryKeyOfTheReportIsDeclaredOnceInTheTable) {
  const Mesh mesh = Mesh::generate({.name = "box-tri", .size = 2});
  Result result;
  result.problem.targets.mode = "smoothed";
  result.untangling.emplace();
  result.corner_phase.emplace();
  result.ideal_retry.emplace();
  result.worst_cell_repair.emplace();
  result.quality_guard.emplace();
  result.curved.emplace();
  result.fit.emplace();
  const CommandLineRecord command_line;
  nlohmann::json report = result_report(result, mesh);
  report.update(adapt_report(AdaptOptions{}, result, "a size field"));
  add_report_parts(report, ReportScope::CommandLine,
                   {.result = result, .command_line = &command_line});

  std::set<std::string> declared = keys(to_json(AdaptOptions{}));
  for (const ReportPart& part : report_parts())
    EXPECT_TRUE(declared.insert(std::string(part.key)).second) << part.key << " twice";
  EXPECT_EQ(keys(report), declared);
}

TEST(ReportParts, AMissingPhaseIsLeftOutAndAMissingFitIsNull) {
  const Mesh mesh = Mesh::generate({.name = "box-tri", .size = 2});
  const Result result;
  const nlohmann::json report = result_report(result, mesh);
  EXPECT_FALSE(report.contains("untangling"));
  EXPECT_FALSE(report.contains("targets"));
  EXPECT_TRUE(adapt_report(AdaptOptions{}, result, "")["fit"].is_null());
}

}  // namespace
}  // namespace neomesh
