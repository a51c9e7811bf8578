// Paths of test input files (tests/data) and scratch files for unit tests.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace neomesh::testing {

inline std::filesystem::path data_path(const std::string& name) {
  const char* dir = std::getenv("NEOMESH_TEST_DATA");
  return std::filesystem::path(dir ? dir : "tests/data") / name;
}

// A fresh, empty directory for one test's output files (per process; removed at exit).
std::filesystem::path scratch_dir(const std::string& test_name);

// The same for a test under `mpiexec`, collective over PETSC_COMM_WORLD: rank 0's scratch_dir,
// the same path on every rank (rank 0 removes it at exit).
std::filesystem::path shared_scratch_dir(const std::string& test_name);

// A file's bytes, "" if it cannot be read.
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace neomesh::testing
