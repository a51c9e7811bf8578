#include "formats/cgns_file.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace neomesh {

namespace {

constexpr auto kTriangle = CellType::Triangle, kQuadrilateral = CellType::Quadrilateral,
               kTetrahedron = CellType::Tetrahedron, kHexahedron = CellType::Hexahedron;
constexpr CgnsElement kElements[] = {
    {CGNS_ENUMV(NODE), 0, 1, 1, std::nullopt, std::nullopt},
    {CGNS_ENUMV(BAR_2), 1, 2, 2, std::nullopt, std::nullopt},
    {CGNS_ENUMV(TRI_3), 2, 3, 3, kTriangle, std::nullopt},
    {CGNS_ENUMV(QUAD_4), 2, 4, 4, kQuadrilateral, std::nullopt},
    {CGNS_ENUMV(TETRA_4), 3, 4, 4, kTetrahedron, std::nullopt},
    {CGNS_ENUMV(PYRA_5), 3, 5, 5, CellType::Pyramid, std::nullopt},
    {CGNS_ENUMV(PENTA_6), 3, 6, 6, CellType::Wedge, std::nullopt},
    {CGNS_ENUMV(HEXA_8), 3, 8, 8, kHexahedron, std::nullopt},
    {CGNS_ENUMV(BAR_3), 1, 3, 2, std::nullopt, std::nullopt},
    {CGNS_ENUMV(TRI_6), 2, 6, 3, kTriangle, CurvedType::Triangle6},
    {CGNS_ENUMV(QUAD_8), 2, 8, 4, kQuadrilateral, CurvedType::Quadrilateral8},
    {CGNS_ENUMV(QUAD_9), 2, 9, 4, kQuadrilateral, CurvedType::Quadrilateral9},
    {CGNS_ENUMV(TETRA_10), 3, 10, 4, kTetrahedron, CurvedType::Tetrahedron10},
    {CGNS_ENUMV(HEXA_20), 3, 20, 8, kHexahedron, CurvedType::Hexahedron20},
    {CGNS_ENUMV(HEXA_27), 3, 27, 8, kHexahedron, CurvedType::Hexahedron27},
    {CGNS_ENUMV(PENTA_15), 3, 15, 6, CellType::Wedge, CurvedType::Wedge15},
    {CGNS_ENUMV(PENTA_18), 3, 18, 6, CellType::Wedge, CurvedType::Wedge18}};

// cg_close as a function (the CGNS functions are called through macros, cgns_library.hpp).
int close_cgns(int file) {
  return cg_close(file);
}

std::optional<std::string> cgns_failure(int status) {
  if (status == CG_OK) return std::nullopt;
  return std::string(cg_get_error());
}

}  // namespace

CgnsFile::CgnsFile(const std::filesystem::path& path, Mode mode, const std::string& shown)
    : LibraryFile(shown, close_cgns, cgns_failure) {
  const bool read = mode == Mode::Read;
  if (cg_open(path.c_str(), read ? CG_MODE_READ : CG_MODE_WRITE, &id_) == CG_OK) return;
  id_ = -1;
  if (read) fail("{}: is not a CGNS file the CGNS library can open ({})", name(), cg_get_error());
  fail("cannot write {}: the CGNS library cannot create it ({})", name(), cg_get_error());
}

std::optional<CgnsElement> cgns_element(CGNS_ENUMT(ElementType_t) type) {
  for (const CgnsElement& e : kElements)
    if (e.type == type) return e;
  return std::nullopt;
}

CGNS_ENUMT(ElementType_t) cgns_type(CellType t) {
  return std::find_if(std::begin(kElements), std::end(kElements),
                      [&](const CgnsElement& e) { return e.cell == t; })
      ->type;
}

CGNS_ENUMT(ElementType_t) cgns_type(CurvedType t) {
  return std::find_if(std::begin(kElements), std::end(kElements),
                      [&](const CgnsElement& e) { return e.curved == t; })
      ->type;
}

CGNS_ENUMT(ElementType_t) cgns_facet_type(int dim, int points) {
  return std::find_if(std::begin(kElements), std::end(kElements),
                      [&](const CgnsElement& e) { return e.dim == dim - 1 && e.nodes == points; })
      ->type;
}

}  // namespace neomesh
