// Writing meshes. The format follows the extension: .vtu (ParaView, with fields) or
// .msh (Gmsh 4.1 ASCII, keeping the input's physical groups). Every write goes to a
// temporary file beside the target, renamed over it only when complete, so a failed or
// interrupted run never leaves a partial output file. Collective: rank 0 writes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <neomesh/mesh.hpp>

#include "mesh/plex_mesh.hpp"

namespace neomesh {

// A named field with one value per local cell (MeshView order) or per local vertex.

// Facets (edges in 2D, faces in 3D) that a .msh output lists as the physical group `name`
// (replacing an input group of that name); other formats leave them out.
struct FacetGroup {
  std::string name;
  std::vector<PetscInt> offsets = {0};
  std::vector<PetscInt> vertices;  // per facet, local vertices (MeshView order)
};

struct MeshFields {
  std::vector<Field> cell;
  std::vector<Field> vertex;
  std::vector<FacetGroup> facet_groups;
};

void write_mesh(const PlexMesh& mesh, const std::filesystem::path& path,
                const MeshFields& fields = {});

// Throws Error unless `path` has an extension neomesh can read (.msh, .xml) / write.
void check_readable_format(const std::filesystem::path& path);
void check_writable_format(const std::filesystem::path& path);

}  // namespace neomesh
