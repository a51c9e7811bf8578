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

// The elements of a VTK file (.vtu, .vtk) of a mesh: its cells in input order, then the facets
// of its facet groups (lines, triangles, quadrilaterals; a curved mesh's at second order, as its
// cells) and the points of its point groups (vertices), as meshio writes Gmsh's groups. The cells
// of a curved mesh list their points (InputMesh::num_points) in VTK's order, as Lagrange cells
// (`lagrange`; the serendipity quadrilateral8 and hexahedron20 have none: quadratic cells) or
// quadratic cells. `tags`: each element's physical tag (0: none), written as the cell data
// "physical" when `has_tags`.
struct VtkElements {
  std::vector<std::uint8_t> types;
  std::vector<std::int64_t> offsets;  // where each element's points end in `connectivity`
  std::vector<std::int64_t> connectivity;
  std::vector<std::int32_t> tags;
  bool has_tags = false;
  std::size_t size() const { return types.size(); }
};
VtkElements vtk_elements(const GatheredMesh& mesh, bool lagrange);

// Cell data `values` (per cell) for every element: facets and points get `fill`.
std::vector<double> per_element(const std::vector<double>& values, int components, double fill,
                                std::size_t elements);

// VTK XML UnstructuredGrid (.vtu), binary in a raw appended section (which ParaView and
// meshio read; meshio converts to ASCII for reading by eye). Elements as VtkElements (curved
// cells as Lagrange cells, which ParaView draws curved); point
// data: the input's, then the vertex fields; cell data: the input's (in their types), then the
// cell fields (NaN for facets and points, 0 in integer arrays), then "physical". Field data: an
// Int32 array [tag, dimension] per named group, named by the group.
void write_vtu(const GatheredMesh& mesh, std::ostream& out);

// VTK legacy ASCII (.vtk, version 4.2, UNSTRUCTURED_GRID; what Mesquite and many codes read):
// points, elements as VtkElements (curved cells as quadratic cells, which older readers know), the
// cell scalars "physical", the input's data and the fields as FIELD data (0 for facets and points:
// VTK's legacy reader reads no NaN), the group names as the dataset's FIELD data (as for .vtu).
// Values in their shortest exact form, so that reading the file back gives the same coordinates and
// data. Names with spaces or '%' are written as VTK does ("%20", "%25").
void write_vtk(const GatheredMesh& mesh, std::ostream& out);

// Gmsh 4.1 ASCII (.msh): cells (curved ones as Gmsh's second-order elements, their
// high-order nodes after the vertices) and the boundary facets (a curved mesh's at second order,
// CurvedFacets) and points of physical groups, one
// entity per physical group, so that reading the file back gives the same groups; the input's
// point and cell data as $NodeData and $ElementData (time 0, values as doubles).
void write_msh(const GatheredMesh& mesh, std::ostream& out);

// Medit ASCII (.mesh, MeshVersionFormatted 2): vertices (a curved mesh's points), cells with
// their groups as references, and the boundary facets of facet groups (edges in 2D, triangles
// and quadrilaterals in 3D; EdgesP2 and TrianglesP2 of a curved mesh) with theirs; vertex
// references from the point data "medit:ref" (else 0). Group names, fields and other data are not
// kept: Medit has no place for them.
void write_medit(const GatheredMesh& mesh, std::ostream& out);
// Curved cells go to Medit's TrianglesP2 and TetrahedraP2 (VTK's node order, as Gmsh's); throws
// Error naming `target` for curved quadrilaterals and hexahedra, whose QuadrilateralsQ2 and
// HexahedraQ2 have no order Medit files agree on.
void require_medit_curved_types(const InputMesh& mesh, const std::string& target);

// Exodus II (.exo, .e, .ex2) through the Exodus library, to the file `path` (messages name
// `target`): coordinates (num_dim 2 for a 2D mesh in the plane z = 0), an element block per
// cell group and cell type (id: the group's tag; name: the group's; curved cells as TRI6, QUAD8/9,
// TETRA10, HEX20/27 in Exodus' node order), a side set per facet group, the input's point and cell
// data as nodal and element variables of one time step (time 0; exodus_file.hpp names their
// components). Fields and point groups are not written.
void write_exodus(const GatheredMesh& mesh, const std::filesystem::path& path,
                  const std::string& target);

// CGNS (.cgns, HDF5) through the CGNS library, to the file `path` (messages name `target`): one
// base with one unstructured zone, a section per cell group (MIXED where the group has cells
// of several types; curved cells as TRI_6 ... HEXA_27 in CGNS' node order) named by the group, a
// section of facet elements (a curved mesh's at second order) and a BC (PointRange at
// FaceCenter/EdgeCenter) per facet group. Fields and point groups are not written.
void write_cgns(const GatheredMesh& mesh, const std::filesystem::path& path,
                const std::string& target);

}  // namespace neomesh
