// What the Exodus II reader and writer share: an open file, the element types neomesh reads and
// writes, and Exodus' numbering of element sides.
//
// Exodus' linear node orders are Gmsh's (Exodus II manual, "Element Types": TETRA4 positively
// oriented, HEX8 with both faces counter-clockwise seen from above, WEDGE6 with 1 2 3
// counter-clockwise seen from 4 5 6, PYRAMID5 with the base counter-clockwise seen from the
// apex), so gmsh_from_canonical() converts them. Side sets name a facet as (element, side),
// both 1-based, sides numbered as in the manual's side tables.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "formats/library_file.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

// A file opened (or created) with the Exodus library, every integer 64-bit.
class ExodusFile : public LibraryFile {
 public:
  ExodusFile(const std::filesystem::path& path, Mode mode, const std::string& shown);
};

// An element side of Exodus' side numbering: `size` local nodes (0-based, in the file's order)
// per side.
struct ExodusSide {
  int size;
  std::array<std::uint8_t, 4> nodes;
};

// The sides of an element of each cell type, indexed by CellType: 3 or 4 edges of a triangle
// or quadrilateral (2D), the faces of a solid (3D).
struct ExodusSides {
  int count;
  std::array<ExodusSide, 6> sides;
};
const ExodusSides& exodus_sides(CellType t);

// The name the writer gives each cell type (TRI3, QUAD4, TETRA, HEX8, WEDGE, PYRAMID).
std::string_view exodus_type_name(CellType t);

// The cell type of an Exodus element type name (any case, any node count suffix: "TRI",
// "TRIANGLE", "TRI3", "SHELL4", "TETRA4", "TET4", ...), or none for a type neomesh does not
// optimize (BAR2, SPHERE, NSIDED, ...). `shell` tells a shell (SHELL, TRISHELL), whose sides 1
// and 2 are its two faces and whose edges come after.
std::optional<CellType> exodus_cell_type(std::string_view name, bool& shell);

// The dimension of a type of points (SPHERE, CIRCLE) or lines (BAR, BEAM, TRUSS): 0 or 1, or
// none for other types.
std::optional<int> exodus_point_or_line(std::string_view name);

// Exodus variables are scalars: an array of 2 or 3 components is written as the variables
// "<name>_x", "<name>_y" (, "<name>_z"), one of k other components as "<name>_1" .. "<name>_k".
std::vector<std::string> exodus_variable_names(const DataArray& array);

// Scalar variables (values per entity each) as arrays, the variables "<name>_x", "<name>_y"
// (and "<name>_z") next to each other joined into one array "<name>" of 2 (3) components.
std::vector<DataArray> join_exodus_variables(std::vector<DataArray> scalars);

}  // namespace neomesh
