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
// <Points> lines "k [k inner control points] x y", as FEAT3 writes them), <SurfaceMesh verts
// trias> (<Vertices>, <Triangles>) and <Extrude> of a Circle or Bezier. FEAT3's other chart
// types (Tube, Spline, Polyline, CGALSurfaceMesh) are skipped: a part on one of them gets no
// chart. Charts may come from other files than the mesh (FEAT3's chart files: a
// <FeatMeshFile> with <Chart>s only), given in any order; a part whose chart none of the files
// defines is read without chart, with a notice. Anything else in a <Chart>, a chart missing a
// number or a non-finite number is an error. As FEAT3's own parser, two attributes need no
// blank between them (`chart="a"parent="root"`); chart="" means no chart.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "mesh/mesh_data.hpp"

namespace neomesh {

// One FEAT3 file as it is: a mesh file (with charts or not) or a chart file.
struct FeatFile {
  std::string path;
  bool has_mesh = false;
  MeshData data;  // the mesh and its parts (if has_mesh), the charts neomesh reads
  std::vector<std::string> skipped_charts;  // charts of a type neomesh does not read
};

// Throws Error "<file>:<line>: <what is wrong>" for a file it cannot read.
FeatFile read_feat_file(const std::filesystem::path& path);

// The mesh of the one file among `paths` that has a <Mesh>, with the charts of all of them;
// throws Error unless exactly one has a mesh, or if two files define a chart of one name.
MeshData read_feat(std::span<const std::filesystem::path> paths);
MeshData read_feat(const std::filesystem::path& path);

}  // namespace neomesh
