// Output files appear complete or not at all: content is written to a temporary file
// beside the target and renamed over it only by commit(). A failed or interrupted run
// (exception, Ctrl-C) leaves no partial output; an existing target stays untouched.
#pragma once

#include <filesystem>
#include <fstream>

namespace neomesh {

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
};

}  // namespace neomesh
