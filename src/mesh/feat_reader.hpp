// Reading FEAT3 mesh files (.xml): conformal 2D/3D meshes of triangles, quadrilaterals,
// tetrahedra or hexahedra, with <MeshPart>s (vertex mappings) as named boundary parts and
// <Chart>s (exact boundary shapes) the parts may lie on.
//
//   <FeatMeshFile version="1" mesh="conformal:hypercube:2:2">
//     <Chart name="outer"> <Circle radius="1" midpoint="0 0" domain="0 4"/> </Chart>
//     <Mesh type="conformal:hypercube:2:2" size="nverts nedges [nfaces] [ncells]">
//       <Vertices> x y (z) per line </Vertices>
//       <Topology dim="k"> 0-based vertex indices per line </Topology>   (k = 1..dim)
//     </Mesh>
//     <MeshPart name="bnd:outer" parent="root" chart="outer" topology="none" size="...">
//       <Mapping dim="0"> one vertex index per line </Mapping> ...
//     </MeshPart>
//   </FeatMeshFile>
//
// Any XML is accepted (comments, attributes in any order, any layout, any nesting depth):
// the file is parsed by pugixml, blocks are found by name, and the numbers inside a block are
// read line by line. Quadrilaterals and hexahedra are in tensor order and simplices positively
// oriented: FEAT3's order is neomesh's canonical order (a mirrored cell, all of whose corners
// are negatively oriented, is reoriented later by validate()).
//
// Charts: <Circle radius midpoint>, <Sphere radius midpoint>, <Bezier dim="2" size type> (its
// <Points> lines "k x y [k inner control points]"; curved segments are sampled into a
// polyline) and <SurfaceMesh verts trias> (<Vertices>, <Triangles>). FEAT3's other chart types
// (Extrude, Tube, Spline, Polyline, CGALSurfaceMesh) are skipped: a part on one of them gets
// no chart. Anything else in a <Chart>, a chart missing a number, a non-finite number or a
// part naming an undeclared chart is an error.
#pragma once

#include <filesystem>

#include "mesh/mesh_data.hpp"

namespace neomesh {

// Throws Error "<file>:<line>: <what is wrong>" for a file it cannot read.
MeshData read_feat(const std::filesystem::path& path);

}  // namespace neomesh
