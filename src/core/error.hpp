// neomesh::Error — the one exception type users see. Its message is a complete sentence
// a user can act on ("in.msh: cell 1843 is inverted (det J = -0.02)"); the command line
// prints it as `neomesh: error: <message>` and exits 1.
#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace neomesh {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws Error with a fmt-formatted message.
template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace neomesh
