// A surface mesh's vertices slide on the surface made of its own cells (docs/boundary.md): its
// cells play the part a volume mesh's boundary facets play, so ridges (dihedral angle above the
// feature angle), borders between cell groups and the open boundary curves are ridges, their
// vertices slide along them, and corners stay.
#include <gtest/gtest.h>

#include "boundary/boundary.hpp"
#include "boundary/features.hpp"
#include "formats/gmsh_reader.hpp"
#include "formats/surface_mesh_test_util.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {
namespace {

PlexMesh read_surface(const std::string& name, const std::string& text) {
  InputMesh input = read_gmsh(testing::write_scratch(name, text));
  return PlexMesh::from_input(input, name, PETSC_COMM_SELF);
}

TEST(SurfaceBoundary, ACubesEdgesAreRidgesAndItsCornersStay) {
  const PlexMesh mesh = read_surface("cube.msh", testing::cube_surface(3));
  const MeshView& view = mesh.view();
  const BoundaryFeatures f = find_features(*view.boundary, 40.0);
  EXPECT_EQ(f.count(VertexFeature::Corner), 8);
  EXPECT_EQ(f.count(VertexFeature::Ridge), 12 * 2);
  EXPECT_EQ(f.count(VertexFeature::Surface), 6 * 4);
  EXPECT_EQ(f.num_patches, 6);
  // The faces are axis-aligned planes: every coordinate stays exactly or moves freely.
  const Boundary boundary(view, mesh.dofs(), BoundaryOptions(BoundaryMode::Slide));
  EXPECT_TRUE(boundary.sliding_vertices().vertices.empty());
  const std::vector<std::uint8_t> fixed = boundary.fixed_dofs().flags;
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    int on_faces = 0;
    for (int j = 0; j < 3; ++j) {
      const double x = view.coords[3 * v + j];
      const bool on_face = x == 0.0 || x == 1.0;
      on_faces += on_face;
      EXPECT_EQ(fixed[3 * v + j], on_face) << v << " " << j;
    }
    EXPECT_GE(on_faces, 1) << v;
  }
}

TEST(SurfaceBoundary, OpenCurvesAndGroupBordersAreRidgesOnACurvedPatch) {
  const int n = 4;
  const PlexMesh mesh = read_surface("patch.msh", testing::cylinder_patch(n));
  const MeshView& view = mesh.view();
  const BoundaryFeatures f = find_features(*view.boundary, 40.0);
  // The patch's 4 corners and the 2 ends of the border between its groups.
  EXPECT_EQ(f.count(VertexFeature::Corner), 6);
  // Along the bottom, the top, the sides (less the border's ends) and the border.
  EXPECT_EQ(f.count(VertexFeature::Ridge), 2 * (n - 1) + 2 * (n - 2) + (n - 1));
  EXPECT_EQ(f.count(VertexFeature::Surface), (n - 1) * (n - 1) - (n - 1));
  EXPECT_EQ(f.num_patches, 2);

  // Every vertex that is no corner slides on the input's cells, and is put back on them.
  const Boundary boundary(view, mesh.dofs(), BoundaryOptions(BoundaryMode::Slide));
  const SlidingVertices sliding = boundary.sliding_vertices();
  EXPECT_EQ(static_cast<int>(sliding.vertices.size()), view.num_vertices - 6);
  OwnedVec x = mesh.coordinates();
  {
    VecWriteView out(x);  // the sliding vertices off the surface
    for (PetscInt v : sliding.vertices)
      for (int j = 0; j < 3; ++j) out[3 * v + j] += 0.01 * (j - 1);
  }
  boundary.project(x);
  EXPECT_LT(boundary.max_distance_from_input(x), 1e-14);
  VecReadView moved(x);
  for (PetscInt v : sliding.vertices) {  // on the cylinder's chords: radius within the sagitta
    const double r = std::hypot(moved[3 * v], moved[3 * v + 1]);
    EXPECT_LE(r, 1.0 + 1e-14) << v;
    EXPECT_GE(r, std::cos(std::numbers::pi / 4 / n) - 1e-14) << v;
  }
}

}  // namespace
}  // namespace neomesh
