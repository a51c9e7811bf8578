#include <algorithm>
#include <map>
#include <set>

#include "core/error.hpp"
#include "formats/cgns_file.hpp"
#include "formats/mesh_writers.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// CGNS names (of nodes) have at most 32 characters.
constexpr std::size_t kNameLength = 32;

// A section to write: elements (CGNS type and 1-based nodes each) under a unique name.
struct Section {
  std::string name;
  std::vector<CGNS_ENUMT(ElementType_t)> types;
  std::vector<cgsize_t> nodes;
  void add(CGNS_ENUMT(ElementType_t) type, const cgsize_t* v, int n) {
    types.push_back(type);
    nodes.insert(nodes.end(), v, v + n);
  }
};

// Names unique among the zone's sections: a name taken (or too long) gets its tag appended.
class UniqueNames {
 public:
  std::string of(const std::string& name, int tag, const char* fallback) {
    std::string out = name.empty() ? fmt::format("{}_{}", fallback, tag) : name;
    if (out.size() > kNameLength || used_.contains(out)) {
      const std::string suffix = fmt::format("_{}", tag);
      out = out.substr(0, kNameLength - suffix.size()) + suffix;
    }
    used_.insert(out);
    return out;
  }

 private:
  std::set<std::string> used_;
};

// A section per cell group, in tag order (the .msh writer's order of cells).
std::vector<Section> cell_sections(const InputMesh& mesh, const WrittenGroups& groups,
                                   UniqueNames& names) {
  std::map<int, Section> by_tag;
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellType t = mesh.cell_types[c];
    Section& section = by_tag[mesh.cell_tags[c] != 0 ? mesh.cell_tags[c] : groups.untagged_cells];
    cgsize_t v[kMaxCurvedNodes];
    if (mesh.curved()) {  // its points (curved_cell_points) in CGNS' order
      const CurvedFacts& f = facts(mesh.high_order.types[c]);
      PetscInt points[kMaxCurvedNodes];
      curved_cell_points(mesh, c, points);
      for (int i = 0; i < f.nodes; ++i) v[i] = points[f.cgns_order[i]] + 1;
      section.add(cgns_type(mesh.high_order.types[c]), v, f.nodes);
      continue;
    }
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    for (int i = 0; i < num_vertices(t); ++i) v[i] = cell[gmsh_from_canonical(t)[i]] + 1;
    section.add(cgns_type(t), v, num_vertices(t));
  }
  std::map<int, std::string> group_names;
  for (const PhysicalGroup& g : groups.all)
    if (g.dim == mesh.dim) group_names[g.tag] = g.name;
  std::vector<Section> out;
  for (auto& [tag, section] : by_tag) {
    section.name =
        tag == 0 ? names.of("cells", tag, "cells") : names.of(group_names[tag], tag, "group");
    out.push_back(std::move(section));
  }
  return out;
}

// A section per facet group with facets, named as the group (the BC's name too).
std::vector<Section> facet_sections(const InputMesh& mesh, const WrittenGroups& groups,
                                    UniqueNames& names) {
  std::vector<Section> out;
  const TaggedEntities& facets = mesh.facets;
  const CurvedFacets curved(mesh);
  for (const PhysicalGroup& g : groups.all) {
    if (g.dim != mesh.dim - 1) continue;
    Section s;
    for (PetscInt k = 0; k < facets.size(); ++k) {
      if (facets.tags[k] != g.tag) continue;
      PetscInt points[9];
      const int n = curved.points(k, points);
      cgsize_t v[9];
      for (int j = 0; j < n; ++j) v[j] = points[j] + 1;
      s.add(cgns_facet_type(mesh.dim, n), v, n);
    }
    if (s.types.empty()) continue;
    s.name = names.of(g.name, g.tag, "boundary");
    out.push_back(std::move(s));
  }
  return out;
}

// Writes a section from element `start` on; returns the id of its last element.
cgsize_t write_section(const CgnsFile& file, int base, int zone, const Section& s, cgsize_t start) {
  const auto end = start + static_cast<cgsize_t>(s.types.size()) - 1;
  const bool mixed =
      std::any_of(s.types.begin(), s.types.end(), [&](auto t) { return t != s.types.front(); });
  int index = 0;
  if (!mixed) {
    file.check(cg_section_write(file.id(), base, zone, s.name.c_str(), s.types.front(), start, end,
                                0, s.nodes.data(), &index),
               "writing a section");
    return end;
  }
  std::vector<cgsize_t> data, offsets = {0};
  for (std::size_t e = 0, at = 0; e < s.types.size(); ++e) {
    int n = 0;
    cg_npe(s.types[e], &n);
    data.push_back(s.types[e]);
    data.insert(data.end(), s.nodes.begin() + at, s.nodes.begin() + at + n);
    offsets.push_back(static_cast<cgsize_t>(data.size()));
    at += n;
  }
  file.check(cg_poly_section_write(file.id(), base, zone, s.name.c_str(), CGNS_ENUMV(MIXED), start,
                                   end, 0, data.data(), offsets.data(), &index),
             "writing a section");
  return end;
}

void write_coordinates(const CgnsFile& file, int base, int zone, const InputMesh& mesh,
                       int num_dim) {
  const std::vector<double> xyz = points_in_space(mesh);
  const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  std::vector<double> c(mesh.num_points());
  for (int i = 0; i < num_dim; ++i) {
    for (PetscInt v = 0; v < mesh.num_points(); ++v) c[v] = xyz[3 * v + i];
    int index = 0;
    file.check(
        cg_coord_write(file.id(), base, zone, CGNS_ENUMV(RealDouble), names[i], c.data(), &index),
        "writing the coordinates");
  }
}

// The CGNS type an array is written as: its own where CGNS has it, else the next wider one.
CGNS_ENUMT(DataType_t) cgns_type(ValueType type) {
  switch (type) {
    case ValueType::Float32:
      return CGNS_ENUMV(RealSingle);
    case ValueType::Float64:
      return CGNS_ENUMV(RealDouble);
    case ValueType::UInt32:
    case ValueType::Int64:
    case ValueType::UInt64:
      return CGNS_ENUMV(LongInteger);
    default:
      return CGNS_ENUMV(Integer);
  }
}

// One field of a FlowSolution: component k of `values` (`components` per entity) as `type`.
void write_field(const CgnsFile& file, int base, int zone, int solution, const std::string& name,
                 CGNS_ENUMT(DataType_t) type, const std::vector<double>& values, int components,
                 int k) {
  const std::size_t n = values.size() / components;
  auto pick = [&]<typename T>(T) {
    std::vector<T> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<T>(values[components * i + k]);
    return out;
  };
  int index = 0;
  const std::string what = fmt::format("writing the data '{}'", name);
  if (type == CGNS_ENUMV(RealDouble)) {
    const auto v = pick(double{});
    file.check(
        cg_field_write(file.id(), base, zone, solution, type, name.c_str(), v.data(), &index),
        what);
  } else if (type == CGNS_ENUMV(RealSingle)) {
    const auto v = pick(float{});
    file.check(
        cg_field_write(file.id(), base, zone, solution, type, name.c_str(), v.data(), &index),
        what);
  } else if (type == CGNS_ENUMV(LongInteger)) {
    const auto v = pick(cglong_t{});
    file.check(
        cg_field_write(file.id(), base, zone, solution, type, name.c_str(), v.data(), &index),
        what);
  } else {
    const auto v = pick(int{});
    file.check(
        cg_field_write(file.id(), base, zone, solution, type, name.c_str(), v.data(), &index),
        what);
  }
}

// The input's arrays at `location` as one FlowSolution, a field per component: "vX", "vY", "vZ"
// for a vector of 2 or 3 components (the SIDS' convention), "v_0", "v_1", ... for more
// (read_cgns joins them back). Names are cut to CGNS' 32 characters. neomesh's own fields are
// not written: a solution at cell centres beside sections of boundary faces is valid CGNS, but
// meshio's reader refuses such a file, and a file without data should stay readable to it.
void write_solution(const CgnsFile& file, int base, int zone, const char* name,
                    CGNS_ENUMT(GridLocation_t) location, const std::vector<DataArray>& data) {
  if (data.empty()) return;
  int solution = 0;
  file.check(cg_sol_write(file.id(), base, zone, name, location, &solution),
             "writing a flow solution");
  auto write = [&](const std::string& array, CGNS_ENUMT(DataType_t) type,
                   const std::vector<double>& values, int components) {
    for (int k = 0; k < components; ++k) {
      std::string field = array;
      if (components > 1)
        field += components <= 3 ? std::string(1, "XYZ"[k]) : fmt::format("_{}", k);
      if (field.size() > 32) field.resize(32);
      write_field(file, base, zone, solution, field, type, values, components, k);
    }
  };
  for (const DataArray& a : data) write(a.name, cgns_type(a.type), a.values, a.components);
}

}  // namespace

void write_cgns(const GatheredMesh& g, const std::filesystem::path& path,
                const std::string& target) {
  const InputMesh& mesh = g.mesh;
  const WrittenGroups groups = physical_groups(mesh);
  UniqueNames names;
  const std::vector<Section> cells = cell_sections(mesh, groups, names);
  const std::vector<Section> facets = facet_sections(mesh, groups, names);

  CgnsFile file(path, CgnsFile::Mode::Create, target);
  const int num_dim = mesh.dim == 2 && !mesh.plane && !mesh.surface ? 2 : 3;
  int base = 0, zone = 0;
  file.check(cg_base_write(file.id(), "Base", mesh.dim, num_dim, &base), "writing the base");
  const cgsize_t size[3] = {static_cast<cgsize_t>(mesh.num_points()),
                            static_cast<cgsize_t>(mesh.num_cells()), 0};
  file.check(cg_zone_write(file.id(), base, "Zone", size, CGNS_ENUMV(Unstructured), &zone),
             "writing the zone");
  write_coordinates(file, base, zone, mesh, num_dim);
  cgsize_t last = 0;
  for (const Section& s : cells) last = write_section(file, base, zone, s, last + 1);
  for (const Section& s : facets) {
    const cgsize_t range[2] = {last + 1, write_section(file, base, zone, s, last + 1)};
    last = range[1];
    int bc = 0;
    file.check(cg_boco_write(file.id(), base, zone, s.name.c_str(), CGNS_ENUMV(BCTypeUserDefined),
                             CGNS_ENUMV(PointRange), 2, range, &bc),
               "writing a boundary condition");
    file.check(
        cg_boco_gridlocation_write(file.id(), base, zone, bc,
                                   mesh.dim == 3 ? CGNS_ENUMV(FaceCenter) : CGNS_ENUMV(EdgeCenter)),
        "writing a boundary condition");
  }
  write_solution(file, base, zone, "VertexData", CGNS_ENUMV(Vertex), mesh.point_data);
  write_solution(file, base, zone, "CellData", CGNS_ENUMV(CellCenter), mesh.cell_data);
  file.close();
}

}  // namespace neomesh
