#include "formats/exodus_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <dlfcn.h>
#include <exodusII.h>
#include <netcdf.h>

#include "core/error.hpp"
#include "formats/exodus_file.hpp"
#include "formats/input_file.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// An element block as the file has it: nodes per element (1-based node numbers).
struct Block {
  std::int64_t id = 0;
  std::string name;              // the block's, or "block_<id>"
  std::optional<CellType> type;  // none for points and lines, which are never cells
  int dim = 0;
  bool shell = false;
  std::int64_t first_element = 0;  // 0-based global element number of its first element
  std::int64_t size = 0;
  std::optional<CurvedType> curved;  // of a block of second-order cells
  int per_element = 0;               // nodes: the corners first
  std::vector<std::int64_t> nodes;   // per_element per element
};

class ExodusReader {
 public:
  explicit ExodusReader(const std::filesystem::path& path)
      : file_(path, ExodusFile::Mode::Read, path.string()) {
    const int id = file_.id();
    file_.check(ex_get_init_ext(id, &init_), "reading the header");
    if (init_.num_dim < 2 || init_.num_dim > 3)
      fail("{}: has {}D coordinates; neomesh reads 2D and 3D meshes", name(), init_.num_dim);
    const auto longest = ex_inquire_int(id, EX_INQ_DB_MAX_USED_NAME_LENGTH);
    if (longest > 0) ex_set_max_name_length(id, static_cast<int>(longest));
    name_length_ = std::max<std::int64_t>(longest, MAX_STR_LENGTH);
  }

  const std::string& name() const { return file_.name(); }

  // x, y, z of every node (z = 0 for 2D coordinates).
  std::vector<double> coordinates() {
    const std::size_t n = init_.num_nodes;
    std::vector<double> x(n), y(n), z(n, 0.0), xyz(3 * n);
    file_.check(
        ex_get_coord(file_.id(), x.data(), y.data(), init_.num_dim == 3 ? z.data() : nullptr),
        "reading the coordinates");
    for (std::size_t i = 0; i < n; ++i) {
      xyz[3 * i] = x[i];
      xyz[3 * i + 1] = y[i];
      xyz[3 * i + 2] = z[i];
    }
    return xyz;
  }

  std::vector<Block> blocks() {
    std::vector<Block> out;
    std::int64_t first = 0;
    for (std::int64_t id : ids(EX_ELEM_BLOCK, init_.num_elem_blk)) {
      out.push_back(block(id));
      out.back().first_element = first;
      first += out.back().size;
    }
    return out;
  }

  std::vector<std::int64_t> ids(ex_entity_type kind, std::int64_t count) {
    std::vector<std::int64_t> out(count);
    if (count > 0) file_.check(ex_get_ids(file_.id(), kind, out.data()), "reading the ids");
    return out;
  }

  // The entity's name, or "<prefix>_<id>" if it has none.
  std::string entity_name(ex_entity_type kind, std::int64_t id, std::string_view prefix) {
    std::string buffer(name_length_ + 1, '\0');
    file_.check(ex_get_name(file_.id(), kind, id, buffer.data()), "reading a name");
    buffer.resize(buffer.find('\0'));
    return buffer.empty() ? fmt::format("{}_{}", prefix, id) : buffer;
  }

  // A side set: 1-based global element numbers and 1-based sides.
  std::pair<std::vector<std::int64_t>, std::vector<std::int64_t>> side_set(std::int64_t id) {
    std::int64_t size = 0, factors = 0;
    file_.check(ex_get_set_param(file_.id(), EX_SIDE_SET, id, &size, &factors),
                fmt::format("reading side set {}", id));
    std::vector<std::int64_t> elements(size), sides(size);
    if (size > 0)
      file_.check(ex_get_set(file_.id(), EX_SIDE_SET, id, elements.data(), sides.data()),
                  fmt::format("reading side set {}", id));
    return {std::move(elements), std::move(sides)};
  }

  const ex_init_params& init() const { return init_; }

  // The variables of `kind` (EX_GLOBAL, EX_NODAL, EX_ELEM_BLOCK): their names, or none
  // without time steps.
  std::vector<std::string> variable_names(ex_entity_type kind) {
    if (num_steps() <= 0) return {};
    int count = 0;
    file_.check(ex_get_variable_param(file_.id(), kind, &count), "reading the variables");
    std::vector<std::string> names(count, std::string(name_length_ + 1, '\0'));
    std::vector<char*> list;
    for (std::string& n : names) list.push_back(n.data());
    if (count > 0)
      file_.check(ex_get_variable_names(file_.id(), kind, count, list.data()),
                  "reading the variable names");
    for (std::string& n : names) n.resize(n.find('\0'));
    return names;
  }

  int num_steps() { return static_cast<int>(ex_inquire_int(file_.id(), EX_INQ_TIME)); }

  std::vector<double> times() {
    std::vector<double> out(std::max(num_steps(), 0));
    if (!out.empty()) file_.check(ex_get_all_times(file_.id(), out.data()), "reading the times");
    return out;
  }

  // Variable `var` (1-based) of entity `id` at time step `step` (1-based): `n` values (of a
  // global variable: the n global variables from `var` on).
  std::vector<double> variable(int step, ex_entity_type kind, int var, std::int64_t id,
                               std::int64_t n) {
    std::vector<double> values(n);
    if (n == 0) return values;
    const int status = ex_get_var(file_.id(), step, kind, var, id, n, values.data());
    file_.check(status, "reading a variable");
    // A warning: the library found no values (all would read as 0).
    if (status > 0 && !(kind == EX_NODAL && separate_nodal_variable(step, var, values)))
      fail("{}: reading variable {} of time step {} failed (the Exodus library finds no values)",
           name(), var, step);
    return values;
  }

  // Which element variables each block has (block-major), all true without a truth table.
  std::vector<int> truth_table(std::int64_t blocks, int vars) {
    std::vector<int> table(blocks * vars, 1);
    if (blocks > 0 && vars > 0)
      file_.check(ex_get_truth_table(file_.id(), EX_ELEM_BLOCK, static_cast<int>(blocks), vars,
                                     table.data()),
                  "reading the element variables' truth table");
    return table;
  }

 private:
  // meshio writes each nodal variable as a netCDF variable of its own (vals_nod_var1, ...), as
  // Exodus' "large model" does, without the attribute file_size that says so; the Exodus library
  // then looks for them all in one (vals_nod_var) and warns. Reads such a variable through the
  // netCDF library that the Exodus library uses (an Exodus id is its netCDF id), found in the
  // process, not linked: Debian's libexodusii uses the MPI netCDF while libnetcdf-dev links the
  // serial one, and two netCDF libraries do not share their ids. Returns whether it was there.
  bool separate_nodal_variable(int step, int var, std::vector<double>& values) {
    const auto inq_varid =
        reinterpret_cast<decltype(&nc_inq_varid)>(dlsym(RTLD_DEFAULT, "nc_inq_varid"));
    const auto get_vara =
        reinterpret_cast<decltype(&nc_get_vara_double)>(dlsym(RTLD_DEFAULT, "nc_get_vara_double"));
    int varid = 0;
    const std::string variable = fmt::format("vals_nod_var{}", var);
    const std::size_t start[2] = {static_cast<std::size_t>(step - 1), 0},
                      count[2] = {1, values.size()};
    return inq_varid && get_vara && inq_varid(file_.id(), variable.c_str(), &varid) == NC_NOERR &&
           get_vara(file_.id(), varid, start, count, values.data()) == NC_NOERR;
  }

  Block block(std::int64_t id) {
    Block b;
    b.id = id;
    b.name = entity_name(EX_ELEM_BLOCK, id, "block");
    char type[MAX_STR_LENGTH + 1] = {};
    std::int64_t nodes = 0, edges = 0, faces = 0, attributes = 0;
    file_.check(ex_get_block(file_.id(), EX_ELEM_BLOCK, id, type, &b.size, &nodes, &edges, &faces,
                             &attributes),
                fmt::format("reading element block {}", id));
    b.type = exodus_cell_type(type, b.shell);
    if (const auto point_or_line = exodus_point_or_line(type); !b.type && point_or_line) {
      b.dim = *point_or_line;  // (its elements count in the numbering of side sets)
      return b;
    }
    if (!b.type)
      fail(
          "{}: element block {} ('{}') has {} elements, which neomesh does not read (it reads "
          "TRI3/6, QUAD4/8/9, SHELL4, TETRA4/10, HEX8/20/27, WEDGE6/15/18 and PYRAMID5, and skips "
          "points and lines)",
          name(), id, b.name, type);
    if (nodes != num_vertices(*b.type)) {
      b.curved = curved_type(*b.type, static_cast<int>(nodes));
      if (!b.curved || b.shell)
        fail(
            "{}: element block {} ('{}') has {} elements with {} nodes; neomesh reads {} of {} "
            "nodes{}",
            name(), id, b.name, type, nodes, facts(*b.type).plural, num_vertices(*b.type),
            b.type == CellType::Pyramid || b.shell
                ? ""
                : " and their second-order cells (TRI6, QUAD8/9, TETRA10, HEX20/27, WEDGE15/18)");
    }
    b.dim = facts(*b.type).dim;
    b.per_element = static_cast<int>(nodes);
    b.nodes.resize(b.size * nodes);
    if (b.size > 0)
      file_.check(ex_get_conn(file_.id(), EX_ELEM_BLOCK, id, b.nodes.data(), nullptr, nullptr),
                  fmt::format("reading element block {}", id));
    return b;
  }

  ExodusFile file_;
  ex_init_params init_{};
  std::int64_t name_length_ = MAX_STR_LENGTH;
};

// Group tags from Exodus ids: the id itself where it is a valid tag (1..INT_MAX), else (meshio
// numbers its blocks from 0) the next tag above every id.
class GroupTags {
 public:
  explicit GroupTags(const std::vector<std::int64_t>& ids) {
    for (std::int64_t id : ids)
      if (valid(id)) next_ = std::max(next_, static_cast<int>(id) + 1);
  }
  int of(std::int64_t id) { return valid(id) ? static_cast<int>(id) : next_++; }

 private:
  static bool valid(std::int64_t id) { return id >= 1 && id < std::numeric_limits<int>::max(); }
  int next_ = 1;
};

// Numbers the nodes that cells use (file order) into `vertex` (their corners) and `node` (the
// other nodes of second-order cells), and sets the mesh's coordinates and high-order nodes.
std::vector<PetscInt> number_vertices(const std::vector<Block>& blocks,
                                      const std::vector<double>& xyz, const std::string& file,
                                      std::vector<PetscInt>& node, InputMesh& mesh) {
  const std::int64_t nn = static_cast<std::int64_t>(xyz.size() / 3);
  std::vector<PetscInt> vertex(nn, -1);
  node.assign(nn, -1);
  const Block* first = nullptr;  // of the cells
  for (const Block& b : blocks) {
    if (b.dim != mesh.dim) continue;
    if (first && first->curved.has_value() != b.curved.has_value())
      fail(
          "{}: mixes first-order and second-order cells (blocks {} and {}); neomesh reads meshes "
          "of one order",
          file, first->id, b.id);
    if (!first) first = &b;
    const int corners = num_vertices(*b.type);
    for (std::size_t k = 0; k < b.nodes.size(); ++k) {
      const std::int64_t n = b.nodes[k];
      if (n < 1 || n > nn)
        fail("{}: element {} of block {} refers to node {}, which is out of range (1..{})", file,
             k / b.per_element + 1, b.id, n, nn);
      (static_cast<int>(k % b.per_element) < corners ? vertex : node)[n - 1] = 0;
    }
  }
  number_used_vertices(vertex, xyz, file, mesh);
  number_high_order_nodes(node, vertex, xyz, file, mesh);
  return vertex;
}

void add_cells(const std::vector<Block>& blocks, const std::vector<PetscInt>& vertex,
               const std::vector<PetscInt>& node, const std::string& file, InputMesh& mesh) {
  std::vector<std::int64_t> ids;
  for (const Block& b : blocks) ids.push_back(b.id);
  GroupTags tags(ids);
  std::map<std::string, int> tag_of;  // group name → tag
  for (const Block& b : blocks) {
    if (b.dim != mesh.dim) continue;
    const auto [it, added] = tag_of.try_emplace(b.name, 0);
    if (added) {
      it->second = tags.of(b.id);
      mesh.groups.push_back({mesh.dim, it->second, b.name});
    }
    const int n = num_vertices(*b.type);
    for (std::int64_t e = 0; e < b.size; ++e) {
      const std::int64_t* nodes = b.nodes.data() + e * b.per_element;
      if (b.curved && std::set<std::int64_t>(nodes, nodes + b.per_element).size() !=
                          static_cast<std::size_t>(b.per_element))
        fail("{}: element {} of block {} has a repeated node", file, b.first_element + e + 1, b.id);
      PetscInt v[8];
      for (int j = 0; j < n; ++j) v[gmsh_from_canonical(*b.type)[j]] = vertex[nodes[j] - 1];
      mesh.add_cell(*b.type, v, it->second);
      if (b.curved) {
        PetscInt gmsh[kMaxCurvedNodes];
        for (int j = n; j < b.per_element; ++j)
          gmsh[facts(*b.curved).exodus_order[j]] = node[nodes[j] - 1];
        mesh.high_order.add(*b.curved, gmsh + n);
      }
      mesh.element_tag.push_back(b.first_element + e + 1);
    }
  }
}

void add_side_sets(ExodusReader& reader, const std::vector<Block>& blocks,
                   const std::vector<PetscInt>& vertex, InputMesh& mesh) {
  const std::string& file = reader.name();
  const std::vector<std::int64_t> ids = reader.ids(EX_SIDE_SET, reader.init().num_side_sets);
  GroupTags tags(ids);
  for (std::int64_t id : ids) {
    const auto [elements, sides] = reader.side_set(id);
    const int tag = tags.of(id);
    mesh.groups.push_back({mesh.dim - 1, tag, reader.entity_name(EX_SIDE_SET, id, "sideset")});
    for (std::size_t k = 0; k < elements.size(); ++k) {
      const std::int64_t e = elements[k] - 1;
      const auto b =
          std::upper_bound(blocks.begin(), blocks.end(), e,
                           [](std::int64_t x, const Block& y) { return x < y.first_element; }) -
          1;
      if (e < 0 || b < blocks.begin() || e >= b->first_element + b->size)
        fail("{}: side set {} names element {}, which does not exist", file, id, e + 1);
      if (b->dim != mesh.dim)
        fail(
            "{}: side set {} names element {} of block {}, which is not a cell (its dimension is "
            "lower than the mesh's)",
            file, id, e + 1, b->id);
      const ExodusSides& table = exodus_sides(*b->type);
      const std::int64_t side = sides[k] - 1 - (b->shell ? 2 : 0);  // a shell's faces come first
      if (side < 0 || side >= table.count)
        fail("{}: side set {} names side {} of element {}, which has no such side", file, id,
             sides[k], e + 1);
      const ExodusSide& s = table.sides[side];
      const std::int64_t* nodes = b->nodes.data() + (e - b->first_element) * b->per_element;
      PetscInt v[4];
      for (int j = 0; j < s.size; ++j) v[j] = vertex[nodes[s.nodes[j]] - 1];
      mesh.facets.add(v, s.size, tag);
    }
  }
}

// The nodal and element variables of one time step as point and cell data (element variables
// that a block of cells lacks are NaN there).
class StepData {
 public:
  StepData(ExodusReader& reader, const std::vector<Block>& blocks,
           const std::vector<PetscInt>& vertex, int dim)
      : reader_(reader), blocks_(blocks), num_nodes_(vertex.size()), dim_(dim) {
    for (std::size_t n = 0; n < vertex.size(); ++n)
      if (vertex[n] >= 0) used_.push_back(static_cast<std::int64_t>(n));
    nodal_ = reader.variable_names(EX_NODAL);
    element_ = reader.variable_names(EX_ELEM_BLOCK);
    truth_ = reader.truth_table(static_cast<std::int64_t>(blocks.size()),
                                static_cast<int>(element_.size()));
  }

  std::vector<DataArray> point_data(int step) {
    std::vector<DataArray> nodal;
    for (std::size_t k = 0; k < nodal_.size(); ++k)
      nodal.push_back({nodal_[k], 1, ValueType::Float64,
                       reader_.variable(step, EX_NODAL, static_cast<int>(k) + 1, 1,
                                        static_cast<std::int64_t>(num_nodes_))});
    return join_exodus_variables(select_data(nodal, num_nodes_, used_));
  }

  std::vector<DataArray> cell_data(int step) {
    const int vars = static_cast<int>(element_.size());
    std::vector<DataArray> element;
    for (int k = 0; k < vars; ++k) {
      DataArray a{element_[k], 1, ValueType::Float64, {}};
      for (std::size_t b = 0; b < blocks_.size(); ++b) {
        if (blocks_[b].dim != dim_) continue;
        if (truth_[b * vars + k]) {
          const auto v =
              reader_.variable(step, EX_ELEM_BLOCK, k + 1, blocks_[b].id, blocks_[b].size);
          a.values.insert(a.values.end(), v.begin(), v.end());
        } else {
          a.values.resize(a.values.size() + blocks_[b].size, std::nan(""));
        }
      }
      element.push_back(std::move(a));
    }
    return join_exodus_variables(std::move(element));
  }

 private:
  ExodusReader& reader_;
  const std::vector<Block>& blocks_;
  std::size_t num_nodes_;
  int dim_;
  std::vector<std::int64_t> used_;  // the nodes that are vertices
  std::vector<std::string> nodal_, element_;
  std::vector<int> truth_;
};

// Every time step: its time and global variables, and its nodal and element variables as point
// and cell data (the last step's as mesh.point_data and cell_data).
void add_variables(ExodusReader& reader, const std::vector<Block>& blocks,
                   const std::vector<PetscInt>& vertex, InputMesh& mesh) {
  TimeSteps& steps = mesh.steps;
  steps.times = reader.times();
  const int last = static_cast<int>(steps.times.size());
  if (last == 0) return;
  steps.global_names = reader.variable_names(EX_GLOBAL);
  StepData data(reader, blocks, vertex, mesh.dim);
  for (int step = 1; step <= last; ++step) {
    steps.globals.push_back(reader.variable(step, EX_GLOBAL, 1, 0,
                                            static_cast<std::int64_t>(steps.global_names.size())));
    std::vector<DataArray> point = data.point_data(step), cell = data.cell_data(step);
    // (A curved mesh's nodal variables would need its nodes' values too: they are not carried.)
    if (mesh.curved()) point.clear();
    if (step == last) {
      mesh.point_data = std::move(point);
      mesh.cell_data = std::move(cell);
    } else {
      steps.point_data.push_back(std::move(point));
      steps.cell_data.push_back(std::move(cell));
    }
  }
}

}  // namespace

InputMesh read_exodus(const std::filesystem::path& path) {
  check_regular_file(path);
  ExodusReader reader(path);
  const std::string& file = reader.name();
  const std::vector<Block> blocks = reader.blocks();
  InputMesh mesh;
  mesh.dim = 0;
  for (const Block& b : blocks)
    if (b.size > 0) mesh.dim = std::max(mesh.dim, b.dim);
  if (mesh.dim == 0) fail("{}: has no elements", file);
  std::vector<PetscInt> node;
  const std::vector<PetscInt> vertex =
      number_vertices(blocks, reader.coordinates(), file, node, mesh);
  add_cells(blocks, vertex, node, file, mesh);
  check_high_order_nodes(mesh, file);
  add_side_sets(reader, blocks, vertex, mesh);
  add_variables(reader, blocks, vertex, mesh);
  std::sort(mesh.groups.begin(), mesh.groups.end(), [](const auto& a, const auto& b) {
    return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
  });
  return mesh;
}

}  // namespace neomesh
