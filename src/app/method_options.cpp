#include "app/method_options.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <iostream>
#include <type_traits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/log.hpp"
#include "report/run_report.hpp"

namespace neomesh::app {

namespace {

// What --thesis sets, where it differs from the default: "--thesis: 3", "--thesis implies it";
// empty where it changes nothing.
template <typename Options>
std::string thesis_note(const OptionSpec<Options>& spec) {
  static const Options defaults{};
  static const Options thesis = Options::thesis();
  if (!differs(spec, defaults, thesis)) return "";
  if (spec.negated) return "--thesis implies it";
  return "--thesis: " + value_text(spec, thesis);
}

template <typename Options>
std::string help_text(const OptionSpec<Options>& spec) {
  const std::string note = thesis_note(spec);
  return note.empty() ? std::string(spec.help) : fmt::format("{} ({})", spec.help, note);
}

// A markdown table cell: | escaped.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

Shapes parse_shapes(const std::vector<std::string>& texts) {
  Shapes shapes;
  for (const std::string& shape : texts) {
    const auto equals = shape.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == shape.size())
      fail("--shape '{}': expected PART=SHAPE, e.g. hole=circle:0,0,0.5", shape);
    shapes.emplace_back(shape.substr(0, equals), shape.substr(equals + 1));
  }
  return shapes;
}

template <typename Options>
void TaskOptions<Options>::add(CLI::App& cmd, const OptionSpec<Options>& spec) {
  const std::string flag(spec.flag), help = help_text(spec);
  static const Options defaults{};
  CLI::Option* option = std::visit(
      [&](const auto& access) -> CLI::Option* {
        using A = std::decay_t<decltype(access)>;
        if constexpr (std::is_same_v<A, Preset>) {
          return cmd.add_flag(flag, thesis_, help);
        } else {
          auto& value = access(given_);
          using T = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<T, bool>) {
            if (!spec.negated) return cmd.add_flag(flag, value, help);
            return cmd.add_flag_function(
                flag, [&value](std::int64_t count) { value = count <= 0; }, help);
          } else if constexpr (std::is_same_v<T, Shapes>) {
            return cmd.add_option(flag, shape_texts_[spec.path], help);
          } else if constexpr (std::is_enum_v<T>) {
            return cmd
                .add_option_function<std::string>(
                    flag, [&value](const std::string& name) { value = parse_choice<T>(name); },
                    help)
                ->check(CLI::IsMember(choice_names<T>()))
                ->default_str(default_text(spec, defaults));
          } else {
            return cmd.add_option(flag, value, help)->default_str(default_text(spec, defaults));
          }
        }
      },
      spec.field);
  if (!spec.group.empty()) option->group(std::string(spec.group));
  added_.emplace_back(&spec, option);
}

template <typename Options>
void TaskOptions<Options>::add(CLI::App& cmd, std::string_view group) {
  for (const OptionSpec<Options>& spec : task_option_table<Options>())
    if (!spec.flag.empty() && spec.group == group) add(cmd, spec);
}

template <typename Options>
void TaskOptions<Options>::add_remaining(CLI::App& cmd) {
  // Hidden (group ""), and before the groups that follow so that --help ends as before.
  cmd.add_flag_callback(
         "--help-markdown",
         [] {
           if (is_root_rank()) std::cout << options_markdown<Options>();
           throw CLI::Success();
         },
         "print the table of these options in docs/user-guide.md")
      ->group("");
  cmd.add_flag_callback(
         "--report-markdown",
         [] {
           if (is_root_rank()) std::cout << report_markdown();
           throw CLI::Success();
         },
         "print the table of the report's keys in docs/user-guide.md")
      ->group("");
  for (const OptionSpec<Options>& spec : task_option_table<Options>()) {
    const bool added =
        std::any_of(added_.begin(), added_.end(), [&](const auto& a) { return a.first == &spec; });
    if (!spec.flag.empty() && !added) add(cmd, spec);
  }
}

template <typename Options>
Options TaskOptions<Options>::resolve() const {
  Options given = given_;
  for (const auto& [path, texts] : shape_texts_)
    for (const auto& [spec, option] : added_)
      if (spec->path == path)
        std::get<Access<Options, Shapes>>(spec->field)(given) = parse_shapes(texts);
  Options options = given;
  if (thesis_) {
    options = Options::thesis(given);
    for (const auto& [spec, option] : added_)
      if (option->count() > 0) copy_field(*spec, given, options);
  }
  // A shape needs sliding vertices, and --thesis' boundary is fixed: say it in the flags' words.
  if (!given.boundary.shapes.empty() && (given.boundary.mode != BoundaryMode::Slide || thesis_))
    fail("--shape needs --boundary slide (with fixed boundary vertices nothing slides on it)");
  options.validate();
  return options;
}

template <typename Options>
std::string options_markdown() {
  const Options defaults{}, thesis = Options::thesis();
  std::string table =
      "| option | field | default | `--thesis` | what it does |\n|---|---|---|---|---|\n";
  for (const OptionSpec<Options>& spec : task_option_table<Options>()) {
    const bool preset = std::holds_alternative<Preset>(spec.field);
    table += fmt::format(
        "| {} | {} | {} | {} | {} |\n", spec.flag.empty() ? "—" : fmt::format("`{}`", spec.flag),
        preset ? "—" : fmt::format("`{}`", spec.path), cell(default_text(spec, defaults)),
        preset                            ? "on"
        : differs(spec, defaults, thesis) ? cell(value_text(spec, thesis))
                                          : "",
        cell(spec.help));
  }
  return table;
}

template class TaskOptions<SmoothOptions>;
template class TaskOptions<AdaptOptions>;
template std::string options_markdown<SmoothOptions>();
template std::string options_markdown<AdaptOptions>();

std::string cli_message(const std::string& message) {
  static const OptionNames kFlags = [] {
    OptionNames flags = {{"fit", "--fit"}};
    flags.merge(reported_option_names([](const auto& spec) { return std::string(spec.flag); }));
    return flags;
  }();
  return respell_option_message(message, kFlags);
}

}  // namespace neomesh::app
