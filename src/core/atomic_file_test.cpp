#include "core/atomic_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"

namespace neomesh {
namespace {

using testing::read_file;
using testing::scratch_dir;

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A write that ends without commit() (an exception on the way): the temporary file goes, the
// existing target keeps its old content. The interrupt's clean-up (remove_temporary_files) is
// tested by tests/cli/test_interrupt.py.
TEST(AtomicFile, UncommittedWriteLeavesTheOldTargetAndNoTemporaryFile) {
  const auto dir = scratch_dir("AtomicFile.Uncommitted");
  const auto target = dir / "out.txt";
  std::ofstream(target) << "old";
  {
    AtomicFile file(target);
    file.stream() << "new";
    file.stream().flush();
    ASSERT_TRUE(std::filesystem::exists(file.temporary_path()));
    EXPECT_EQ(file.temporary_path().parent_path(), dir);
  }
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.txt"});
  EXPECT_EQ(read_file(target), "old");
}

TEST(AtomicFile, CommitReplacesTheTarget) {
  const auto dir = scratch_dir("AtomicFile.Commit");
  const auto target = dir / "out.txt";
  std::ofstream(target) << "old";
  {
    AtomicFile file(target);
    file.stream() << "new";
    file.commit();
  }
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.txt"});
  EXPECT_EQ(read_file(target), "new");
}

TEST(AtomicFile, RefusesAMissingDirectory) {
  const auto dir = scratch_dir("AtomicFile.MissingDirectory");
  EXPECT_THROW(AtomicFile(dir / "nodir" / "out.txt"), Error);
  EXPECT_THROW(check_writable(dir / "nodir" / "out.txt"), Error);
  EXPECT_TRUE(files_in(dir).empty());
}

}  // namespace
}  // namespace neomesh
