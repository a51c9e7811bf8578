// Reading FEAT3 mesh files (.xml): conformal 2D/3D meshes of triangles, quadrilaterals,
// tetrahedra or hexahedra, with <MeshPart>s (vertex mappings) as named boundary parts.
//
// The format is line-based: every tag on its own line, one vertex or entity per line:
//   <FeatMeshFile version="1" mesh="conformal:hypercube:2:2">
//     <Mesh type="conformal:hypercube:2:2" size="nverts nedges [nfaces] [ncells]">
//       <Vertices> x y (z) per line </Vertices>
//       <Topology dim="k"> 0-based vertex indices per line </Topology>   (k = 1..dim)
//     </Mesh>
//     <MeshPart name="bnd:left" parent="root" topology="none" size="...">
//       <Mapping dim="0"> one vertex index per line </Mapping> ...
//     </MeshPart>
//   </FeatMeshFile>
// Quadrilaterals and hexahedra are in tensor order, simplices positively oriented: FEAT3's
// order is neomesh's canonical order. <Chart> and other blocks are skipped.
#pragma once

#include <filesystem>

#include "mesh/mesh_data.hpp"

namespace neomesh {

// Throws Error "<file>:<line>: <what is wrong>" for a file it cannot read.
MeshData read_feat(const std::filesystem::path& path);

}  // namespace neomesh
