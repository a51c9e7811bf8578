// The features of a mesh's boundary (docs/boundary.md): where it bends sharply or where two
// boundary parts (physical groups) meet. They split the boundary into patches that vertices
// slide within:
// - 2D: a corner is a boundary vertex where the boundary turns by more than the feature angle,
//   where two parts meet, or where other than two boundary edges meet; the edges between
//   corners form the patches (curves).
// - 3D: a ridge edge is a boundary edge whose two facets' normals differ by more than the
//   feature angle, whose facets are in different parts, or that has other than two facets;
//   the facets between ridges form the patches (surfaces). A vertex on no ridge edge is a
//   surface vertex; on two ridge edges that continue each other (turning by less than the
//   feature angle, between the same two patches), a ridge vertex; otherwise a corner.
// Computed from the whole input boundary, identically on every rank.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <petscsys.h>

#include "boundary/shape.hpp"
#include "mesh/boundary_surface.hpp"

namespace neomesh {

// Boundary vertex b of the surface as a point (z = 0 in 2D).
inline Point surface_point(const BoundarySurface& s, PetscInt b) {
  Point p = Point::Zero();
  for (int j = 0; j < s.dim; ++j) p[j] = s.coords[b * s.dim + j];
  return p;
}

// Facet f's normal scaled by its size, in its vertex order: an edge's perpendicular (2D,
// length = edge length), Newell's sum for a polygon (3D, length = twice the area).
Point facet_area_normal(const BoundarySurface& s, PetscInt f);

enum class VertexFeature : std::uint8_t { Surface, Ridge, Corner };

struct BoundaryFeatures {
  // Per boundary vertex (BoundarySurface numbering).
  std::vector<VertexFeature> kind;
  std::vector<int> patch;  // Surface vertices: their patch; else -1
  std::vector<int> ridge;  // Ridge vertices: their ridge; else -1
  // Per facet: its patch.
  std::vector<int> facet_patch;
  int num_patches = 0;
  // Per patch: the part (MeshView::parts index) of its facets, or -1.
  std::vector<int> patch_part;
  // Per ridge (3D): its edges (pairs of boundary vertices) and the two patches it separates.
  std::vector<std::vector<std::array<PetscInt, 2>>> ridge_edges;
  std::vector<std::array<int, 2>> ridge_patches;

  PetscInt count(VertexFeature k) const;
};

// `smooth_part` (per MeshView::parts entry, may be empty): 1 for a part on one smooth shape or
// chart (circle, sphere, plane, ...). Such a part is one patch: its facets are never split by
// the feature angle (the coarse facets of a sphere meet at large angles, but there is no ridge
// between a surface and itself). With `folds` (a surface mesh's cells), a facet folded over the
// surface around it (geometry/surface_orientation.hpp) is seen with its normal reversed, so that
// the edges of a fold are no ridges.
BoundaryFeatures find_features(const BoundarySurface& surface, double feature_angle_degrees,
                               std::span<const std::uint8_t> smooth_part = {}, bool folds = false);

}  // namespace neomesh
