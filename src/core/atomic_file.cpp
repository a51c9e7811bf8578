#include "core/atomic_file.hpp"

#include <unistd.h>

#include "core/error.hpp"

namespace neomesh {

AtomicFile::AtomicFile(const std::filesystem::path& target, bool binary) : target_(target) {
  if (std::filesystem::is_directory(target))
    fail("cannot write {}: it is a directory", target.string());
  const auto dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir))
    fail("cannot write {}: directory {} does not exist", target.string(), dir.string());
  temporary_ = dir / fmt::format(".{}.tmp-{}", target.filename().string(), getpid());
  stream_.open(temporary_, binary ? std::ios::out | std::ios::binary : std::ios::out);
  if (!stream_)
    fail("cannot write {}: directory {} is not writable", target.string(), dir.string());
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  stream_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::commit() {
  stream_.flush();
  if (!stream_) fail("writing {} failed (disk full?)", target_.string());
  stream_.close();
  std::error_code error;
  std::filesystem::rename(temporary_, target_, error);
  if (error) fail("cannot write {}: {}", target_.string(), error.message());
  committed_ = true;
}

}  // namespace neomesh
