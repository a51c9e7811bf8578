// Reading Gmsh .msh files (2.2 and 4.1, ASCII and binary) with PETSc's reader, on one
// process, into an InputMesh with the file's physical groups and their names.
#pragma once

#include <filesystem>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Not collective (call it on rank 0). Throws Error naming the file for anything PETSc cannot
// read or neomesh cannot use (lines only, prisms, second-order elements, mixed dimensions).
InputMesh read_gmsh(const std::filesystem::path& path);

}  // namespace neomesh
