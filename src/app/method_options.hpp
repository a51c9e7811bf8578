// The options of `smooth` and `adapt` on the command line, bound straight to the library's
// option structs (include/neomesh/options.hpp) from their tables (src/api/option_table.hpp):
// each table entry is one option of --help with its flag, help text, group and default, and
// what --thesis changes is said in its help. What the command line adds is small: --thesis
// applies the preset first and the options given explicitly win over it, and --shape
// PART=SPEC is split.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include <neomesh/error.hpp>
#include <neomesh/options.hpp>

#include "api/option_table.hpp"

namespace neomesh::app {

// The command line's options of a task: Options is SmoothOptions or AdaptOptions.
template <typename Options>
class TaskOptions {
 public:
  TaskOptions() = default;
  TaskOptions(const TaskOptions&) = delete;  // the command line holds references into it
  TaskOptions& operator=(const TaskOptions&) = delete;

  // Adds the options of the task's table in `group` ("": the subcommand's own), in the
  // table's order, so that a subcommand can place them among options of its own.
  void add(CLI::App& cmd, std::string_view group);
  // Adds the options not added yet, and the hidden --help-markdown and --report-markdown.
  void add_remaining(CLI::App& cmd);

  // The options of the command line: with --thesis its preset, then the options given
  // explicitly (or in a config file) over it; the ranges checked (OptionError).
  Options resolve() const;

 private:
  void add(CLI::App& cmd, const OptionSpec<Options>& spec);

  Options given_;  // the defaults, and what the command line wrote over them
  bool thesis_ = false;
  std::map<std::string_view, std::vector<std::string>> shape_texts_;  // --shape PART=SPEC
  std::vector<std::pair<const OptionSpec<Options>*, CLI::Option*>> added_;
};

// The task's options as a markdown table (docs/user-guide.md): option, field, default, what
// --thesis sets, help.
template <typename Options>
std::string options_markdown();

// `--shape` arguments PART=SPEC as (part, spec) pairs; throws Error for one without a part or a
// shape.
Shapes parse_shapes(const std::vector<std::string>& texts);

// A library error about an option begins with the option's field path ("solver.advanced.eta must be
// ...", "boundary.shapes: ..."): the message with the command line's spelling instead
// ("--eta must be ...", "--shape: ...").
std::string cli_message(const std::string& message);

}  // namespace neomesh::app
