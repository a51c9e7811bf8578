// Reading and writing meshes. The format follows the extension. load_mesh() reads .msh (Gmsh
// 2.2/4.1), .xml (FEAT3), .vtk, .vtu/.pvtu, .mesh (Medit), .exo/.e/.ex2 (Exodus II) and .cgns.
// write_mesh() writes .vtu (ParaView, with fields),
// .msh (Gmsh 4.1 ASCII, keeping the input's physical groups), .mesh (Medit, keeping the
// groups as references) or .exo/.e/.ex2 (Exodus II: element blocks and side sets). Every write goes
// to a temporary file beside the target, renamed over it only when complete, so a failed or
// interrupted run never leaves a partial output file. Collective: rank 0 writes.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "mesh/gather.hpp"
#include "mesh/plex_mesh.hpp"

namespace neomesh {

// Exodus II's extensions: .exo, .e, .ex2.
bool is_exodus(const std::filesystem::path& path);

// Throw Error unless neomesh reads / writes `path`'s format (check_readable_format() and
// check_writable_format() of the public API).
void require_readable_format(const std::filesystem::path& path);
void require_writable_format(const std::filesystem::path& path);

// Reads a mesh file on rank 0 and distributes it (PlexMesh::from_input). Validates the mesh
// (see validate.hpp): throws Error naming the file (and cell) for anything neomesh cannot use;
// with `keep_inverted`, inverted and degenerate cells are kept (InvertedCells::Keep).
PlexMesh load_mesh(const std::filesystem::path& path, MPI_Comm comm = PETSC_COMM_WORLD,
                   bool keep_inverted = false);
// A FEAT3 mesh file with its chart files, in any order (one path: as above). `prepare`, if
// given, changes the mesh as read on rank 0 before it is checked and distributed (`neomesh
// curve` raises its order there).
PlexMesh load_mesh(const std::vector<std::filesystem::path>& paths,
                   MPI_Comm comm = PETSC_COMM_WORLD, bool keep_inverted = false,
                   const std::function<void(InputMesh&)>& prepare = {});

void write_mesh(const PlexMesh& mesh, const std::filesystem::path& path,
                const MeshFields& fields = {});

}  // namespace neomesh
