// Reading a whole input file into memory, for the readers. Only regular files: a FIFO with no
// writer would block forever and /dev/zero would never end, so both are refused before they
// are opened.
#pragma once

#include <filesystem>
#include <string>

namespace neomesh {

// Throws Error "<file>: is not a regular file" (FIFO, device, socket, directory), "... no such
// file" or "... cannot be read".
void check_regular_file(const std::filesystem::path& path);

// The file's bytes, after check_regular_file.
std::string read_input_file(const std::filesystem::path& path);

}  // namespace neomesh
