#include "mesh/gmsh_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"

namespace neomesh {
namespace {

using testing::data_path;
using testing::scratch_dir;

// The message of the Error that reading `text` as a .msh file throws ("" if none).
std::string error_reading(const std::string& text) {
  const auto path = scratch_dir("GmshReaderErrors") / "in.msh";
  std::ofstream(path) << text;
  try {
    read_gmsh(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ReadGmsh, AsciiAndBinaryOfBothVersionsAgree) {
  const InputMesh a = read_gmsh(data_path("square_tri_v22.msh"));
  for (const char* other :
       {"square_tri_v22_bin.msh", "square_tri_v41.msh", "square_tri_v41_bin.msh"}) {
    const InputMesh b = read_gmsh(data_path(other));
    ASSERT_EQ(a.coords.size(), b.coords.size()) << other;
    for (std::size_t i = 0; i < a.coords.size(); ++i)  // ASCII has 16 digits, binary all
      EXPECT_NEAR(a.coords[i], b.coords[i], 1e-15) << other;
    EXPECT_EQ(a.cell_vertices, b.cell_vertices) << other;
    EXPECT_EQ(a.cell_tags, b.cell_tags) << other;
    EXPECT_EQ(a.facets.vertices, b.facets.vertices) << other;
    EXPECT_EQ(a.facets.tags, b.facets.tags) << other;
  }
}

TEST(ReadGmsh, KeepsUsedGroupsWithTheirNames) {
  const InputMesh mesh = read_gmsh(data_path("square_quad_v41.msh"));
  ASSERT_EQ(mesh.groups.size(), 5u);
  EXPECT_EQ(mesh.groups[0].name, "bottom");
  EXPECT_EQ(mesh.groups[0].dim, 1);
  EXPECT_EQ(mesh.groups[4].tag, 10);
  EXPECT_EQ(mesh.groups[4].dim, 2);
  EXPECT_EQ(mesh.cell_tags, std::vector<int>(mesh.num_cells(), 10));
}

TEST(ReadGmsh, NumbersTrianglesBeforeQuadrilaterals) {
  const InputMesh mesh = read_gmsh(data_path("mixed_tri_quad_v41.msh"));
  ASSERT_EQ(mesh.num_cells(), 18);
  EXPECT_TRUE(std::is_sorted(mesh.cell_types.begin(), mesh.cell_types.end()));
  EXPECT_EQ(mesh.cell_types.back(), CellType::Quadrilateral);
}

TEST(ReadGmsh, RejectsOtherVersionsAndTruncatedFiles) {
  EXPECT_NE(error_reading("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n").find("Gmsh 3.0 file"),
            std::string::npos);
  EXPECT_NE(error_reading("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n")
                .find("not a valid Gmsh mesh file (the file ends inside $Nodes"),
            std::string::npos);
  EXPECT_NE(error_reading("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 x 0 0\n")
                .find("expected a number in $Nodes, found 'x'"),
            std::string::npos);
}

}  // namespace
}  // namespace neomesh
