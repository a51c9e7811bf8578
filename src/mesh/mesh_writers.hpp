// The output formats, written from a GatheredMesh on rank 0 to a stream (Exodus, CGNS: to a file).
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "mesh/gather.hpp"

namespace neomesh {

// The physical groups to write, and the tag of the cells that have none (0: they stay without).
// Gmsh saves only elements in physical groups once a file has any, and meshio requires every
// element block to have one: cells the input left without a group while its facets have
// groups (as `neomesh generate` and many .geo files make them) go into a new cell group
// "domain" with the next free tag.
struct WrittenGroups {
  std::vector<PhysicalGroup> all;  // sorted by (dim, tag)
  int untagged_cells = 0;
};
WrittenGroups physical_groups(const InputMesh& mesh);

// VTK XML UnstructuredGrid (.vtu), binary in a raw appended section (which ParaView and
// meshio read; meshio converts to ASCII for reading by eye): cell and vertex fields, plus the
// cell field "physical" when the cells carry physical groups.
void write_vtu(const GatheredMesh& mesh, std::ostream& out);

// VTK legacy ASCII (.vtk, version 4.2, UNSTRUCTURED_GRID; what Mesquite and many codes read):
// points, cells, the cell scalars "physical" when the cells carry physical groups, and the
// cell and vertex fields as FIELD data. Values in their shortest exact form, so that reading
// the file back gives the same coordinates. Facet groups are not written (the format has no
// place for them).
void write_vtk(const GatheredMesh& mesh, std::ostream& out);

// Gmsh 4.1 ASCII (.msh): cells and the boundary facets and points of physical groups, one
// entity per physical group, so that reading the file back gives the same groups.
void write_msh(const GatheredMesh& mesh, std::ostream& out);

// Medit ASCII (.mesh, MeshVersionFormatted 2): vertices, cells with their groups as
// references, and the boundary facets of facet groups (edges in 2D, triangles and
// quadrilaterals in 3D) with theirs. Group names and fields are not kept: Medit has none.
void write_medit(const GatheredMesh& mesh, std::ostream& out);

// Exodus II (.exo, .e, .ex2) through the Exodus library, to the file `path` (messages name
// `target`): coordinates (num_dim 2 for a 2D mesh in the plane z = 0), an element block per
// cell group and cell type (id: the group's tag; name: the group's), a side set per facet
// group. Fields and point groups are not written.
void write_exodus(const GatheredMesh& mesh, const std::filesystem::path& path,
                  const std::string& target);

// CGNS (.cgns, HDF5) through the CGNS library, to the file `path` (messages name `target`): one
// base with one unstructured zone, a section per cell group (MIXED where the group has cells
// of several types) named by the group, a section of facet elements and a BC (PointRange at
// FaceCenter/EdgeCenter) per facet group. Fields and point groups are not written.
void write_cgns(const GatheredMesh& mesh, const std::filesystem::path& path,
                const std::string& target);

}  // namespace neomesh
