#include "formats/mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "core/testing/thread_count.hpp"
#include "formats/mesh_test_util.hpp"
#include "generate/generate.hpp"

namespace neomesh {
namespace {

using testing::data_path;
using testing::scratch_dir;

// A Python with meshio (the system one; a virtualenv's may lack it), or "".
std::string python_with_meshio() {
  for (const char* python : {"/usr/bin/python3", "python3"})
    if (std::system(fmt::format("{} -c 'import meshio' 2>/dev/null", python).c_str()) == 0)
      return python;
  return "";
}

void expect_same_mesh(const PlexMesh& a, const PlexMesh& b) {
  const MeshView &va = a.view(), &vb = b.view();
  ASSERT_EQ(va.num_vertices, vb.num_vertices);
  ASSERT_EQ(va.blocks.size(), vb.blocks.size());
  for (std::size_t k = 0; k < va.blocks.size(); ++k) {
    ASSERT_EQ(va.blocks[k].size(), vb.blocks[k].size());
    // Same input numbering: cell c has the same vertex coordinates, in the same order.
    for (std::size_t i = 0; i < va.blocks[k].vertices.size(); ++i)
      for (int d = 0; d < va.dim; ++d)
        EXPECT_EQ(va.coords[va.blocks[k].vertices[i] * va.dim + d],
                  vb.coords[vb.blocks[k].vertices[i] * vb.dim + d]);
  }
  ASSERT_EQ(va.parts.size(), vb.parts.size());
  for (std::size_t p = 0; p < va.parts.size(); ++p) {
    EXPECT_EQ(va.parts[p].name, vb.parts[p].name);
    EXPECT_EQ(va.parts[p].tag, vb.parts[p].tag);
  }
  EXPECT_EQ(va.part_count, vb.part_count);
  EXPECT_EQ(va.on_boundary, vb.on_boundary);
}

class MshRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(MshRoundTrip, KeepsCoordinatesConnectivityAndGroups) {
  PlexMesh in = load_mesh(data_path(GetParam()));
  const auto out = scratch_dir("MshRoundTrip") / "out.msh";
  write_mesh(in, out);
  PlexMesh back = load_mesh(out);
  expect_same_mesh(in, back);
  EXPECT_GT(testing::min_view_jacobian(back.view()), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Files, MshRoundTrip,
                         ::testing::Values("square_tri_v41.msh", "square_quad_v22.msh",
                                           "cube_tet_v41.msh", "cube_hex_v41.msh",
                                           "mixed_tri_quad_v41.msh", "feat_square_quad.xml",
                                           "feat_cube_hex.xml"),
                         [](const auto& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find('.'));
                         });

TEST(WriteVtu, MeshioReadsCellsAndFields) {
  const std::string python = python_with_meshio();
  if (python.empty()) GTEST_SKIP() << "no python3 with meshio";
  PlexMesh mesh = load_mesh(data_path("mixed_tri_quad_v41.msh"));
  const MeshView& view = mesh.view();
  MeshFields fields;
  Field cell_index{"input_cell", {}, 1};
  for (PetscInt c = 0; c < view.num_cells; ++c)
    cell_index.values.push_back(static_cast<double>(view.global_cell[c]));
  fields.cell.push_back(cell_index);
  fields.vertex.push_back({"position", view.coords, 2});
  const auto out = scratch_dir("WriteVtu") / "out.vtu";
  write_mesh(mesh, out, fields);

  const std::string check = fmt::format(
      "import meshio, numpy as np\n"
      "m = meshio.read('{}')\n"
      "n = {{b.type: len(b.data) for b in m.cells}}\n"
      "assert n == {{'triangle': 14, 'quad': 4, 'line': 12}}, n\n"  // + the facet groups' lines
      "cells = [k for k, b in enumerate(m.cells) if b.type != 'line']\n"
      "c = np.concatenate([m.cell_data['input_cell'][k] for k in cells]).ravel()\n"
      "assert (np.sort(c) == np.arange(18)).all(), c\n"
      "assert np.allclose(m.point_data['position'], m.points[:, :2])\n"
      "p = lambda ks: set(np.concatenate([m.cell_data['physical'][k] for k in ks]).ravel())\n"
      "assert p(cells) == {{10, 11}}\n"
      "assert p([k for k in range(len(m.cells)) if k not in cells]) == {{1, 2, 3}}\n",
      out.string());
  const auto script = out.parent_path() / "check.py";
  std::ofstream(script) << check;
  EXPECT_EQ(std::system(fmt::format("{} {}", python, script.string()).c_str()), 0);
}

// meshio takes the arrays of a raw appended section one by one and may mistake one for
// another (vtu_writer.cpp): every field of many small meshes must come back as written.
TEST(WriteVtu, MeshioReadsEveryFieldAsWritten) {
  const std::string python = python_with_meshio();
  if (python.empty()) GTEST_SKIP() << "no python3 with meshio";
  const auto dir = scratch_dir("WriteVtuFields");
  std::string files;
  for (CellType type : {CellType::Quadrilateral, CellType::Hexahedron})
    for (int n = 1; n <= 6; ++n) {
      PlexMesh mesh = PlexMesh::from_data(box(type, n), "box");
      const MeshView& view = mesh.view();
      MeshFields fields;
      for (int k = 0; k < 10; ++k) {
        Field field{fmt::format("c{}", k), {}, 1};
        for (PetscInt c = 0; c < view.num_cells; ++c)
          field.values.push_back(1000.0 * k + static_cast<double>(view.global_cell[c]));
        fields.cell.push_back(field);
      }
      for (int k = 0; k < 2; ++k) {
        Field field{fmt::format("v{}", k), {}, 1};
        for (PetscInt v = 0; v < view.num_vertices; ++v)
          field.values.push_back(1000.0 * k + static_cast<double>(view.input_vertex[v]));
        fields.vertex.push_back(field);
      }
      const auto out = dir / fmt::format("{}-{}.vtu", name(type), n);
      write_mesh(mesh, out, fields);
      files += fmt::format("'{}', ", out.string());
    }
  const std::string check = fmt::format(
      "import meshio, numpy as np\n"
      "for f in [{}]:\n"
      "    m = meshio.read(f)\n"
      "    cells = [k for k, b in enumerate(m.cells) if b.type == m.cells[0].type]\n"
      "    for k in range(10):\n"
      "        c = np.concatenate([m.cell_data[f'c{{k}}'][j] for j in cells]).ravel()\n"
      "        assert (c == 1000 * k + np.arange(len(c))).all(), (f, k, c)\n"
      "    for k in range(2):\n"
      "        v = m.point_data[f'v{{k}}'].ravel()\n"
      "        assert (v == 1000 * k + np.arange(len(m.points))).all(), (f, k, v)\n",
      files);
  const auto script = dir / "check.py";
  std::ofstream(script) << check;
  EXPECT_EQ(std::system(fmt::format("{} {}", python, script.string()).c_str()), 0);
}

TEST(WriteMsh, GmshReadsIt) {
  if (std::system("gmsh --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "no gmsh";
  PlexMesh mesh = load_mesh(data_path("cube_hex_v41.msh"));
  const auto dir = scratch_dir("WriteMshGmsh");
  write_mesh(mesh, dir / "out.msh");
  const std::string command = fmt::format(
      "cd {} && gmsh -0 out.msh -format msh22 -o again.msh >/dev/null 2>&1", dir.string());
  ASSERT_EQ(std::system(command.c_str()), 0);
  PlexMesh again = load_mesh(dir / "again.msh");
  EXPECT_EQ(again.global_num_cells(), 8);
  EXPECT_EQ(again.view().parts.size(), 2u);
}

// The .msh writer formats its lines in chunks on every thread: a mesh of several chunks
// (2 × 16,384 lines and more) is written to the same bytes on one thread and on two, and reads
// back as written.
TEST(WriteMsh, SameBytesOnAnyNumberOfThreadsAcrossChunks) {
  PlexMesh mesh = PlexMesh::from_data(box(CellType::Quadrilateral, 200), "box");  // 40,401 vertices
  const auto dir = scratch_dir("WriteMshThreads");
  for (const int threads : {1, 2}) {
    const testing::ThreadCount count(threads);
    write_mesh(mesh, dir / (threads == 1 ? "one.msh" : "two.msh"));
  }
  const std::string one = testing::read_file(dir / "one.msh");
  EXPECT_EQ(one, testing::read_file(dir / "two.msh"));
  // The chunks' joints are exact: the last vertex, the last cell.
  EXPECT_NE(one.find("\n1 1 0\n$EndNodes\n"), std::string::npos);
  EXPECT_NE(one.find("\n40000 40199 40200 40401 40400\n"), std::string::npos);
  expect_same_mesh(mesh, load_mesh(dir / "two.msh"));
}

TEST(WriteMesh, RejectsUnknownExtension) {
  PlexMesh mesh = load_mesh(data_path("feat_square_tri.xml"));
  EXPECT_THROW(write_mesh(mesh, scratch_dir("WriteMeshExt") / "out.stl"), Error);
}

TEST(WriteMesh, MissingDirectoryIsAClearErrorAndLeavesNoFile) {
  PlexMesh mesh = load_mesh(data_path("feat_square_tri.xml"));
  const auto dir = scratch_dir("WriteMeshDir");
  try {
    write_mesh(mesh, dir / "missing" / "out.vtu");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(WriteMesh, WrongFieldSizeThrowsAndLeavesNoFile) {
  PlexMesh mesh = load_mesh(data_path("feat_square_tri.xml"));
  const auto dir = scratch_dir("WriteMeshField");
  MeshFields fields;
  fields.cell.push_back({"bad", {1.0}, 1});
  EXPECT_THROW(write_mesh(mesh, dir / "out.vtu", fields), Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace neomesh
