#include "mesh/input_file.hpp"

#include <fstream>
#include <iterator>

#include "core/error.hpp"

namespace neomesh {

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

std::string read_input_file(const std::filesystem::path& path) {
  check_regular_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot be opened for reading", path.string());
  // Read to the end rather than trusting the size the file system reports: the file may change
  // while we read it.
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) fail("{}: cannot be read", path.string());
  return text;
}

}  // namespace neomesh
