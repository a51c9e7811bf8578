#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <optional>

#include <exodusII.h>

#include "core/error.hpp"
#include "formats/exodus_file.hpp"
#include "formats/mesh_writers.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// An element block to write: the cells of one group and type, in input order.
struct Block {
  std::int64_t id;
  std::string name;
  CellType type;
  std::optional<CurvedType> curved;  // of a curved mesh's cells
  std::vector<PetscInt> cells;

  int nodes() const { return curved ? facts(*curved).nodes : num_vertices(type); }
  std::string type_name() const {
    if (!curved) return std::string(exodus_type_name(type));
    constexpr const char* kNames[] = {"TRI6",  "QUAD8", "QUAD9",   "TETRA10",
                                      "HEX20", "HEX27", "WEDGE15", "WEDGE18"};
    static_assert(std::size(kNames) == kCurvedTypes.size());
    return kNames[static_cast<int>(*curved)];
  }
};

// A block per (cell group, type), by tag then type (the order of the .msh writer's elements).
// A group's first block has the group's tag as id, its others the next free ids; a group
// without a name whose cells have several types names its blocks "block_<tag>", which the
// reader joins into one group again.
std::vector<Block> element_blocks(const InputMesh& mesh, const WrittenGroups& groups) {
  using Type = std::pair<CellType, std::optional<CurvedType>>;
  std::map<std::pair<int, Type>, std::vector<PetscInt>> cells;
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const int tag = mesh.cell_tags[c] != 0 ? mesh.cell_tags[c] : groups.untagged_cells;
    std::optional<CurvedType> curved;
    if (mesh.curved()) curved = mesh.high_order.types[c];
    cells[{tag, {mesh.cell_types[c], curved}}].push_back(c);
  }
  int largest = 0;
  std::map<int, std::string> names;
  std::map<int, int> types;  // per tag
  for (const auto& [key, list] : cells) {
    largest = std::max(largest, key.first);
    ++types[key.first];
  }
  for (const PhysicalGroup& g : groups.all)
    if (g.dim == mesh.dim) names[g.tag] = g.name;
  std::vector<Block> out;
  int previous = -1;
  std::int64_t next_id = largest + 1;
  for (auto& [key, list] : cells) {
    const auto [tag, type] = key;
    std::string name = names[tag];
    if (name.empty() && types[tag] > 1) name = fmt::format("block_{}", tag);
    const std::int64_t id = tag > 0 && tag != previous ? tag : next_id++;
    out.push_back({id, std::move(name), type.first, type.second, std::move(list)});
    previous = tag;
  }
  return out;
}

// A cell's nodes in Exodus' order, 1-based (a curved mesh's points as curved_cell_points
// numbers them).
std::array<std::int64_t, kMaxCurvedNodes> exodus_nodes(const InputMesh& mesh, PetscInt c) {
  std::array<std::int64_t, kMaxCurvedNodes> out{};
  if (mesh.curved()) {
    PetscInt points[kMaxCurvedNodes];
    const int n = curved_cell_points(mesh, c, points);
    for (int i = 0; i < n; ++i)
      out[i] = points[facts(mesh.high_order.types[c]).exodus_order[i]] + 1;
    return out;
  }
  const CellType t = mesh.cell_types[c];
  const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
  for (int i = 0; i < num_vertices(t); ++i) out[i] = cell[gmsh_from_canonical(t)[i]] + 1;
  return out;
}

using FacetKey = std::array<std::int64_t, 4>;
FacetKey facet_key(const std::int64_t* v, int n) {
  FacetKey key = {-1, -1, -1, -1};
  std::copy_n(v, n, key.begin());
  sort_facet_key(key, n);
  return key;
}

// A side set per facet group: (element, side) of a cell each facet bounds, both 1-based.
struct SideSet {
  int tag;
  std::string name;
  std::vector<std::int64_t> elements, sides;
};

std::vector<SideSet> side_sets(const InputMesh& mesh, const WrittenGroups& groups,
                               const std::vector<Block>& blocks, const std::string& target) {
  const TaggedEntities& facets = mesh.facets;
  const auto key_of_facet = [&](PetscInt k) {
    std::int64_t v[4];
    const int n = static_cast<int>(facets.offsets[k + 1] - facets.offsets[k]);
    for (int j = 0; j < n; ++j) v[j] = facets.vertices[facets.offsets[k] + j] + 1;
    return facet_key(v, n);
  };
  std::map<FacetKey, std::pair<std::int64_t, std::int64_t>> found;  // key → (element, side)
  for (PetscInt k = 0; k < facets.size(); ++k) found[key_of_facet(k)] = {0, 0};
  std::int64_t element = 0;
  for (const Block& b : blocks)
    for (PetscInt c : b.cells) {
      ++element;
      const auto nodes = exodus_nodes(mesh, c);
      const ExodusSides& table = exodus_sides(b.type);
      for (int s = 0; s < table.count; ++s) {
        std::int64_t v[4];
        for (int j = 0; j < table.sides[s].size; ++j) v[j] = nodes[table.sides[s].nodes[j]];
        const auto it = found.find(facet_key(v, table.sides[s].size));
        if (it != found.end() && it->second.first == 0) it->second = {element, s + 1};
      }
    }
  std::vector<SideSet> out;
  for (const PhysicalGroup& g : groups.all) {
    if (g.dim != mesh.dim - 1) continue;
    SideSet set{g.tag, g.name, {}, {}};
    for (PetscInt k = 0; k < facets.size(); ++k) {
      if (facets.tags[k] != g.tag) continue;
      const auto [e, side] = found.at(key_of_facet(k));
      if (e == 0) fail("cannot write {}: a facet of group {} bounds no cell", target, g.tag);
      set.elements.push_back(e);
      set.sides.push_back(side);
    }
    out.push_back(std::move(set));
  }
  return out;
}

void write_coordinates(const ExodusFile& file, const InputMesh& mesh, int num_dim) {
  const std::vector<double> xyz = points_in_space(mesh);
  const PetscInt n = mesh.num_points();
  std::vector<double> x(n), y(n), z(n);
  for (PetscInt v = 0; v < n; ++v) {
    x[v] = xyz[3 * v];
    y[v] = xyz[3 * v + 1];
    z[v] = xyz[3 * v + 2];
  }
  file.check(ex_put_coord(file.id(), x.data(), y.data(), num_dim == 3 ? z.data() : nullptr),
             "writing the coordinates");
  char names[3][2] = {"x", "y", "z"};
  char* list[3] = {names[0], names[1], names[2]};
  file.check(ex_put_coord_names(file.id(), list), "writing the coordinate names");
}

void write_block(const ExodusFile& file, const InputMesh& mesh, const Block& b) {
  const int n = b.nodes();
  const std::string type = b.type_name();
  file.check(ex_put_block(file.id(), EX_ELEM_BLOCK, b.id, type.c_str(),
                          static_cast<std::int64_t>(b.cells.size()), n, 0, 0, 0),
             "writing an element block");
  std::vector<std::int64_t> nodes;
  nodes.reserve(b.cells.size() * n);
  for (PetscInt c : b.cells) {
    const auto exo = exodus_nodes(mesh, c);
    nodes.insert(nodes.end(), exo.begin(), exo.begin() + n);
  }
  file.check(ex_put_conn(file.id(), EX_ELEM_BLOCK, b.id, nodes.data(), nullptr, nullptr),
             "writing an element block");
  if (!b.name.empty())
    file.check(ex_put_name(file.id(), EX_ELEM_BLOCK, b.id, b.name.c_str()), "writing a name");
}

void write_side_set(const ExodusFile& file, const SideSet& s) {
  const auto size = static_cast<std::int64_t>(s.elements.size());
  file.check(ex_put_set_param(file.id(), EX_SIDE_SET, s.tag, size, 0), "writing a side set");
  file.check(ex_put_set(file.id(), EX_SIDE_SET, s.tag, s.elements.data(), s.sides.data()),
             "writing a side set");
  if (!s.name.empty())
    file.check(ex_put_name(file.id(), EX_SIDE_SET, s.tag, s.name.c_str()), "writing a name");
}

// Group and variable names longer than Exodus' default of 32 characters are kept whole.
int longest_name(const WrittenGroups& groups, const InputMesh& mesh) {
  std::size_t longest = MAX_STR_LENGTH;
  for (const PhysicalGroup& g : groups.all) longest = std::max(longest, g.name.size());
  for (const auto* data : {&mesh.point_data, &mesh.cell_data})
    for (const DataArray& a : *data)
      for (const std::string& name : exodus_variable_names(a))
        longest = std::max(longest, name.size());
  for (const std::string& name : mesh.steps.global_names) longest = std::max(longest, name.size());
  return static_cast<int>(longest);
}

void put_names(const ExodusFile& file, ex_entity_type kind, std::vector<std::string> names) {
  if (names.empty()) return;
  std::vector<char*> list;
  for (std::string& name : names) list.push_back(name.data());
  const int n = static_cast<int>(names.size());
  file.check(ex_put_variable_param(file.id(), kind, n), "writing the variables");
  file.check(ex_put_variable_names(file.id(), kind, n, list.data()), "writing the variables");
}

// Declares the variables of `kind` (one per component of each array).
void put_variable_names(const ExodusFile& file, ex_entity_type kind,
                        const std::vector<DataArray>& arrays) {
  std::vector<std::string> names;
  for (const DataArray& a : arrays)
    for (std::string& name : exodus_variable_names(a)) names.push_back(std::move(name));
  put_names(file, kind, std::move(names));
}

// The values of `a` at an earlier step: the step's array of its name and shape, or NaN.
std::vector<double> at_step(const DataArray& a, const std::vector<DataArray>* step) {
  if (!step) return a.values;
  for (const DataArray& b : *step)
    if (b.name == a.name && b.components == a.components && b.values.size() == a.values.size())
      return b.values;
  return std::vector<double>(a.values.size(), std::nan(""));
}

// The point and cell data of time step `step` (`point` and `cell`: an earlier step's arrays, or
// null for the last step's, mesh.point_data and cell_data).
void write_step(const ExodusFile& file, int step, const InputMesh& mesh,
                const std::vector<Block>& blocks, const std::vector<DataArray>* point,
                const std::vector<DataArray>* cell) {
  int var = 0;
  const PetscInt nv = mesh.num_vertices();
  for (const DataArray& a : mesh.point_data) {
    const std::vector<double> all = at_step(a, point);
    for (int k = 0; k < a.components; ++k) {
      std::vector<double> values(mesh.num_points(), std::nan(""));  // high-order nodes: NaN
      for (PetscInt v = 0; v < nv; ++v) values[v] = all[v * a.components + k];
      file.check(ex_put_var(file.id(), step, EX_NODAL, ++var, 1, mesh.num_points(), values.data()),
                 "writing a nodal variable");
    }
  }
  var = 0;
  for (const DataArray& a : mesh.cell_data) {
    const std::vector<double> all = at_step(a, cell);
    for (int k = 0; k < a.components; ++k) {
      ++var;
      for (const Block& b : blocks) {
        std::vector<double> values;
        values.reserve(b.cells.size());
        for (PetscInt c : b.cells) values.push_back(all[c * a.components + k]);
        file.check(ex_put_var(file.id(), step, EX_ELEM_BLOCK, var, b.id,
                              static_cast<std::int64_t>(values.size()), values.data()),
                   "writing an element variable");
      }
    }
  }
}

// The input's point and cell data as nodal and element variables and its global variables, at
// each of the input's time steps (an Exodus input's), or else at one step at time 0.
void write_variables(const ExodusFile& file, const InputMesh& mesh,
                     const std::vector<Block>& blocks) {
  const TimeSteps& steps = mesh.steps;
  if (mesh.point_data.empty() && mesh.cell_data.empty() && steps.global_names.empty()) return;
  put_variable_names(file, EX_NODAL, mesh.point_data);
  put_variable_names(file, EX_ELEM_BLOCK, mesh.cell_data);
  put_names(file, EX_GLOBAL, steps.global_names);
  const auto count = std::max<std::size_t>(steps.times.size(), 1);
  for (std::size_t s = 0; s < count; ++s) {
    const int step = static_cast<int>(s) + 1;
    const double time = steps.times.empty() ? 0.0 : steps.times[s];
    file.check(ex_put_time(file.id(), step, &time), "writing the time step");
    // An earlier step's arrays (none: NaN, for a step the input lacked), or null for the last.
    static const std::vector<DataArray> none;
    const auto arrays = [&](const std::vector<std::vector<DataArray>>& all) {
      return s + 1 == count ? nullptr : s < all.size() ? &all[s] : &none;
    };
    write_step(file, step, mesh, blocks, arrays(steps.point_data), arrays(steps.cell_data));
    if (!steps.global_names.empty() && s < steps.globals.size() &&
        steps.globals[s].size() == steps.global_names.size())
      file.check(
          ex_put_var(file.id(), step, EX_GLOBAL, 1, 0,
                     static_cast<std::int64_t>(steps.globals[s].size()), steps.globals[s].data()),
          "writing the global variables");
  }
}

}  // namespace

void write_exodus(const GatheredMesh& g, const std::filesystem::path& path,
                  const std::string& target) {
  const InputMesh& mesh = g.mesh;
  const WrittenGroups groups = physical_groups(mesh);
  const std::vector<Block> blocks = element_blocks(mesh, groups);
  const std::vector<SideSet> sets = side_sets(mesh, groups, blocks, target);

  ExodusFile file(path, ExodusFile::Mode::Create, target);
  file.check(ex_set_max_name_length(file.id(), longest_name(groups, mesh)),
             "setting the name length");
  ex_init_params init{};
  std::snprintf(init.title, sizeof init.title, "neomesh");
  init.num_dim = mesh.dim == 2 && !mesh.plane && !mesh.surface ? 2 : 3;
  init.num_nodes = mesh.num_points();
  init.num_elem = mesh.num_cells();
  init.num_elem_blk = static_cast<std::int64_t>(blocks.size());
  init.num_side_sets = static_cast<std::int64_t>(sets.size());
  file.check(ex_put_init_ext(file.id(), &init), "writing the header");
  write_coordinates(file, mesh, static_cast<int>(init.num_dim));
  for (const Block& b : blocks) write_block(file, mesh, b);
  for (const SideSet& s : sets) write_side_set(file, s);
  write_variables(file, mesh, blocks);
  file.close();
}

}  // namespace neomesh
