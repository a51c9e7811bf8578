#include "mesh/cgns_reader.hpp"

#include <algorithm>
#include <map>

#include "core/error.hpp"
#include "mesh/cell_order.hpp"
#include "mesh/cgns_file.hpp"
#include "mesh/input_file.hpp"

namespace neomesh {

namespace {

// The base and zone read (the only ones).
constexpr int kBase = 1, kZone = 1;

// A section's elements: their types, and their 1-based nodes (CSR).
struct Section {
  std::string name;
  cgsize_t start = 0, end = 0;  // element ids, inclusive
  std::vector<CgnsElement> elements;
  std::vector<cgsize_t> offsets = {0}, nodes;
};

class CgnsReader {
 public:
  explicit CgnsReader(const std::filesystem::path& path)
      : file_(path, CgnsFile::Mode::Read, path.string()) {
    int bases = 0, zones = 0;
    file_.check(cg_nbases(id(), &bases), "reading the bases");
    if (bases != 1) fail("{}: has {} bases; neomesh reads files of one base", name(), bases);
    file_.check(cg_nzones(id(), kBase, &zones), "reading the zones");
    if (zones != 1)
      fail("{}: has {} zones; neomesh reads one zone (join them first, e.g. in Pointwise)", name(),
           zones);
    CGNS_ENUMT(ZoneType_t) type;
    file_.check(cg_zone_type(id(), kBase, kZone, &type), "reading the zone");
    if (type != CGNS_ENUMV(Unstructured))
      fail("{}: its zone is a structured grid; neomesh reads unstructured zones", name());
  }

  int id() const { return file_.id(); }
  const std::string& name() const { return file_.name(); }
  void check(int status, std::string_view what) const { file_.check(status, what); }

  // x, y, z of every node (z = 0 without CoordinateZ).
  std::vector<double> coordinates() {
    char zone[33];
    cgsize_t size[3];
    file_.check(cg_zone_read(id(), kBase, kZone, zone, size), "reading the zone");
    int count = 0;
    file_.check(cg_ncoords(id(), kBase, kZone, &count), "reading the coordinates");
    std::vector<double> xyz(3 * static_cast<std::size_t>(size[0]), 0.0), c(size[0]);
    const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
    for (int i = 0; i < std::min(count, 3); ++i) {
      cgsize_t first = 1, last = size[0];
      file_.check(cg_coord_read(id(), kBase, kZone, names[i], CGNS_ENUMV(RealDouble), &first, &last,
                                c.data()),
                  fmt::format("reading {} (neomesh reads Cartesian coordinates)", names[i]));
      for (cgsize_t v = 0; v < size[0]; ++v) xyz[3 * v + i] = c[v];
    }
    return xyz;
  }

  std::vector<Section> sections() {
    int count = 0;
    file_.check(cg_nsections(id(), kBase, kZone, &count), "reading the sections");
    std::vector<Section> out;
    for (int s = 1; s <= count; ++s) out.push_back(section(s));
    std::sort(out.begin(), out.end(),
              [](const auto& a, const auto& b) { return a.start < b.start; });
    return out;
  }

 private:
  Section section(int s) {
    Section out;
    char name[33] = {};
    CGNS_ENUMT(ElementType_t) type;
    int boundary = 0, parents = 0;
    file_.check(cg_section_read(id(), kBase, kZone, s, name, &type, &out.start, &out.end, &boundary,
                                &parents),
                "reading a section");
    out.name = name;
    cgsize_t size = 0;
    file_.check(cg_ElementDataSize(id(), kBase, kZone, s, &size), "reading a section");
    const auto kind = cgns_element(type);
    if (!kind && type != CGNS_ENUMV(MIXED)) refuse(out.name, type);
    const cgsize_t n = out.end - out.start + 1;
    std::vector<cgsize_t> data(size), offsets(n + 1);
    if (type == CGNS_ENUMV(MIXED)) {
      file_.check(
          cg_poly_elements_read(id(), kBase, kZone, s, data.data(), offsets.data(), nullptr),
          fmt::format("reading section '{}'", out.name));
    } else {
      file_.check(cg_elements_read(id(), kBase, kZone, s, data.data(), nullptr),
                  fmt::format("reading section '{}'", out.name));
    }
    for (cgsize_t e = 0, at = 0; e < n; ++e) {
      const auto t =
          type == CGNS_ENUMV(MIXED) ? static_cast<CGNS_ENUMT(ElementType_t)>(data[at++]) : type;
      const auto element = t == type ? kind : cgns_element(t);
      if (!element) refuse(out.name, t);
      out.elements.push_back(*element);
      out.nodes.insert(out.nodes.end(), data.begin() + at, data.begin() + at + element->nodes);
      out.offsets.push_back(static_cast<cgsize_t>(out.nodes.size()));
      at += element->nodes;
    }
    return out;
  }

  [[noreturn]] void refuse(const std::string& section, CGNS_ENUMT(ElementType_t) type) const {
    fail(
        "{}: section '{}' has {} elements; neomesh reads linear ones (NODE, BAR_2, TRI_3, QUAD_4, "
        "TETRA_4, PYRA_5, PENTA_6, HEXA_8), alone or in MIXED sections",
        name(), section, cg_ElementTypeName(type));
  }

  CgnsFile file_;
};

// Group tags by name, in the order the names first come.
struct Names {
  std::map<std::string, int> tag;
  int of(const std::string& name, int dim, InputMesh& mesh) {
    const auto [it, added] = tag.try_emplace(name, static_cast<int>(tag.size()) + 1);
    if (added) mesh.groups.push_back({dim, it->second, name});
    return it->second;
  }
};

// The element of id `e`: its section and index there, or none.
std::optional<std::pair<Section*, cgsize_t>> element(std::vector<Section>& sections, cgsize_t e) {
  const auto s = std::upper_bound(sections.begin(), sections.end(), e,
                                  [](cgsize_t x, const Section& y) { return x < y.start; });
  if (s == sections.begin() || e > (s - 1)->end) return std::nullopt;
  return std::pair(&*(s - 1), e - (s - 1)->start);
}

class MeshBuilder {
 public:
  MeshBuilder(CgnsReader& reader, std::vector<Section>& sections, InputMesh& mesh)
      : reader_(reader), sections_(sections), mesh_(mesh) {}

  void number_vertices(const std::vector<double>& xyz) {
    const auto nn = static_cast<cgsize_t>(xyz.size() / 3);
    vertex_.assign(nn, -1);
    for (const Section& s : sections_)
      for (std::size_t e = 0; e < s.elements.size(); ++e) {
        if (s.elements[e].dim != mesh_.dim) continue;
        for (cgsize_t k = s.offsets[e]; k < s.offsets[e + 1]; ++k) {
          if (s.nodes[k] < 1 || s.nodes[k] > nn)
            fail("{}: element {} of section '{}' refers to node {}, which is out of range (1..{})",
                 reader_.name(), s.start + static_cast<cgsize_t>(e), s.name, s.nodes[k], nn);
          vertex_[s.nodes[k] - 1] = 0;
        }
      }
    number_used_vertices(vertex_, xyz, reader_.name(), mesh_);
  }

  void add_cells() {
    Names names;
    for (const Section& s : sections_)
      for (std::size_t e = 0; e < s.elements.size(); ++e) {
        const CgnsElement& kind = s.elements[e];
        if (kind.dim != mesh_.dim) continue;
        PetscInt v[8];
        for (int j = 0; j < kind.nodes; ++j)
          v[gmsh_from_canonical(*kind.cell)[j]] = vertex_[s.nodes[s.offsets[e] + j] - 1];
        mesh_.add_cell(*kind.cell, v, names.of(s.name, mesh_.dim, mesh_));
        mesh_.element_tag.push_back(s.start + static_cast<std::int64_t>(e));
      }
  }

  // Returns how many there are.
  int add_boundary_conditions() {
    int count = 0;
    const int id = reader_.id();
    check(cg_nbocos(id, kBase, kZone, &count), "reading the boundary conditions");
    for (int bc = 1; bc <= count; ++bc) {
      char name[33] = {};
      CGNS_ENUMT(BCType_t) type;
      CGNS_ENUMT(PointSetType_t) set;
      CGNS_ENUMT(GridLocation_t) location;
      CGNS_ENUMT(DataType_t) normal_type;
      cgsize_t size = 0, normals = 0;
      int normal_index[3], datasets = 0;
      check(cg_boco_info(id, kBase, kZone, bc, name, &type, &set, &size, normal_index, &normals,
                         &normal_type, &datasets),
            "reading a boundary condition");
      check(cg_boco_gridlocation_read(id, kBase, kZone, bc, &location),
            "reading a boundary condition");
      std::vector<cgsize_t> points(std::max<cgsize_t>(size, 2));
      check(cg_boco_read(id, kBase, kZone, bc, points.data(), nullptr),
            fmt::format("reading boundary condition '{}'", name));
      const bool range = set == CGNS_ENUMV(PointRange) || set == CGNS_ENUMV(ElementRange);
      if (range) {
        const cgsize_t first = points[0], last = points[1];
        points.clear();
        for (cgsize_t p = first; p <= last; ++p) points.push_back(p);
      } else {
        points.resize(size);
      }
      const std::string group = family(bc).value_or(name);
      const bool at_vertices = location == CGNS_ENUMV(Vertex) && set != CGNS_ENUMV(ElementRange) &&
                               set != CGNS_ENUMV(ElementList);
      if (at_vertices)
        add_vertex_set(group, points);
      else
        add_facets(name, names_.of(group, mesh_.dim - 1, mesh_), points);
    }
    return count;
  }

  // For a zone without BCs: the facet elements, a group per section. (With BCs, sections of
  // facets often repeat a BC's patch, which would make it two boundary parts.)
  void add_section_facets() {
    for (const Section& s : sections_)
      for (std::size_t e = 0; e < s.elements.size(); ++e)
        if (s.elements[e].dim == mesh_.dim - 1)
          add_facet(s, e, names_.of(s.name, mesh_.dim - 1, mesh_));
  }

  // The FlowSolutions at vertices and cell centres: the input's point and cell data (neomesh
  // writes them back). Fields named vX, vY(, vZ) or v_0, v_1, ... in a row are one array of
  // that many components, as write_cgns writes them; solutions elsewhere (faces) are left out.
  void add_solutions() {
    const int id = reader_.id();
    int count = 0;
    check(cg_nsols(id, kBase, kZone, &count), "reading the flow solutions");
    char zone[33] = {};
    cgsize_t size[3];
    check(cg_zone_read(id, kBase, kZone, zone, size), "reading the zone");
    for (int s = 1; s <= count; ++s) {
      char solution[33] = {};
      CGNS_ENUMT(GridLocation_t) location;
      check(cg_sol_info(id, kBase, kZone, s, solution, &location), "reading a flow solution");
      const bool at_vertices = location == CGNS_ENUMV(Vertex);
      if (!at_vertices && location != CGNS_ENUMV(CellCenter)) continue;
      const cgsize_t n = at_vertices ? size[0] : size[1];
      if (!at_vertices && n != static_cast<cgsize_t>(mesh_.num_cells())) continue;
      int fields = 0;
      check(cg_nfields(id, kBase, kZone, s, &fields), "reading a flow solution");
      std::vector<DataArray> arrays;
      for (int f = 1; f <= fields; ++f) {
        char name[33] = {};
        CGNS_ENUMT(DataType_t) type;
        check(cg_field_info(id, kBase, kZone, s, f, &type, name), "reading a flow solution");
        std::vector<double> values(n);
        cgsize_t first = 1, last = n;
        check(cg_field_read(id, kBase, kZone, s, name, CGNS_ENUMV(RealDouble), &first, &last,
                            values.data()),
              fmt::format("reading the field '{}' of '{}'", name, solution));
        DataArray a{.name = name, .components = 1, .type = value_type(type), .values = {}};
        if (at_vertices) {
          a.values.assign(mesh_.num_vertices(), 0.0);
          for (cgsize_t v = 0; v < n; ++v)
            if (vertex_[v] >= 0) a.values[vertex_[v]] = values[v];
        } else {
          a.values = std::move(values);
        }
        arrays.push_back(std::move(a));
      }
      std::vector<DataArray>& out = at_vertices ? mesh_.point_data : mesh_.cell_data;
      for (DataArray& a : join_components(std::move(arrays))) out.push_back(std::move(a));
    }
  }

 private:
  void check(int status, std::string_view what) const { reader_.check(status, what); }

  static ValueType value_type(CGNS_ENUMT(DataType_t) type) {
    switch (type) {
      case CGNS_ENUMV(Integer):
        return ValueType::Int32;
      case CGNS_ENUMV(LongInteger):
        return ValueType::Int64;
      case CGNS_ENUMV(RealSingle):
        return ValueType::Float32;
      default:
        return ValueType::Float64;
    }
  }

  // The suffix of component k of an array of `components` (write_cgns' names).
  static std::string suffix(int k, int components) {
    return components <= 3 ? std::string(1, "XYZ"[k]) : fmt::format("_{}", k);
  }

  // Scalar fields vX, vY(, vZ) or v_0, ..., v_{m-1} in a row, of one type, joined into one array
  // v of 2, 3 or m components.
  static std::vector<DataArray> join_components(std::vector<DataArray> fields) {
    std::vector<DataArray> out;
    for (std::size_t i = 0; i < fields.size();) {
      std::size_t joined = 1;
      // vX vY vZ before vX vY; v_0 ... v_{m-1} for any m > 3.
      const std::string& first = fields[i].name;
      int many = 0;
      if (first.size() > 2 && first.ends_with("_0")) {
        const std::string stem = first.substr(0, first.size() - 2);
        while (i + many < fields.size() && fields[i + many].name == stem + suffix(many, 4) &&
               fields[i + many].type == fields[i].type)
          ++many;
      }
      for (int m : {many, 3, 2}) {
        if (m < 2 || (m == many && m <= 3)) continue;
        const std::string tail = suffix(0, m);
        if (first.size() <= tail.size() || !first.ends_with(tail)) continue;
        const std::string stem = first.substr(0, first.size() - tail.size());
        int k = 0;
        while (k < m && i + k < fields.size() && fields[i + k].name == stem + suffix(k, m) &&
               fields[i + k].type == fields[i].type)
          ++k;
        if (k < m) continue;
        DataArray a{.name = stem, .components = m, .type = fields[i].type, .values = {}};
        const std::size_t n = fields[i].values.size();
        a.values.resize(n * m);
        for (int c = 0; c < m; ++c)
          for (std::size_t e = 0; e < n; ++e) a.values[m * e + c] = fields[i + c].values[e];
        out.push_back(std::move(a));
        joined = m;
        break;
      }
      if (joined == 1) out.push_back(std::move(fields[i]));
      i += joined;
    }
    return out;
  }

  std::optional<std::string> family(int bc) {
    char name[33] = {};
    if (cg_goto(reader_.id(), kBase, "Zone_t", kZone, "ZoneBC_t", 1, "BC_t", bc, "end") != CG_OK ||
        cg_famname_read(name) != CG_OK || name[0] == '\0')
      return std::nullopt;
    return std::string(name);
  }

  void add_facets(const std::string& bc, int tag, const std::vector<cgsize_t>& ids) {
    for (cgsize_t e : ids) {
      const auto found = element(sections_, e);
      if (!found || found->first->elements[found->second].dim != mesh_.dim - 1)
        fail("{}: boundary condition '{}' names element {}, which is not a {}", reader_.name(), bc,
             e, mesh_.dim == 3 ? "face (TRI_3, QUAD_4)" : "edge (BAR_2)");
      add_facet(*found->first, found->second, tag);
    }
  }

  void add_facet(const Section& s, std::size_t e, int tag) {
    PetscInt v[4];
    const int n = s.elements[e].nodes;
    for (int j = 0; j < n; ++j) {
      const cgsize_t node = s.nodes[s.offsets[e] + j];
      const bool known = node >= 1 && node <= static_cast<cgsize_t>(vertex_.size());
      const PetscInt p = known ? vertex_[node - 1] : -1;
      if (p < 0)
        fail("{}: the facet element {} of section '{}' is not a facet of any cell", reader_.name(),
             s.start + static_cast<cgsize_t>(e), s.name);
      v[j] = p;
    }
    mesh_.facets.add(v, n, tag);
  }

  // BCs at vertices: vertex sets, whose boundary facets input_topology finds.
  void add_vertex_set(const std::string& group, const std::vector<cgsize_t>& nodes) {
    const int tag = names_.of(group, mesh_.dim - 1, mesh_);
    auto set = std::find_if(mesh_.vertex_sets.begin(), mesh_.vertex_sets.end(),
                            [&](const VertexSet& s) { return s.tag == tag; });
    if (set == mesh_.vertex_sets.end()) {
      mesh_.vertex_sets.push_back({group, tag, {}, ""});
      set = mesh_.vertex_sets.end() - 1;
    }
    for (cgsize_t n : nodes)
      if (n >= 1 && n <= static_cast<cgsize_t>(vertex_.size()) && vertex_[n - 1] >= 0)
        set->vertices.push_back(vertex_[n - 1]);
  }

  CgnsReader& reader_;
  std::vector<Section>& sections_;
  InputMesh& mesh_;
  std::vector<PetscInt> vertex_;
  Names names_;  // of the facet groups
};

}  // namespace

InputMesh read_cgns(const std::filesystem::path& path) {
  check_regular_file(path);
  CgnsReader reader(path);
  std::vector<Section> sections = reader.sections();
  InputMesh mesh;
  mesh.dim = 0;
  for (const Section& s : sections)
    for (const CgnsElement& e : s.elements) mesh.dim = std::max(mesh.dim, e.dim);
  if (mesh.dim < 2) fail("{}: has no 2D or 3D elements", reader.name());
  MeshBuilder builder(reader, sections, mesh);
  builder.number_vertices(reader.coordinates());
  builder.add_cells();
  if (builder.add_boundary_conditions() == 0) builder.add_section_facets();
  builder.add_solutions();
  std::sort(mesh.groups.begin(), mesh.groups.end(), [](const auto& a, const auto& b) {
    return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
  });
  return mesh;
}

}  // namespace neomesh
