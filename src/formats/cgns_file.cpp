#include "formats/cgns_file.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace neomesh {

namespace {

constexpr CgnsElement kElements[] = {{CGNS_ENUMV(NODE), 0, 1, std::nullopt},
                                     {CGNS_ENUMV(BAR_2), 1, 2, std::nullopt},
                                     {CGNS_ENUMV(TRI_3), 2, 3, CellType::Triangle},
                                     {CGNS_ENUMV(QUAD_4), 2, 4, CellType::Quadrilateral},
                                     {CGNS_ENUMV(TETRA_4), 3, 4, CellType::Tetrahedron},
                                     {CGNS_ENUMV(PYRA_5), 3, 5, CellType::Pyramid},
                                     {CGNS_ENUMV(PENTA_6), 3, 6, CellType::Wedge},
                                     {CGNS_ENUMV(HEXA_8), 3, 8, CellType::Hexahedron}};

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

CGNS_ENUMT(ElementType_t) cgns_facet_type(int vertices) {
  return vertices == 2 ? CGNS_ENUMV(BAR_2) : vertices == 3 ? CGNS_ENUMV(TRI_3) : CGNS_ENUMV(QUAD_4);
}

}  // namespace neomesh
