// An open file of a C library that numbers the files it opens (Exodus II, CGNS): the owner of
// that number, which closes the file when it goes, and turns failed calls into Error naming the
// file and the library's reason.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace neomesh {

class LibraryFile {
 public:
  // The library's call that closes file `id`, and what a status its calls return says: the
  // reason of a failure, or none for success.
  using Close = int (*)(int id);
  using Failure = std::optional<std::string> (*)(int status);

  enum class Mode { Read, Create };

  // `shown` is how messages name the file (the target, when writing to a temporary file).
  LibraryFile(std::string shown, Close close, Failure failure)
      : name_(std::move(shown)), close_(close), failure_(failure) {}
  ~LibraryFile();
  LibraryFile(const LibraryFile&) = delete;
  LibraryFile& operator=(const LibraryFile&) = delete;

  int id() const { return id_; }
  const std::string& name() const { return name_; }
  // Throws Error "<file>: <what> failed (<the library's reason>)" if `status` is a failure.
  void check(int status, std::string_view what) const;
  // Closes the file (once); throws Error if that fails (a write not completed).
  void close();

 protected:
  int id_ = -1;  // set by the derived class' constructor once the file is open

 private:
  std::string name_;
  Close close_;
  Failure failure_;
};

}  // namespace neomesh
