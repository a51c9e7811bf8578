#include "formats/library_file.hpp"

#include "core/error.hpp"

namespace neomesh {

LibraryFile::~LibraryFile() {
  if (id_ >= 0) close_(id_);
}

void LibraryFile::check(int status, std::string_view what) const {
  if (const auto reason = failure_(status)) fail("{}: {} failed ({})", name_, what, *reason);
}

void LibraryFile::close() {
  if (id_ < 0) return;
  const int status = close_(id_);
  id_ = -1;
  check(status, "closing the file");
}

}  // namespace neomesh
