// Output files appear complete or not at all: content is written to a temporary file
// beside the target and renamed over it only by commit(). A failed or interrupted run
// (exception, Ctrl-C) leaves no partial output; an existing target stays untouched.
#pragma once

#include <filesystem>
#include <fstream>

namespace neomesh {

// Throws Error (the same messages as AtomicFile) unless `target` could be written: its
// directory exists and a file can be created there. Lets a command fail before a long run.
void check_writable(const std::filesystem::path& target);

// Removes the temporary files of every AtomicFile not yet committed. Async-signal-safe:
// for a SIGINT/SIGTERM handler. If a commit is renaming a file right now (on another
// thread), waits for it to finish first, so that committed_targets() is then true.
void remove_temporary_files() noexcept;

// Async-signal-safe: the targets that commit() has renamed into place so far in this process,
// separated by ", " (cut after a few thousand characters), or "" if none. For an interrupt
// message that says what was, and was not, written.
const char* committed_targets() noexcept;

class AtomicFile {
 public:
  // Opens the temporary file; throws Error naming `target` if its directory is not writable.
  explicit AtomicFile(const std::filesystem::path& target, bool binary = false);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return stream_; }
  const std::filesystem::path& temporary_path() const { return temporary_; }
  // Flushes, checks for write errors and renames the temporary file onto the target.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream stream_;
  bool committed_ = false;
  int slot_ = -1;  // entry in the registry of remove_temporary_files()
};

}  // namespace neomesh
