// The keyword arguments of neomesh.smooth and neomesh.adapt, read through the option table
// (src/api/option_table.hpp): a keyword is the command line's flag without its dashes, with
// underscores ("--feature-angle" is feature_angle=, "--no-guard" no_guard=True); an option the
// command line does not have is named by its field's last part (armijo_beta=). Defaults, ranges,
// help and the --thesis preset all come from the table, never from a list here.
#pragma once

#include <stdexcept>
#include <string>

#include <pybind11/pybind11.h>
#include <nlohmann/json.hpp>

namespace neomesh::python {

// A keyword argument neomesh cannot use (unknown, of the wrong type); raised as
// neomesh.OptionError. Its message begins with the keyword.
class KeywordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The options `kwargs` give, over the defaults (over the thesis' preset with thesis=True, as
// the command line's --thesis), validated: KeywordError or OptionError. `task`: "smooth" or
// "adapt", for messages.
template <typename Options>
Options keyword_options(const pybind11::kwargs& kwargs, const char* task);

// Every option of the task as a list of objects: name (the keyword), field, default, thesis
// (what thesis=True sets, where it differs), help, group, type, choices.
template <typename Options>
nlohmann::json option_list();

// A library message that begins with an option's field path ("solver.advanced.eta must be ...",
// "boundary.shapes: ...") with the keyword instead ("eta must be ...", "shape: ...").
std::string python_message(const std::string& message);

}  // namespace neomesh::python
