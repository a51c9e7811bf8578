#include "formats/exodus_file.hpp"

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

std::vector<std::string> exodus_variable_names(const DataArray& array) {
  if (array.components == 1) return {array.name};
  std::vector<std::string> out;
  for (int k = 0; k < array.components; ++k)
    out.push_back(array.components <= 3 ? fmt::format("{}_{}", array.name, "xyz"[k])
                                        : fmt::format("{}_{}", array.name, k + 1));
  return out;
}

std::vector<DataArray> join_exodus_variables(std::vector<DataArray> scalars) {
  // The number of components of a vector starting at scalar `i`: 2 or 3, or 1.
  const auto components = [&](std::size_t i) {
    const std::string& x = scalars[i].name;
    if (x.size() < 3 || !x.ends_with("_x")) return 1;
    const std::string base = x.substr(0, x.size() - 2);
    int k = 1;
    while (k < 3 && i + k < scalars.size() && scalars[i + k].name == base + "_" + "xyz"[k]) ++k;
    return k;
  };
  std::vector<DataArray> out;
  for (std::size_t i = 0; i < scalars.size();) {
    const int k = components(i);
    if (k == 1) {
      out.push_back(std::move(scalars[i++]));
      continue;
    }
    const std::size_t n = scalars[i].values.size();
    DataArray joined{scalars[i].name.substr(0, scalars[i].name.size() - 2), k, scalars[i].type,
                     std::vector<double>(n * k)};
    for (int c = 0; c < k; ++c)
      for (std::size_t e = 0; e < n && e < scalars[i + c].values.size(); ++e)
        joined.values[e * k + c] = scalars[i + c].values[e];
    out.push_back(std::move(joined));
    i += k;
  }
  return out;
}

}  // namespace neomesh
