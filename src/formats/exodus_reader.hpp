// Reading Exodus II files (.exo, .e, .ex2: Cubit, Trelis, SEACAS, MOOSE, meshio) on one process
// into an InputMesh, through the Exodus library.
//
// The cells are the elements of the element blocks of the highest dimension: TRI/TRIANGLE/
// TRISHELL, QUAD/SHELL (2D), TETRA, HEX, WEDGE, PYRAMID (3D), linear only. Each element block is
// a cell group named by the block's name, or "block_<id>" without one; blocks of the same name
// make one group, whose tag is the first such block's id (if it is > 0; meshio numbers blocks
// from 0, and such blocks get the tags above every id). Blocks of a lower dimension (shells on
// a solid's boundary, BAR/BEAM/TRUSS lines, SPHERE points) are not kept. Side sets are facet groups
// (tag: the set's id; name: the set's, or "sideset_<id>"). Nodal and element variables (results)
// of the last time step are point and cell data ("<name>_x", "_y", "_z" next to each other
// joined into vectors; an element variable a block of cells lacks is NaN on its cells); every
// step's time and global variables and the earlier steps' nodal and element variables are
// InputMesh::steps. Node sets, attributes and maps are not kept.
#pragma once

#include <filesystem>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Not collective (call it on rank 0). Throws Error naming the file (and the block or set) for a
// file the Exodus library cannot read or neomesh cannot use (second-order elements, element
// types other than the above, side sets naming elements or sides that do not exist).
InputMesh read_exodus(const std::filesystem::path& path);

}  // namespace neomesh
