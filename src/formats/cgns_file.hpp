// What the CGNS reader and writer share: an open file and CGNS' linear element types.
//
// CGNS' linear node orders are Gmsh's (SIDS, "Unstructured Grid Element Numbering
// Conventions": TETRA_4 positively oriented, PYRA_5 and HEXA_8 with the base
// counter-clockwise seen from inside, PENTA_6 with 1 2 3 counter-clockwise seen from 4 5 6),
// so gmsh_from_canonical() converts them. Their second-order types list the corners first, then
// the other nodes in CgnsFacts' cgns_order (curved_type.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "formats/cgns_library.hpp"
#include "formats/library_file.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/curved_type.hpp"

namespace neomesh {

class CgnsFile : public LibraryFile {
 public:
  CgnsFile(const std::filesystem::path& path, Mode mode, const std::string& shown);
};

// A CGNS element type neomesh reads: its dimension, nodes (`corners` of them first), neomesh's
// cell type (none for NODE, BAR_2 and BAR_3, which are never cells) and curved type.
struct CgnsElement {
  CGNS_ENUMT(ElementType_t) type;
  int dim, nodes, corners;
  std::optional<CellType> cell;
  std::optional<CurvedType> curved;
};

// The facts of a type neomesh reads, or none for others (third order, polyhedra, MIXED).
std::optional<CgnsElement> cgns_element(CGNS_ENUMT(ElementType_t) type);
// The CGNS type of a cell type (or a curved one), and of a boundary facet of `points` points
// (a facet of a 2D mesh: `dim` 2).
CGNS_ENUMT(ElementType_t) cgns_type(CellType t);
CGNS_ENUMT(ElementType_t) cgns_type(CurvedType t);
CGNS_ENUMT(ElementType_t) cgns_facet_type(int dim, int points);

}  // namespace neomesh
