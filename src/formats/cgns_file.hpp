// What the CGNS reader and writer share: an open file and CGNS' linear element types.
//
// CGNS' linear node orders are Gmsh's (SIDS, "Unstructured Grid Element Numbering
// Conventions": TETRA_4 positively oriented, PYRA_5 and HEXA_8 with the base
// counter-clockwise seen from inside, PENTA_6 with 1 2 3 counter-clockwise seen from 4 5 6),
// so gmsh_from_canonical() converts them.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "formats/cgns_library.hpp"
#include "formats/library_file.hpp"
#include "mesh/cell_type.hpp"

namespace neomesh {

class CgnsFile : public LibraryFile {
 public:
  CgnsFile(const std::filesystem::path& path, Mode mode, const std::string& shown);
};

// A linear CGNS element type: its dimension, nodes, and neomesh's cell type (none for NODE
// and BAR_2, which are never cells).
struct CgnsElement {
  CGNS_ENUMT(ElementType_t) type;
  int dim, nodes;
  std::optional<CellType> cell;
};

// The facts of a linear type, or none for others (second order, polyhedra, MIXED).
std::optional<CgnsElement> cgns_element(CGNS_ENUMT(ElementType_t) type);
// The CGNS type of a cell type, and of a boundary facet of `vertices` vertices.
CGNS_ENUMT(ElementType_t) cgns_type(CellType t);
CGNS_ENUMT(ElementType_t) cgns_facet_type(int vertices);

}  // namespace neomesh
