// Surface meshes in the mesh layer: 2D cells whose vertices do not lie in one plane are read
// with their 3D coordinates, become a DMPlex of 2D cells in space, and give a view with 3
// coordinates per vertex whose boundary is the surface itself (docs/method.md, "Surface cells").
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"
#include "formats/gmsh_reader.hpp"
#include "formats/mesh_io.hpp"
#include "formats/surface_mesh_test_util.hpp"
#include "mesh/boundary_surface.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

using testing::cylinder_patch;
using testing::write_scratch;

TEST(SurfaceMesh, IsReadWithItsThreeCoordinatesPerVertex) {
  const InputMesh mesh = read_gmsh(write_scratch("patch.msh", cylinder_patch(4)));
  EXPECT_TRUE(mesh.surface);
  EXPECT_EQ(mesh.dim, 2);
  EXPECT_EQ(mesh.coord_dim(), 3);
  EXPECT_EQ(mesh.num_vertices(), 25);
  EXPECT_EQ(mesh.num_cells(), 4 * 2 + 12);
  EXPECT_EQ(mesh.coords[3 * 24 + 2], 1.0);  // the last vertex at z = 1, as the file says
}

TEST(SurfaceMesh, GivesAViewInSpaceWhoseBoundaryIsTheSurface) {
  InputMesh input = read_gmsh(write_scratch("patch.msh", cylinder_patch(4)));
  const std::vector<double> xyz = input.coords;
  const PlexMesh mesh = PlexMesh::from_input(input, "patch.msh", PETSC_COMM_SELF);
  const MeshView& view = mesh.view();
  EXPECT_TRUE(view.surface);
  EXPECT_EQ(view.dim, 3);
  EXPECT_EQ(view.cell_dim(), 2);
  EXPECT_EQ(mesh.dim(), 2);
  EXPECT_EQ(mesh.dofs().dim(), 3);
  ASSERT_EQ(view.num_vertices, 25);
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    EXPECT_TRUE(view.on_boundary[v]) << v;
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(view.coords[3 * v + d], xyz[3 * view.input_vertex[v] + d]) << v;
  }
  // Its parts are its cell groups, and the vertices where they meet are in both.
  ASSERT_EQ(view.parts.size(), 2u);
  EXPECT_EQ(view.parts[0].name, "low");
  EXPECT_EQ(view.parts[1].name, "high");
  int on_both = 0;
  for (PetscInt v = 0; v < view.num_vertices; ++v) on_both += view.part_count[v] == 2;
  EXPECT_EQ(on_both, 5);
  // Its boundary facets are its cells, each in its group.
  const BoundarySurface& surface = *view.boundary;
  EXPECT_EQ(surface.dim, 3);
  EXPECT_EQ(surface.num_vertices(), 25);
  ASSERT_EQ(surface.num_facets(), 20);
  EXPECT_EQ(surface.facet(0).size(), 3u);
  EXPECT_EQ(surface.facet(19).size(), 4u);
  EXPECT_EQ(surface.facet_part[0], 0);
  EXPECT_EQ(surface.facet_part[19], 1);
}

TEST(SurfaceMesh, KeepsItsCoordinatesThroughTheWriters) {
  InputMesh input = read_gmsh(write_scratch("patch.msh", cylinder_patch(4)));
  const PlexMesh mesh = PlexMesh::from_input(input, "patch.msh", PETSC_COMM_SELF);
  std::vector<std::string> names = {"out.msh", "out.vtu", "out.vtk", "out.mesh", "out.exo"};
#ifdef NEOMESH_HAS_CGNS
  names.push_back("out.cgns");
#endif
  for (const std::string& name : names) {
    const auto path = testing::scratch_dir("SurfaceMesh") / name;
    write_mesh(mesh, path);
    const PlexMesh back = load_mesh(path, PETSC_COMM_SELF);
    EXPECT_TRUE(back.view().surface) << name;
    ASSERT_EQ(back.view().coords.size(), mesh.view().coords.size()) << name;
    for (std::size_t i = 0; i < back.view().coords.size(); ++i)
      EXPECT_EQ(back.view().coords[i], mesh.view().coords[i]) << name << " " << i;
  }
}

TEST(SurfaceMesh, WithCellsOrientedApartIsRefusedNamingTheCell) {
  InputMesh input = read_gmsh(write_scratch("flipped.msh", cylinder_patch(4, true)));
  try {
    PlexMesh::from_input(input, "flipped.msh", PETSC_COMM_SELF);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("flipped.msh: its cells are not oriented alike: cell"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace neomesh
