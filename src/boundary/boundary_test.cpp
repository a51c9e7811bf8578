#include "boundary/boundary.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "mesh/generate.hpp"
#include "mesh/serial_view.hpp"

namespace neomesh {
namespace {

// Per vertex of box(type, n) on [-1,1]^d: how many of its coordinates are ±1, i.e. how many
// box faces it lies on (0 inside, 1 on a face, 2 on an edge, d at a corner).
int box_faces(const MeshView& view, PetscInt v) {
  int faces = 0;
  for (int j = 0; j < view.dim; ++j) faces += std::abs(view.coords[v * view.dim + j]) == 1.0;
  return faces;
}

void expect_box_mask(CellType type, int n) {
  const MeshData data = box(type, n);
  const MeshView view = serial_view(data);
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  const std::vector<std::uint8_t> slide = fixed_dofs(view, dofs, BoundaryMode::Slide);
  const std::vector<std::uint8_t> fixed = fixed_dofs(view, dofs, BoundaryMode::Fixed);
  const int d = view.dim;
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const bool corner = box_faces(view, v) == d;
    for (int j = 0; j < d; ++j) {
      // Sliding fixes exactly the coordinates that are ±1: the vertex stays on its faces.
      const bool on_plane = std::abs(view.coords[v * d + j]) == 1.0;
      EXPECT_EQ(slide[v * d + j], on_plane) << "vertex " << v << " component " << j;
      EXPECT_EQ(fixed[v * d + j], box_faces(view, v) > 0) << "vertex " << v;
      if (corner) {
        EXPECT_EQ(slide[v * d + j], 1);
      }
    }
  }
}

TEST(FixedDofs, QuadAndTriangleBoxesSlideAlongTheirSides) {
  expect_box_mask(CellType::Quadrilateral, 4);
  expect_box_mask(CellType::Triangle, 3);
}

TEST(FixedDofs, HexAndTetBoxesSlideInFacesAndAlongEdges) {
  expect_box_mask(CellType::Hexahedron, 3);
  expect_box_mask(CellType::Tetrahedron, 2);
}

// The disc's boundary is curved: no boundary edge is axis-aligned, so nothing slides.
TEST(FixedDofs, CurvedBoundaryStaysFixed) {
  const MeshData data = circle_quad(2);
  const MeshView view = serial_view(data);
  const DofMap dofs = DofMap::serial(view.dim, view.num_vertices);
  const std::vector<std::uint8_t> slide = fixed_dofs(view, dofs, BoundaryMode::Slide);
  for (PetscInt v = 0; v < view.num_vertices; ++v)
    for (int j = 0; j < 2; ++j) EXPECT_EQ(slide[v * 2 + j], view.on_boundary[v]) << v;
}

TEST(BoundaryMode, ParsesItsNames) {
  EXPECT_EQ(parse_boundary_mode("fixed"), BoundaryMode::Fixed);
  EXPECT_EQ(parse_boundary_mode("slide"), BoundaryMode::Slide);
  EXPECT_EQ(name(BoundaryMode::Slide), "slide");
  EXPECT_THROW(parse_boundary_mode("free"), Error);
}

}  // namespace
}  // namespace neomesh
