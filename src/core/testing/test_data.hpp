// Paths of test input files (tests/data) and scratch files for unit tests.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace neomesh::testing {

inline std::filesystem::path data_path(const std::string& name) {
  const char* dir = std::getenv("NEOMESH_TEST_DATA");
  return std::filesystem::path(dir ? dir : "tests/data") / name;
}

// A fresh, empty directory for one test's output files (per process; removed at exit).
std::filesystem::path scratch_dir(const std::string& test_name);

}  // namespace neomesh::testing
