// Every input that ever crashed, hung or misread a reader (tests/data/fuzz-regressions: the
// issue's list and what fuzz/ found) is read again: each must end in a neomesh::Error, never a
// crash, a hang (ctest's timeout) or a mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "mesh/feat_reader.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/vtk_reader.hpp"

namespace neomesh {
namespace {

std::vector<std::filesystem::path> regressions() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(testing::data_path("fuzz-regressions")))
    if (entry.path().extension() == ".msh" || entry.path().extension() == ".xml" ||
        entry.path().extension() == ".vtk")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzRegressions, EveryFileIsAnErrorNamingIt) {
  const auto files = regressions();
  ASSERT_GE(files.size(), 30u);
  for (const auto& path : files) {
    try {
      if (path.extension() == ".msh")
        read_gmsh(path);
      else if (path.extension() == ".vtk")
        read_vtk(path);
      else
        read_feat(path);
      ADD_FAILURE() << path << " was read without an error";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_LT(message.size(), 400u) << message;
    }
  }
}

}  // namespace
}  // namespace neomesh
