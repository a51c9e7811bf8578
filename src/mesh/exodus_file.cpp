#include "mesh/exodus_file.hpp"

#include <algorithm>
#include <cctype>

#include <exodusII.h>

#include "core/error.hpp"

namespace neomesh {

namespace {

// Word sizes of the floating-point data: doubles in memory and in the file.
constexpr int kDoubleBytes = 8;

// The manual's side tables, 0-based, by CellType.
constexpr ExodusSides kSides[kNumCellTypes] = {
    {3, {{{2, {0, 1}}, {2, {1, 2}}, {2, {2, 0}}}}},
    {4, {{{2, {0, 1}}, {2, {1, 2}}, {2, {2, 3}}, {2, {3, 0}}}}},
    {4, {{{3, {0, 1, 3}}, {3, {1, 2, 3}}, {3, {0, 3, 2}}, {3, {0, 2, 1}}}}},
    {6,
     {{{4, {0, 1, 5, 4}},
       {4, {1, 2, 6, 5}},
       {4, {2, 3, 7, 6}},
       {4, {0, 4, 7, 3}},
       {4, {0, 3, 2, 1}},
       {4, {4, 5, 6, 7}}}}},
    {5,
     {{{4, {0, 1, 4, 3}}, {4, {1, 2, 5, 4}}, {4, {0, 3, 5, 2}}, {3, {0, 2, 1}}, {3, {3, 4, 5}}}}},
    {5, {{{3, {0, 1, 4}}, {3, {1, 2, 4}}, {3, {2, 3, 4}}, {3, {0, 4, 3}}, {4, {0, 3, 2, 1}}}}}};

// The names the writer gives: the ones every reader knows (meshio 5 reads TETRA4 as a type of
// its own and knows neither WEDGE6 nor PYRAMID5).
constexpr std::string_view kTypeNames[kNumCellTypes] = {"TRI3", "QUAD4", "TETRA",
                                                        "HEX8", "WEDGE", "PYRAMID"};

// Exodus element type names by their letters (the node count that may follow is checked by the
// reader against the block's nodes per element).
struct TypeWord {
  std::string_view letters;
  CellType type;
  bool shell;
};
constexpr TypeWord kTypeWords[] = {
    {"TRI", CellType::Triangle, false},       {"TRIANGLE", CellType::Triangle, false},
    {"TRISHELL", CellType::Triangle, true},   {"QUAD", CellType::Quadrilateral, false},
    {"SHELL", CellType::Quadrilateral, true}, {"TET", CellType::Tetrahedron, false},
    {"TETRA", CellType::Tetrahedron, false},  {"HEX", CellType::Hexahedron, false},
    {"WEDGE", CellType::Wedge, false},        {"PYRAMID", CellType::Pyramid, false}};

// The letters an element type name starts with (TETRA of TETRA10), and whether they are `upper`
// in any case.
std::string_view letters(std::string_view name) {
  const auto digits = std::find_if(name.begin(), name.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
  return {name.begin(), digits};
}
bool same_word(std::string_view word, std::string_view upper) {
  return std::equal(word.begin(), word.end(), upper.begin(), upper.end(), [](char a, char b) {
    return std::toupper(static_cast<unsigned char>(a)) == b;
  });
}

std::optional<std::string> exodus_failure(int status) {
  if (status >= 0) return std::nullopt;  // (> 0: a warning)
  return fmt::format("Exodus error {}", status);
}

}  // namespace

ExodusFile::ExodusFile(const std::filesystem::path& path, Mode mode, const std::string& shown)
    : LibraryFile(shown, ex_close, exodus_failure) {
  ex_opts(0);  // no messages on stderr: failures become one Error each
  int cpu_word = kDoubleBytes, io_word = kDoubleBytes;
  if (mode == Mode::Read) {
    float version = 0;
    id_ = ex_open(path.c_str(), EX_READ, &cpu_word, &io_word, &version);
    if (id_ < 0) fail("{}: is not an Exodus II file the Exodus library can open", name());
  } else {
    id_ = ex_create(path.c_str(), EX_CLOBBER, &cpu_word, &io_word);
    if (id_ < 0) fail("cannot write {}: the Exodus library cannot create it", name());
  }
  ex_set_int64_status(id_, EX_ALL_INT64_API);
}

const ExodusSides& exodus_sides(CellType t) {
  return kSides[static_cast<int>(t)];
}

std::string_view exodus_type_name(CellType t) {
  return kTypeNames[static_cast<int>(t)];
}

std::optional<CellType> exodus_cell_type(std::string_view name, bool& shell) {
  const std::string_view w = letters(name);
  for (const TypeWord& t : kTypeWords)
    if (same_word(w, t.letters)) {
      shell = t.shell;
      return t.type;
    }
  return std::nullopt;
}

std::optional<int> exodus_point_or_line(std::string_view name) {
  const std::string_view w = letters(name);
  for (std::string_view line : {"BAR", "BEAM", "TRUSS", "ROD", "EDGE"})
    if (same_word(w, line)) return 1;
  for (std::string_view point : {"SPHERE", "CIRCLE", "POINT", "NODE"})
    if (same_word(w, point)) return 0;
  return std::nullopt;
}

}  // namespace neomesh
