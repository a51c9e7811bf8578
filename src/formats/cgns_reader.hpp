// Reading CGNS files (.cgns: ANSYS, Pointwise, CGNS tools; HDF5 or ADF) on one process into an
// InputMesh, through the CGNS library.
//
// One base with one or more unstructured zones, joined into one mesh: nodes that the zones'
// 1-to-1 connectivities pair (Abutting1to1 at Vertex: PointList or PointRange with
// PointListDonor) are one vertex, or, in a file without such connectivity, nodes of different
// zones whose coordinates are equal bit for bit. The cells are the elements of the highest
// dimension (TRI_3, QUAD_4 in 2D; TETRA_4, PYRA_5, PENTA_6, HEXA_8 in 3D), from sections of one
// type or MIXED ones; each section of cells is a cell group named by the section (sections of one
// name in several zones make one group). Boundary conditions are facet groups named by their family
// (BCs of one family make one group) or else by themselves: a BC at faces (edges in 2D) names facet
// elements (PointList/PointRange with GridLocation FaceCenter/EdgeCenter,
// ElementList/ElementRange), one at vertices (the default) names vertices, whose boundary facets
// make the group. In a zone without BCs, each section's facet elements are a facet group of the
// section's name. Flow solutions at Vertex and CellCenter are point and cell data (of several
// zones, the arrays every zone has; a vertex zones share takes the first zone's value). NODE and
// BAR_2 elements of a 3D zone and other nodes are not kept.
#pragma once

#include <filesystem>

#include "mesh/input_mesh.hpp"

namespace neomesh {

// Not collective (call it on rank 0). Throws Error naming the file for anything the CGNS
// library cannot read or neomesh cannot use (structured zones, several bases,
// second-order elements, polyhedra, BCs naming elements that are not facets).
InputMesh read_cgns(const std::filesystem::path& path);

}  // namespace neomesh
