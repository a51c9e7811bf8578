// Every input that ever crashed, hung or misread a reader (tests/data/fuzz-regressions: the
// issue's list and what fuzz/ found) is read again: each must end in a neomesh::Error, never a
// crash, a hang (ctest's timeout) or a mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/feat_reader.hpp"
#include "formats/gmsh_reader.hpp"
#include "formats/medit_reader.hpp"
#include "formats/vtk_reader.hpp"
#include "formats/vtu_reader.hpp"

namespace neomesh {
namespace {

// The reader of each extension.
const std::map<std::string, std::function<void(const std::filesystem::path&)>> kReaders = {
    {".msh", [](const auto& path) { read_gmsh(path); }},
    {".xml", [](const auto& path) { read_feat(path); }},
    {".vtk", [](const auto& path) { read_vtk(path); }},
    {".vtu", [](const auto& path) { read_vtu(path); }},
    {".mesh", [](const auto& path) { read_medit(path); }}};

std::vector<std::filesystem::path> regressions() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(testing::data_path("fuzz-regressions")))
    if (kReaders.contains(entry.path().extension().string())) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzRegressions, EveryFileIsAnErrorNamingIt) {
  const auto files = regressions();
  ASSERT_GE(files.size(), 30u);
  for (const auto& path : files) {
    try {
      kReaders.at(path.extension().string())(path);
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
