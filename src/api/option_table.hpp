// Every option of smooth and adapt declared once: its field path ("solver.advanced.eta"), the
// command line's flag ("--eta"), help text and group, where it lives in the option struct, and its
// range. From these tables come the structs' validate() (src/api/options.cpp), the command
// line (src/app/method_options.cpp), the JSON report's option objects
// (src/report/run_report.cpp), the re-spelling of OptionError messages with the flag, and the
// option tables of docs/user-guide.md (`neomesh smooth --help-markdown`). Defaults are never
// repeated here: they are the structs' own (include/neomesh/options.hpp), read from a
// default-constructed SmoothOptions or AdaptOptions; what --thesis changes is read from
// thesis().
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <neomesh/options.hpp>

namespace neomesh {

// BoundaryOptions::shapes: (part name, shape spec) pairs.
using Shapes = std::vector<std::pair<std::string, std::string>>;

// An entry that is no field: a flag of the command line that applies a preset (--thesis).
struct Preset {};

// Where the option's value lives in an options struct S.
template <typename S, typename T>
using Access = std::function<T&(S&)>;
template <typename S>
using FieldRef =
    std::variant<Access<S, double>, Access<S, int>, Access<S, bool>,
                 Access<S, std::optional<double>>, Access<S, BoundaryMode>,
                 Access<S, SurfaceGeometry>, Access<S, LinearSolverKind>, Access<S, RieszLaplacian>,
                 Access<S, HessianPreconditioner>, Access<S, RejectedDirection>,
                 Access<S, SizeMode>, Access<S, TargetMode>, Access<S, Shapes>, Preset>;

// The member `m` of S.
template <typename S, typename T>
FieldRef<S> member(T S::*m) {
  return Access<S, T>([m](S& s) -> T& { return s.*m; });
}

// The values an option may take: validate() throws OptionError "<path> must be <text> (got
// <value>)" for another, and for inf and nan.
struct Range {
  std::string_view text;  // empty: any value
  bool (*ok)(double) = nullptr;
};

template <typename S>
struct OptionSpec {
  std::string_view path = {};   // the field's path, as OptionError and the report name it
  std::string_view flag = {};   // the command line's spelling; empty: the library's only
  std::string_view help = {};   // one line for --help and the docs
  std::string_view group = {};  // the group of --help; empty: the subcommand's own options
  FieldRef<S> field = Preset{};
  Range range = {};
  // A flag that sets the bool field to false ("--no-practical" for solver.practical).
  bool negated = false;
  // The default's text where the field does not hold it: "auto" for an unset optional, "λ".
  std::string_view shown_default = {};
  // The report's key, where it is not the path's last part.
  std::string_view report_key = {};
  // What the report shows instead of the field (κ as the energy uses it).
  std::function<double(const S&)> reported = {};
  // The report's object of the option: "solver_options"; set by lift().
  std::string_view report_object = {};
};

template <typename S>
using OptionTable = std::vector<OptionSpec<S>>;

// The option structs' tables, in the order of --help.
const OptionTable<EnergyOptions>& energy_option_table();
const OptionTable<BoundaryOptions>& boundary_option_table();
const OptionTable<SolverOptions>& solver_option_table();
const OptionTable<SizeFieldOptions>& size_field_option_table();
const OptionTable<PicardOptions>& picard_option_table();
// A task's own options (SmoothOptions::sizes, AdaptOptions::warm_updates, ...).
const OptionTable<SmoothOptions>& smooth_own_option_table();
const OptionTable<AdaptOptions>& adapt_own_option_table();
// Every option of a task: its own, and those of its parts, with --thesis.
const OptionTable<SmoothOptions>& smooth_option_table();
const OptionTable<AdaptOptions>& adapt_option_table();
// The same, found by the task's type.
template <typename Options>
const OptionTable<Options>& task_option_table();
template <>
const OptionTable<SmoothOptions>& task_option_table<SmoothOptions>();
template <>
const OptionTable<AdaptOptions>& task_option_table<AdaptOptions>();

// The groups of --help that the subcommands place among their own options.
inline constexpr std::string_view kSizeFieldGroup = "Size field (exactly one)";
inline constexpr std::string_view kPicardGroup = "Picard iteration (thesis §6)";
inline constexpr std::string_view kTimeGroup = "A geometry that moves, and fitting the mesh to it";

// An OptionError's message begins with the option's path ("solver.advanced.eta must be ..."),
// which the command line and Python spell their own way. The paths whose errors the library
// reports — the ranged options and the fields of the parts ("boundary.shapes"; not "sizes" or
// "untangle", which begin other messages too) — of smooth and adapt, each with `name(spec)`;
// a spec whose name is empty is left out.
using OptionNames = std::map<std::string, std::string, std::less<>>;
template <typename Name>
OptionNames reported_option_names(Name name) {
  OptionNames names;
  const auto add = [&](const auto& table) {
    for (const auto& spec : table)
      if (!spec.range.text.empty() || spec.path.find('.') != std::string_view::npos)
        if (std::string spelled = name(spec); !spelled.empty())
          names.emplace(spec.path, std::move(spelled));
  };
  add(smooth_option_table());
  add(adapt_option_table());
  return names;
}
// `message` with the path it begins with spelled as `names` spells it (unchanged for another).
std::string respell_option_message(const std::string& message, const OptionNames& names);

// Throws OptionError for the first field of `table` out of its range.
template <typename S>
void check_ranges(const OptionTable<S>& table, const S& options);

// The choice called `name` (the names of choice_names<E>()); throws Error for another.
template <typename E>
E parse_choice(std::string_view name);

// The field of `spec` in `options`.
template <typename S, typename T>
const T& get(const Access<S, T>& access, const S& options) {
  return access(const_cast<S&>(options));
}

// A value as --help, the docs and the thesis notes write it: 1e-08, 64, slide, true.
template <typename T>
std::string to_text(const T& value, std::string_view unset = "auto");

// The text of the field of `spec` in `options` (the shown default where it has one and the
// field is at its default).
template <typename S>
std::string value_text(const OptionSpec<S>& spec, const S& options) {
  return std::visit(
      [&](const auto& access) -> std::string {
        if constexpr (std::is_same_v<std::decay_t<decltype(access)>, Preset>) {
          return "off";
        } else {
          const auto& value = get(access, options);
          using T = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<T, std::optional<double>>)
            return to_text(value, spec.shown_default.empty() ? "auto" : spec.shown_default);
          else
            return to_text(value);
        }
      },
      spec.field);
}

// The default's text as --help and the docs show it.
template <typename S>
std::string default_text(const OptionSpec<S>& spec, const S& defaults) {
  if (!spec.shown_default.empty()) return std::string(spec.shown_default);
  return value_text(spec, defaults);
}

// Whether the field of `spec` differs between `a` and `b`.
template <typename S>
bool differs(const OptionSpec<S>& spec, const S& a, const S& b) {
  return std::visit(
      [&](const auto& access) {
        if constexpr (std::is_same_v<std::decay_t<decltype(access)>, Preset>)
          return false;
        else
          return get(access, a) != get(access, b);
      },
      spec.field);
}

// Copies the field of `spec` from `from` to `to`.
template <typename S>
void copy_field(const OptionSpec<S>& spec, const S& from, S& to) {
  std::visit(
      [&](const auto& access) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(access)>, Preset>)
          access(to) = get(access, from);
      },
      spec.field);
}

}  // namespace neomesh
