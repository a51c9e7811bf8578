#include "core/error.hpp"

#include <filesystem>
#include <ios>
#include <new>
#include <system_error>
#include <vector>

namespace neomesh {

namespace {

// The activities in force, innermost last, and the one an exception left.
std::vector<std::string>& activities() {
  static std::vector<std::string> stack;
  return stack;
}
std::string& failed() {
  static std::string text;
  return text;
}

// A whole message longer than this is cut: it is still one readable line.
constexpr std::size_t kMaxMessage = 1000;

std::string while_doing() {
  const std::string& activity =
      !failed().empty() ? failed() : (activities().empty() ? "" : activities().back());
  return activity.empty() ? "" : " while " + activity;
}

// Standard exceptions whose what() names a function rather than a problem.
bool is_parse_failure(std::string_view what) {
  for (std::string_view f : {"stoi", "stol", "stoll", "stoul", "stoull", "stof", "stod", "stold"})
    if (what == f) return true;
  return false;
}

}  // namespace

std::string shorten(std::string_view text, std::size_t max) {
  if (text.size() <= max) return std::string(text);
  const std::string rest = fmt::format("... ({} characters)", text.size());
  const std::size_t keep = max > 2 * rest.size() ? max - rest.size() : rest.size();
  return std::string(text.substr(0, keep)) + rest;
}

Activity::Activity(std::string what) : uncaught_(std::uncaught_exceptions()) {
  activities().push_back(std::move(what));
  failed().clear();
}

Activity::~Activity() {
  // Unwound by an exception: remember the innermost activity for the message.
  if (std::uncaught_exceptions() > uncaught_ && failed().empty()) failed() = activities().back();
  activities().pop_back();
}

const std::string& failed_activity() {
  return failed();
}

std::string user_message(const std::exception& e) {
  std::string message;
  if (dynamic_cast<const Error*>(&e)) {
    message = e.what();
  } else if (dynamic_cast<const std::bad_alloc*>(&e)) {
    message = fmt::format(
        "out of memory{}: the mesh (or a size stated in the file) is too large for the memory "
        "of this machine",
        while_doing());
  } else if (dynamic_cast<const std::length_error*>(&e)) {
    message = fmt::format(
        "a size is too large{}: more items than can be held in memory (a corrupt or truncated "
        "count in the file?)",
        while_doing());
  } else if ((dynamic_cast<const std::invalid_argument*>(&e) ||
              dynamic_cast<const std::out_of_range*>(&e)) &&
             is_parse_failure(e.what())) {
    message = fmt::format("a number could not be read{}: it is not a number or out of range",
                          while_doing());
  } else if (const auto* fs = dynamic_cast<const std::filesystem::filesystem_error*>(&e)) {
    message = fs->path1().empty()
                  ? fs->code().message()
                  : fmt::format("{}: {}", fs->path1().string(), fs->code().message());
  } else if (const auto* io = dynamic_cast<const std::ios_base::failure*>(&e)) {
    message = fmt::format("input/output error{} ({})", while_doing(), io->code().message());
  } else if (const auto* sys = dynamic_cast<const std::system_error*>(&e)) {
    message = fmt::format("system error{}: {}", while_doing(), sys->code().message());
  } else {
    // A bug rather than a bad input: say so, with what the library said.
    message = fmt::format("internal error{} ({}); please report it with the command line",
                          while_doing(), shorten(e.what(), 200));
  }
  if (message.empty()) message = "unknown error";
  // One line: a newline inside a message would split it.
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  return shorten(message, kMaxMessage);
}

}  // namespace neomesh
