// Reading Medit .mesh files (ASCII; as MMG, Gmsh, meshio and INRIA's libMeshb write them) on
// one process into an InputMesh.
//
//   MeshVersionFormatted 1|2, Dimension 2|3, Vertices (coordinates and a reference each), then
//   Edges, Triangles, Quadrilaterals, Tetrahedra, Pyramids, Prisms, Hexahedra (1-based vertex
//   numbers and a reference each), up to End. Keywords are read in any case; '#' starts a
//   comment. Corners, Ridges, Required*, Normals, Tangents and the like are skipped.
//
// The cells are the elements of the highest dimension, in file order (a type's elements in
// the place of its first section); vertices are the ones
// some cell or kept facet uses, in file order. A cell's reference is its group (the domain):
// references > 0 become cell groups, as Gmsh's physical groups do (without names: Medit has
// none). Elements one dimension lower (triangles and quadrilaterals of a 3D mesh, edges of a 2D
// one) with a reference > 0 are boundary facets in the facet group of that number; others are
// not kept. Vertex references, unless all are 0, are the point data "medit:ref" (Int32, as
// meshio names them), which the other formats carry as data. Local vertex orders are Gmsh's (which
// MMG and Gmsh use for .mesh); meshio writes prisms in VTK's order instead, which reads as inverted
// prisms.
#pragma once

#include <filesystem>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Not collective (call it on rank 0). Throws Error naming the file (and line) for anything that
// is not a valid Medit file or that neomesh cannot use (second-order elements, edges only).
InputMesh read_medit(const std::filesystem::path& path);

}  // namespace neomesh
