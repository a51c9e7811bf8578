#include <algorithm>
#include <map>
#include <numeric>
#include <string>

#include <fmt/compile.h>
#include <fmt/ostream.h>
#include <omp.h>

#include "formats/mesh_writers.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// The Gmsh type of a facet or point of `points` points (a curved mesh's facets at second order).
int gmsh_facet_type(int dim, int points) {
  if (points == 1) return 15;                       // point
  if (dim == 2) return points == 2 ? 1 : 8;         // line, line3
  constexpr int faces[] = {2, 3, 0, 9, 0, 16, 10};  // triangle, quadrilateral, then second order
  return faces[points - 3];
}

// One entity per (dim, physical tag); cells without a tag get the entity of tag 0.
struct Entities {
  std::map<std::pair<int, int>, int> tag;  // (dim, physical tag) → entity tag
  int count(int dim) const {
    return static_cast<int>(
        std::count_if(tag.begin(), tag.end(), [&](const auto& e) { return e.first.first == dim; }));
  }
  void add(int dim, int physical) {
    if (!tag.contains({dim, physical})) tag[{dim, physical}] = count(dim) + 1;
  }
};

// An element block: elements of one type on one entity, as vertex lists (input numbers), and
// for cells their input numbers.
struct Block {
  int dim, entity, type;
  std::vector<std::vector<PetscInt>> elements;
  std::vector<PetscInt> cells;
};

void write_entities(std::ostream& f, const std::vector<double>& xyz, const Entities& entities) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  fmt::print(f, "$Entities\n{} {} {} {}\n", entities.count(0), entities.count(1), entities.count(2),
             entities.count(3));
  for (const auto& [key, entity] : entities.tag) {  // sorted by dim, as Gmsh wants
    const auto [dim, physical] = key;
    const std::string physicals = physical > 0 ? fmt::format("1 {}", physical) : "0";
    if (dim == 0)
      fmt::print(f, "{} {} {} {} {}\n", entity, lo[0], lo[1], lo[2], physicals);
    else
      fmt::print(f, "{} {} {} {} {} {} {} {} 0\n", entity, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2],
                 physicals);
  }
  fmt::print(f, "$EndEntities\n");
}

std::vector<Block> element_blocks(const GatheredMesh& g, const WrittenGroups& groups,
                                  Entities& entities) {
  const InputMesh& mesh = g.mesh;
  std::map<std::tuple<int, int, int>, Block> blocks;  // by (dim, physical tag, type)
  for (const PhysicalGroup& group : groups.all) entities.add(group.dim, group.tag);
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellType t = mesh.cell_types[c];
    const int tag = mesh.cell_tags[c] != 0 ? mesh.cell_tags[c] : groups.untagged_cells;
    entities.add(mesh.dim, tag);
    std::vector<PetscInt> vertices(mesh.curved() ? kMaxCurvedNodes : num_vertices(t));
    int type = facts(t).gmsh;
    if (mesh.curved()) {  // the vertices, then the high-order nodes, in Gmsh's order
      vertices.resize(curved_cell_points(mesh, c, vertices.data()));
      type = facts(mesh.high_order.types[c]).gmsh;
    } else {
      const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
      for (int i = 0; i < num_vertices(t); ++i) vertices[i] = cell[gmsh_from_canonical(t)[i]];
    }
    auto& block = blocks[{mesh.dim, tag, type}];
    block.elements.push_back(std::move(vertices));
    block.cells.push_back(c);
  }
  const CurvedFacets curved(mesh);
  for (const TaggedEntities* tagged : {&mesh.facets, &mesh.points})
    for (PetscInt k = 0; k < tagged->size(); ++k) {
      PetscInt points[9] = {tagged->vertices[tagged->offsets[k]]};
      const int n = tagged == &mesh.facets ? curved.points(k, points) : 1;
      const int dim = n == 1 ? 0 : mesh.dim - 1;
      entities.add(dim, tagged->tags[k]);
      blocks[{dim, tagged->tags[k], gmsh_facet_type(mesh.dim, n)}].elements.emplace_back(
          points, points + n);
    }
  std::vector<Block> out;
  for (auto& [key, block] : blocks) {
    const auto [dim, physical, type] = key;
    out.push_back({dim, entities.tag.at({dim, physical}), type, std::move(block.elements),
                   std::move(block.cells)});
  }
  // Cells first, then facets and points: element numbers then follow the input's cells.
  std::stable_sort(out.begin(), out.end(),
                   [](const Block& a, const Block& b) { return a.dim > b.dim; });
  return out;
}

// Lines 0 .. count−1, as line(out, i) formats them to `out`, formatted chunk by chunk on every
// thread and written in order. fmt::print of each value through the ostream took 0.65 s of
// quads 1024² (defaults), most of a large run's writing; the text of a few chunks per thread
// is held at a time.
template <typename Line>
void write_lines(std::ostream& f, std::size_t count, const Line& line) {
  constexpr std::size_t kChunk = std::size_t{1} << 14;
  const std::size_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<fmt::memory_buffer> text(4 * static_cast<std::size_t>(omp_get_max_threads()));
  for (std::size_t first = 0; first < chunks; first += text.size()) {
    const std::size_t round = std::min(text.size(), chunks - first);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t k = 0; k < round; ++k) {
      text[k].clear();
      const std::size_t begin = (first + k) * kChunk, end = std::min(count, begin + kChunk);
      for (std::size_t i = begin; i < end; ++i) line(std::back_inserter(text[k]), i);
    }
    for (std::size_t k = 0; k < round; ++k)
      f.write(text[k].data(), static_cast<std::streamsize>(text[k].size()));
  }
}

// $NodeData or $ElementData of an array: name, time 0, step 0, the values of every node or
// element, by tag 1, 2, ... (`index[t - 1]`: the entry of the array for tag t, or -1 for an
// element that is not a cell, a facet or point of a group: NaN, since meshio reads an
// $ElementData only if it covers every element).
void write_data(std::ostream& f, const char* section, const DataArray& a,
                const std::vector<std::ptrdiff_t>& index) {
  std::string name = a.name;  // a string tag is one line between quotes
  std::replace_if(
      name.begin(), name.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  std::replace(name.begin(), name.end(), '"', '\'');
  fmt::print(f, "${}\n1\n\"{}\"\n1\n0\n3\n0\n{}\n{}\n", section, name, a.components, index.size());
  write_lines(f, index.size(), [&](auto out, std::size_t t) {
    out = fmt::format_to(out, FMT_COMPILE("{}"), t + 1);
    for (int k = 0; k < a.components; ++k)
      out = index[t] < 0 ? fmt::format_to(out, FMT_COMPILE(" nan"))
                         : fmt::format_to(out, FMT_COMPILE(" {:.17g}"),
                                          a.values[index[t] * a.components + k]);
    *out++ = '\n';
  });
  fmt::print(f, "$End{}\n", section);
}

}  // namespace

WrittenGroups physical_groups(const InputMesh& mesh) {
  WrittenGroups g{mesh.groups, 0};
  const bool any_untagged =
      std::find(mesh.cell_tags.begin(), mesh.cell_tags.end(), 0) != mesh.cell_tags.end();
  if (mesh.groups.empty() || !any_untagged) return g;
  int largest = 0;
  for (const PhysicalGroup& group : mesh.groups)
    if (group.dim == mesh.dim) largest = std::max(largest, group.tag);
  g.untagged_cells = largest + 1;
  g.all.push_back({mesh.dim, g.untagged_cells, "domain"});
  std::sort(g.all.begin(), g.all.end(), [](const auto& a, const auto& b) {
    return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
  });
  return g;
}

void write_msh(const GatheredMesh& g, std::ostream& f) {
  const InputMesh& mesh = g.mesh;
  fmt::print(f, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  const WrittenGroups groups = physical_groups(mesh);
  const auto named = std::count_if(groups.all.begin(), groups.all.end(),
                                   [](const auto& group) { return !group.name.empty(); });
  if (named > 0) {
    fmt::print(f, "$PhysicalNames\n{}\n", named);
    for (const PhysicalGroup& group : groups.all)
      if (!group.name.empty()) fmt::print(f, "{} {} \"{}\"\n", group.dim, group.tag, group.name);
    fmt::print(f, "$EndPhysicalNames\n");
  }

  Entities entities;
  const std::vector<Block> blocks = element_blocks(g, groups, entities);
  const std::vector<double> xyz = points_in_space(mesh);
  write_entities(f, xyz, entities);

  // All nodes on the first cell entity; Gmsh and PETSc accept nodes classified there.
  const PetscInt nv = mesh.num_points();
  fmt::print(f, "$Nodes\n1 {} 1 {}\n{} {} 0 {}\n", nv, nv, mesh.dim, blocks.front().entity, nv);
  const auto vertices = static_cast<std::size_t>(nv);
  write_lines(f, vertices,
              [](auto out, std::size_t v) { fmt::format_to(out, FMT_COMPILE("{}\n"), v + 1); });
  write_lines(f, vertices, [&](auto out, std::size_t v) {
    fmt::format_to(out, FMT_COMPILE("{:.17g} {:.17g} {:.17g}\n"), xyz[3 * v], xyz[3 * v + 1],
                   xyz[3 * v + 2]);
  });
  fmt::print(f, "$EndNodes\n");

  std::size_t total = 0;
  for (const Block& b : blocks) total += b.elements.size();
  fmt::print(f, "$Elements\n{} {} 1 {}\n", blocks.size(), total, total);
  std::vector<std::ptrdiff_t> cell_of;  // per element (tag - 1): its cell, or -1
  cell_of.reserve(total);
  for (const Block& b : blocks) {
    fmt::print(f, "{} {} {} {}\n", b.dim, b.entity, b.type, b.elements.size());
    const std::size_t first = cell_of.size() + 1;  // the block's first element tag
    write_lines(f, b.elements.size(), [&](auto out, std::size_t k) {
      out = fmt::format_to(out, FMT_COMPILE("{}"), first + k);
      for (PetscInt v : b.elements[k]) out = fmt::format_to(out, FMT_COMPILE(" {}"), v + 1);
      *out++ = '\n';
    });
    for (std::size_t k = 0; k < b.elements.size(); ++k)
      cell_of.push_back(k < b.cells.size() ? static_cast<std::ptrdiff_t>(b.cells[k]) : -1);
  }
  fmt::print(f, "$EndElements\n");

  std::vector<std::ptrdiff_t> node(nv);
  std::iota(node.begin(), node.end(), 0);
  std::fill(node.begin() + mesh.num_vertices(), node.end(), -1);  // high-order nodes: NaN
  for (const DataArray& a : mesh.point_data) write_data(f, "NodeData", a, node);
  for (const DataArray& a : mesh.cell_data) write_data(f, "ElementData", a, cell_of);
}

}  // namespace neomesh
