#include "formats/input_file.hpp"

#include <sys/mman.h>

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <new>

#include "core/error.hpp"
#include "core/huge_pages.hpp"

namespace neomesh {

void* allocate_large(std::size_t bytes) {
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  void* p = nullptr;
  if (bytes >= 2 * kHugePage) {
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    p = std::aligned_alloc(kHugePage, rounded);
    // A hint, where the process asked glibc for huge pages too: without it, ordinary pages.
    if (p && huge_pages_asked()) madvise(p, rounded, MADV_HUGEPAGE);
  } else {
    p = std::malloc(bytes ? bytes : 1);
  }
  if (!p) throw std::bad_alloc();
  return p;
}

void free_large(void* p) noexcept {
  std::free(p);
}

void check_regular_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) fail("{}: no such file", path.string());
  if (std::filesystem::is_directory(status))
    fail("{}: is a directory, not a mesh file", path.string());
  if (!std::filesystem::is_regular_file(status))
    fail("{}: is not a regular file (a FIFO, device or socket); neomesh reads mesh files only",
         path.string());
}

InputText read_input_file(const std::filesystem::path& path) {
  check_regular_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot be opened for reading", path.string());
  // One read of the size the file system reports (a character at a time, growing the string,
  // took most of the time of reading a large mesh), then on to the end: the file may have
  // grown meanwhile.
  std::error_code ec;
  const std::uintmax_t expected = std::filesystem::file_size(path, ec);
  InputText text(ec ? 0 : static_cast<std::size_t>(expected), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in) {
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
      text.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) fail("{}: cannot be read", path.string());
  return text;
}

std::string shown_text(std::string_view text, std::size_t max) {
  std::string out(text.substr(0, max));
  for (char& c : out)
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  return text.size() > max ? out + "..." : out;
}

}  // namespace neomesh
