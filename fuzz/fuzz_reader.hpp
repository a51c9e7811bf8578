// The body of a libFuzzer harness for a mesh reader: the readers take a path, so each input is
// written to a scratch file first. A neomesh::Error is the expected outcome of a bad input;
// anything else (a crash, a sanitizer report, another exception, a hang) is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"

namespace neomesh::fuzz {

template <typename Reader>
int read_input(const std::uint8_t* data, std::size_t size, const char* extension, Reader read) {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("neomesh-fuzz-" + std::to_string(::getpid()) + extension);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read(path);
  } catch (const Error&) {
  }
  return 0;
}

}  // namespace neomesh::fuzz
