// GoogleTest main for every unit-test executable: PETSc (and MPI) around the test run.
// Under `mpiexec -n P` only rank 0 prints gtest's report; every rank runs every test.
#include <gtest/gtest.h>
#include <petscsys.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "core/petsc.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  neomesh::configure_singleton_mpi();  // ctest starts a process per test: keep start-up short
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int result = RUN_ALL_TESTS();
  // A test that failed on any rank fails the run on every rank.
  int any = 0;
  MPI_Allreduce(&result, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  PetscFinalize();
  return any;
}

#include "core/testing/test_data.hpp"

namespace neomesh::testing {

namespace {

// The scratch directories of this process, removed when it ends.
struct ScratchDirs {
  std::vector<std::filesystem::path> dirs;
  ~ScratchDirs() {
    std::error_code ignored;
    for (const auto& dir : dirs) std::filesystem::remove_all(dir, ignored);
  }
};
ScratchDirs scratch_dirs;

}  // namespace

// One directory per test name and process: `ctest -j` runs every instance of a parameterized
// test as a process of its own, and they must not share (and wipe) each other's files.
std::filesystem::path scratch_dir(const std::string& test_name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("neomesh-test-" + test_name + "-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  scratch_dirs.dirs.push_back(dir);
  return dir;
}

std::filesystem::path shared_scratch_dir(const std::string& test_name) {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  std::string path = rank == 0 ? scratch_dir(test_name).string() : std::string();
  int length = static_cast<int>(path.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  path.resize(length);
  MPI_Bcast(path.data(), length, MPI_CHAR, 0, PETSC_COMM_WORLD);
  return path;
}

}  // namespace neomesh::testing
