#include "keywords.hpp"

#include <map>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include <neomesh/error.hpp>

#include "api/option_table.hpp"

namespace py = pybind11;

namespace neomesh::python {

namespace {

template <typename Options>
std::string keyword(const OptionSpec<Options>& spec) {
  std::string name(spec.flag.empty() ? spec.path.substr(spec.path.rfind('.') + 1)
                                     : spec.flag.substr(spec.flag.find_first_not_of('-')));
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

template <typename... Args>
[[noreturn]] void refuse(fmt::format_string<Args...> format, Args&&... args) {
  throw KeywordError(fmt::format(format, std::forward<Args>(args)...));
}

std::string shown(const py::handle& value) {
  return py::repr(value).cast<std::string>();
}

bool is_number(const py::handle& value) {
  return !py::isinstance<py::bool_>(value) &&
         (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
          py::hasattr(value, "__index__") || py::hasattr(value, "__float__"));
}

// `value` as the type of the field; KeywordError naming `name` for another type.
template <typename T>
T convert(const std::string& name, const py::handle& value) {
  if constexpr (std::is_same_v<T, bool>) {
    // Python's and numpy's booleans; not 0/1 or a string, which would hide a mistake.
    const std::string type = py::type::of(value).attr("__name__").cast<std::string>();
    if (type != "bool" && type != "bool_")
      refuse("{}: expected True or False (got {})", name, shown(value));
    return py::bool_(py::reinterpret_borrow<py::object>(value)).cast<bool>();
  } else if constexpr (std::is_same_v<T, int>) {
    if (py::isinstance<py::bool_>(value) || !py::hasattr(value, "__index__"))
      refuse("{}: expected an integer (got {})", name, shown(value));
    return value.cast<int>();
  } else if constexpr (std::is_same_v<T, double>) {
    if (!is_number(value)) refuse("{}: expected a number (got {})", name, shown(value));
    return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    if (value.is_none() || (py::isinstance<py::str>(value) && value.cast<std::string>() == "auto"))
      return std::nullopt;
    return convert<double>(name, value);
  } else if constexpr (std::is_same_v<T, Shapes>) {
    // {part: shape}, or "PART=SHAPE" strings as the command line's --shape takes them.
    Shapes shapes;
    const auto add = [&](const std::string& text) {
      const auto equals = text.find('=');
      if (equals == std::string::npos || equals == 0 || equals + 1 == text.size())
        refuse("{} '{}': expected PART=SHAPE, e.g. hole=circle:0,0,0.5", name, text);
      shapes.emplace_back(text.substr(0, equals), text.substr(equals + 1));
    };
    if (py::isinstance<py::dict>(value)) {
      for (auto [part, shape] : value.cast<py::dict>())
        shapes.emplace_back(py::str(part).cast<std::string>(), py::str(shape).cast<std::string>());
    } else if (py::isinstance<py::str>(value)) {
      add(value.cast<std::string>());
    } else if (py::isinstance<py::sequence>(value)) {
      for (const py::handle item : value.cast<py::sequence>()) {
        if (!py::isinstance<py::str>(item))
          refuse("{}: expected 'PART=SHAPE' strings or a dict {{part: shape}} (got {})", name,
                 shown(value));
        add(item.cast<std::string>());
      }
    } else {
      refuse("{}: expected 'PART=SHAPE' strings or a dict {{part: shape}} (got {})", name,
             shown(value));
    }
    return shapes;
  } else {
    static_assert(std::is_enum_v<T>);
    if (!py::isinstance<py::str>(value))
      refuse("{}: expected one of '{}' (got {})", name, fmt::join(choice_names<T>(), "', '"),
             shown(value));
    try {
      return parse_choice<T>(value.cast<std::string>());
    } catch (const Error& e) {
      refuse("{}: {}", name, e.what());
    }
  }
}

template <typename Options>
const OptionSpec<Options>* find(const std::string& name) {
  for (const OptionSpec<Options>& spec : task_option_table<Options>())
    if (keyword(spec) == name) return &spec;
  return nullptr;
}

// The field's type as a type hint.
template <typename Options, typename A>
std::string python_type(const A&) {
  if constexpr (std::is_same_v<A, Preset>) {
    return "bool";
  } else {
    using T = std::remove_cvref_t<std::invoke_result_t<A, Options&>>;
    if constexpr (std::is_same_v<T, bool>) return "bool";
    if constexpr (std::is_same_v<T, int>) return "int";
    if constexpr (std::is_same_v<T, double>) return "float";
    if constexpr (std::is_same_v<T, std::optional<double>>) return "float | None";
    if constexpr (std::is_same_v<T, Shapes>) return "dict[str, str] | list[str]";
    if constexpr (std::is_enum_v<T>) return "str";
    return "object";
  }
}

}  // namespace

template <typename Options>
Options keyword_options(const py::kwargs& kwargs, const char* task) {
  Options given{};
  bool thesis = false;
  std::vector<const OptionSpec<Options>*> set;
  for (auto [key, value] : kwargs) {
    const std::string name = py::str(key).cast<std::string>();
    const OptionSpec<Options>* spec = find<Options>(name);
    if (!spec) refuse("{}: no such option of {} (help(neomesh.{}) lists them)", name, task, task);
    std::visit(
        [&](const auto& access) {
          using A = std::decay_t<decltype(access)>;
          if constexpr (std::is_same_v<A, Preset>) {
            thesis = convert<bool>(name, value);
          } else {
            auto& field = access(given);
            using T = std::decay_t<decltype(field)>;
            field = convert<T>(name, value);
            if constexpr (std::is_same_v<T, bool>)
              if (spec->negated) field = !field;
          }
        },
        spec->field);
    set.push_back(spec);
  }
  Options options = given;
  if (thesis) {
    options = Options::thesis(given);
    for (const OptionSpec<Options>* spec : set) copy_field(*spec, given, options);
  }
  // A shape needs sliding vertices, and the thesis' boundary is fixed: in the keywords' words.
  if (!given.boundary.shapes.empty() && (given.boundary.mode != BoundaryMode::Slide || thesis))
    refuse("shape needs boundary='slide' (with fixed boundary vertices nothing slides on it)");
  options.validate();
  return options;
}
template SmoothOptions keyword_options(const py::kwargs&, const char*);
template AdaptOptions keyword_options(const py::kwargs&, const char*);

template <typename Options>
nlohmann::json option_list() {
  const Options defaults{}, thesis = Options::thesis();
  nlohmann::json list = nlohmann::json::array();
  for (const OptionSpec<Options>& spec : task_option_table<Options>()) {
    const bool preset = std::holds_alternative<Preset>(spec.field);
    nlohmann::json entry = {
        {"name", keyword(spec)},
        {"field", preset ? "" : std::string(spec.path)},
        {"default", preset || spec.negated ? "False" : default_text(spec, defaults)},
        {"thesis", preset                            ? ""
                   : differs(spec, defaults, thesis) ? value_text(spec, thesis)
                                                     : ""},
        {"help", std::string(spec.help)},
        {"group", std::string(spec.group)},
        {"type", std::visit([](const auto& a) { return python_type<Options>(a); }, spec.field)},
        {"choices", nlohmann::json::array()}};
    if (spec.negated && differs(spec, defaults, thesis)) entry["thesis"] = "True";
    // Python's spelling of a boolean's value.
    for (const char* key : {"default", "thesis"})
      if (entry[key] == "true" || entry[key] == "false")
        entry[key] = entry[key] == "true" ? "True" : "False";
    std::visit(
        [&](const auto& access) {
          using A = std::decay_t<decltype(access)>;
          if constexpr (!std::is_same_v<A, Preset>) {
            using T = std::remove_cvref_t<std::invoke_result_t<A, Options&>>;
            if constexpr (std::is_enum_v<T>) entry["choices"] = choice_names<T>();
          }
        },
        spec.field);
    list.push_back(entry);
  }
  return list;
}
template nlohmann::json option_list<SmoothOptions>();
template nlohmann::json option_list<AdaptOptions>();

std::string python_message(const std::string& message) {
  static const OptionNames kKeywords = reported_option_names([](const auto& spec) {
    return std::holds_alternative<Preset>(spec.field) ? std::string() : keyword(spec);
  });
  return respell_option_message(message, kKeywords);
}

}  // namespace neomesh::python
