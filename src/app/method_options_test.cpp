#include "app/method_options.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "app/subcommand.hpp"
#include "report/run_report.hpp"

namespace neomesh::app {
namespace {

std::string user_guide() {
  const char* data = std::getenv("NEOMESH_TEST_DATA");
  const std::string path = std::string(data ? data : "tests/data") + "/../../docs/user-guide.md";
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// What docs/user-guide.md has between the line that begins with `begin` and `end`.
std::string generated_text(const std::string& guide, const std::string& begin,
                           const std::string& end) {
  const auto from = guide.find(begin), to = guide.find(end);
  if (from == std::string::npos || to == std::string::npos) return "(no markers)";
  const auto start = guide.find('\n', from) + 1;
  return guide.substr(start, to - start);
}

// The generated table of `command` in docs/user-guide.md, between its markers.
std::string documented_table(const std::string& guide, const std::string& command) {
  return generated_text(guide, fmt::format("<!-- options of {}: generated", command),
                        fmt::format("<!-- end of the options of {} -->", command));
}

template <typename Options>
void expect_documented(const std::string& command) {
  EXPECT_EQ(documented_table(user_guide(), command), options_markdown<Options>())
      << "docs/user-guide.md's table of " << command
      << " options is not what src/api/option_table.cpp declares: run "
         "scripts/update_option_docs.py build/neomesh";
}

TEST(OptionDocs, TheUserGuideShowsTheTablesOfSmoothAndAdapt) {
  expect_documented<SmoothOptions>("smooth");
  expect_documented<AdaptOptions>("adapt");
}

TEST(ReportDocs, TheUserGuideShowsTheTableOfTheReportsKeys) {
  EXPECT_EQ(generated_text(user_guide(), "<!-- keys of the report: generated",
                           "<!-- end of the keys of the report -->"),
            report_markdown())
      << "docs/user-guide.md's table of the report's keys is not what src/report/run_report.cpp "
         "declares: run scripts/update_option_docs.py build/neomesh";
}

// The documented default of each row: option flag (or field path) -> default cell.
std::map<std::string, std::string> documented_defaults(const std::string& table) {
  std::map<std::string, std::string> defaults;
  std::istringstream lines(table);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> cells;
    std::size_t from = 1;
    for (std::size_t i = 1; i < line.size(); ++i)
      if (line[i] == '|' && line[i - 1] != '\\') {
        cells.push_back(line.substr(from + 1, i - from - 2));
        from = i + 1;
      }
    if (cells.size() != 5 || cells[0] == "option" || line.starts_with("|---")) continue;
    defaults[cells[1] != "—" ? cells[1] : cells[0]] = cells[2];
  }
  return defaults;
}

// A report value as the docs write it.
std::string text_of(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return std::to_string(value.get<long>());
  if (value.is_number()) return fmt::format("{:g}", value.get<double>());
  if (value.is_array() && value.empty()) return "none";
  return value.dump();
}

// Each option of the task's table is on the command line with the docs' default, in the report
// with the docs' default, and in the docs; nothing else is in the docs' table.
template <typename Options>
void expect_same_options(const std::string& command, Subcommand (*add_subcommand)(CLI::App&)) {
  CLI::App app;
  const Subcommand sub = add_subcommand(app);
  const nlohmann::json report = to_json(Options{});
  auto documented = documented_defaults(documented_table(user_guide(), command));
  std::size_t listed = 0;
  for (const OptionSpec<Options>& spec : task_option_table<Options>()) {
    const bool preset = std::holds_alternative<Preset>(spec.field);
    const std::string row = fmt::format("`{}`", preset ? spec.flag : spec.path);
    ASSERT_TRUE(documented.count(row)) << command << ": the docs do not list " << row;
    const std::string doc_default = documented[row];
    ++listed;
    if (!spec.flag.empty()) {
      const CLI::Option* option = sub.cli->get_option(std::string(spec.flag));
      ASSERT_NE(option, nullptr) << spec.flag;
      if (!option->get_default_str().empty()) {
        EXPECT_EQ(option->get_default_str(), doc_default) << command << " " << spec.flag;
      }
    }
    if (preset) continue;
    const std::string key(!spec.report_key.empty() ? spec.report_key
                                                   : spec.path.substr(spec.path.rfind('.') + 1));
    ASSERT_TRUE(report.contains(std::string(spec.report_object)) &&
                report[std::string(spec.report_object)].contains(key))
        << command << ": the report has no " << spec.report_object << "." << key;
    if (spec.shown_default.empty()) {
      EXPECT_EQ(text_of(report[std::string(spec.report_object)][key]), doc_default)
          << command << ": " << spec.path;
    }
  }
  EXPECT_EQ(listed, documented.size()) << command << ": the docs list options the table has not";
}

TEST(OptionTables, TheCommandLineTheReportAndTheDocsListTheSameOptionsAndDefaults) {
  expect_same_options<SmoothOptions>("smooth", add_smooth);
  expect_same_options<AdaptOptions>("adapt", add_adapt);
}

}  // namespace
}  // namespace neomesh::app
