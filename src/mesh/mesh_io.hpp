// Writing meshes. The format follows the extension: .vtu (ParaView, with fields),
// .msh (Gmsh 4.1 ASCII, keeping the input's physical groups), .mesh (Medit, keeping the
// groups as references) or .exo/.e/.ex2 (Exodus II: element blocks and side sets). Every write goes
// to a temporary file beside the target, renamed over it only when complete, so a failed or
// interrupted run never leaves a partial output file. Collective: rank 0 writes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <neomesh/field.hpp>

#include "mesh/plex_mesh.hpp"

namespace neomesh {

// What is written with a mesh: fields per local cell (MeshView order) and per local vertex
// (MeshView order; the owned vertices' values are written), facet groups (input vertex
// numbers).
struct MeshFields {
  std::vector<Field> cell;
  std::vector<Field> vertex;
  std::vector<FacetGroup> facet_groups;
};

// Exodus II's extensions: .exo, .e, .ex2.
bool is_exodus(const std::filesystem::path& path);

// Throw Error unless neomesh reads / writes `path`'s format (check_readable_format() and
// check_writable_format() of the public API).
void require_readable_format(const std::filesystem::path& path);
void require_writable_format(const std::filesystem::path& path);

void write_mesh(const PlexMesh& mesh, const std::filesystem::path& path,
                const MeshFields& fields = {});

}  // namespace neomesh
