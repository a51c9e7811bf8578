// Reading Gmsh .msh files (2.2 and 4.1, ASCII and binary), on one process, into an InputMesh
// with the file's physical groups and their names.
//
// Numbering as PETSc's Gmsh reader (which neomesh used before) numbers, so outputs keep it:
// cells by polytope (tetrahedra, hexahedra, triangles, quadrilaterals), each in file order;
// vertices in the order of $Nodes, counting the nodes that are a corner of some element.
// Facet elements keep the first physical tag; point elements are not kept.
//
// $NodeData and $ElementData (ASCII and binary files) are point and cell data: named by their
// first string tag, by node and element tag; the last section of a name (the last time step) is
// kept; nodes and cells it gives no value get NaN, values of other elements are dropped.
// $ElementNodeData and $InterpolationScheme are skipped.
#pragma once

#include <filesystem>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Not collective (call it on rank 0). Second-order cells (triangle6, quadrilateral8/9,
// tetrahedron10, hexahedron20/27) are read as a curved mesh (InputMesh::high_order): their
// corners are the vertices; second-order facets of groups keep their corners. Throws Error
// naming the file for anything that is not a valid Gmsh file or that neomesh cannot use (lines
// only, second-order wedges and pyramids, third-order cells, cells of both orders, element types
// it does not read).
InputMesh read_gmsh(const std::filesystem::path& path);

}  // namespace neomesh
