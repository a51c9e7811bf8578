// neomesh::Error (include/neomesh/error.hpp) is the one exception type users see; the command
// line prints it as `neomesh: error: <message>` and exits 1. Here: the helpers that build and
// describe errors.
#pragma once

#include <cstddef>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include <neomesh/error.hpp>

namespace neomesh {

// An Error that every rank of a communicator throws with the same message (see
// mesh/collective_error.hpp): whoever catches it knows that no rank is left waiting in a
// collective call, so a parallel run can end in order and rank 0 alone reports it.
class CollectiveError : public Error {
 public:
  using Error::Error;
};

// Throws Error with a fmt-formatted message.
template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

// `text` as it may appear inside a message: at most `max` characters, a longer text cut
// with its length said ("xxxxxxxx... (30000 characters)"), so that a pasted file or a
// runaway value cannot flood the one line of an error.
std::string shorten(std::string_view text, std::size_t max = 60);

// What a failed activity was doing, for messages about standard exceptions: "reading in.msh",
// "writing out.vtu". Scopes nest; the innermost one that an exception leaves is remembered
// (failed_activity()) until the top level has reported it.
class Activity {
 public:
  explicit Activity(std::string what);
  ~Activity();
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;

 private:
  int uncaught_ = 0;
};

// The activity the last exception left, or "" (the innermost Activity that was unwound).
const std::string& failed_activity();

// The one-line message for any exception: an Error's own message; for what the standard
// library throws (std::bad_alloc, std::length_error from a huge size, std::invalid_argument
// from stoi, ...) a sentence that says what went wrong instead of "std::bad_alloc" or "stoi",
// with the activity it interrupted if one is known. Never longer than a line.
std::string user_message(const std::exception& e);

}  // namespace neomesh
