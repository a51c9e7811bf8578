#include "formats/gmsh_reader.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <fstream>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/feat_reader.hpp"
#include "formats/mesh_test_util.hpp"

namespace neomesh {
namespace {

using testing::data_path;

std::string error_reading(const std::string& text) {
  return testing::read_error(text, "in.msh", [](const auto& path) { read_gmsh(path); });
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
                .find("not a valid Gmsh mesh file (truncated: the file ends inside $Nodes"),
            std::string::npos);
  EXPECT_NE(error_reading("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 x 0 0\n")
                .find("expected a number in $Nodes, found 'x'"),
            std::string::npos);
}

TEST(ReadGmsh, RefusesRepeatedSectionsAndTagsOutOfRange) {
  const std::string head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  const std::string nodes = "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n";
  const std::string elements = "$Elements\n1\n1 2 2 10 10 1 2 3\n$EndElements\n";
  EXPECT_NE(error_reading(head + nodes + elements + "$Nodes\n1\n1 0 0 0\n$EndNodes\n")
                .find("it has two $Nodes sections"),
            std::string::npos);
  EXPECT_NE(error_reading(head + nodes + elements + elements).find("it has two $Elements"),
            std::string::npos);
  std::string wrapped = nodes;  // node 3 as 2^32 + 3: once read as node 3
  wrapped.replace(wrapped.find("3 0 1 0"), 1, "4294967299");
  EXPECT_NE(error_reading(head + wrapped + elements)
                .find("node tag 4294967299 in $Nodes is out of range (0..2147483647)"),
            std::string::npos);
  EXPECT_NE(error_reading(head + nodes + "$Elements\n1\n1 2 2 10 10 1 2 99999999999999999999\n")
                .find("the number '99999999999999999999' in $Elements is out of range"),
            std::string::npos);
  EXPECT_NE(error_reading(head + "$Nodes\n100000\n1 0 0 0\n$EndNodes\n")
                .find("(truncated: the file ends inside $Nodes, which announces 100000 items)"),
            std::string::npos);
}

TEST(ReadGmsh, RefusesFifosAndDevicesWithoutOpeningThem) {
  const auto fifo = testing::scratch_dir("ReadGmshFifo") / "in.msh";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);  // no writer: opening it would block forever
  for (const auto& path : {fifo, std::filesystem::path("/dev/zero")}) {
    for (bool feat : {false, true}) {
      try {
        feat ? (void)read_feat(path) : (void)read_gmsh(path);
        ADD_FAILURE() << path << " was read";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path.string() + ": is not a regular file"),
                  std::string::npos)
            << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace neomesh
