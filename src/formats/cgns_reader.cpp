#include "formats/cgns_reader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <map>
#include <set>
#include <unordered_map>

#include "core/error.hpp"
#include "core/union_find.hpp"
#include "formats/cgns_file.hpp"
#include "formats/input_file.hpp"
#include "mesh/cell_order.hpp"

namespace neomesh {

namespace {

// The base read (the only one).
constexpr int kBase = 1;

// The CGNS type of cgsize_t, in which cg_conn_read gives the donor points.
constexpr auto kSizeType = sizeof(cgsize_t) == 4 ? CGNS_ENUMV(Integer) : CGNS_ENUMV(LongInteger);

// A section's elements: their types, and their 1-based nodes (CSR).
struct Section {
  std::string name;
  cgsize_t start = 0, end = 0;  // element ids, inclusive
  std::vector<CgnsElement> elements;
  std::vector<cgsize_t> offsets = {0}, nodes;
};

// A zone: its sections, and where its nodes and elements start in the whole file's numbering
// (the zones' nodes one after the other; element ids likewise, for messages).
struct Zone {
  int index = 0;  // 1-based, as the CGNS library numbers zones
  std::string name;
  cgsize_t nodes = 0, cells = 0;
  std::int64_t first_node = 0, first_element = 0;
  std::vector<Section> sections;  // by start
};

class CgnsReader {
 public:
  explicit CgnsReader(const std::filesystem::path& path)
      : file_(path, CgnsFile::Mode::Read, path.string()) {
    int bases = 0, zones = 0;
    file_.check(cg_nbases(id(), &bases), "reading the bases");
    if (bases != 1) fail("{}: has {} bases; neomesh reads files of one base", name(), bases);
    file_.check(cg_nzones(id(), kBase, &zones), "reading the zones");
    if (zones < 1) fail("{}: has no zone", name());
    std::int64_t first_node = 0, first_element = 0;
    for (int z = 1; z <= zones; ++z) {
      Zone& zone = zones_.emplace_back();
      zone.index = z;
      char zone_name[33] = {};
      cgsize_t size[3];
      file_.check(cg_zone_read(id(), kBase, z, zone_name, size), "reading the zones");
      zone.name = zone_name;
      CGNS_ENUMT(ZoneType_t) type;
      file_.check(cg_zone_type(id(), kBase, z, &type), "reading the zones");
      if (type != CGNS_ENUMV(Unstructured))
        fail("{}: zone '{}' is a structured grid; neomesh reads unstructured zones", name(),
             zone.name);
      zone.nodes = size[0];
      zone.cells = size[1];
      zone.first_node = first_node;
      zone.first_element = first_element;
      zone.sections = sections(z);
      first_node += zone.nodes;
      for (const Section& s : zone.sections)
        first_element = std::max(first_element, zone.first_element + s.end);
    }
  }

  int id() const { return file_.id(); }
  const std::string& name() const { return file_.name(); }
  void check(int status, std::string_view what) const { file_.check(status, what); }
  std::vector<Zone>& zones() { return zones_; }
  std::int64_t num_nodes() const { return zones_.back().first_node + zones_.back().nodes; }

  // x, y, z of every node of every zone, zone after zone (z = 0 without CoordinateZ).
  std::vector<double> coordinates() {
    std::vector<double> xyz(3 * static_cast<std::size_t>(num_nodes()), 0.0);
    for (const Zone& zone : zones_) {
      int count = 0;
      file_.check(cg_ncoords(id(), kBase, zone.index, &count), "reading the coordinates");
      std::vector<double> c(zone.nodes);
      const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
      for (int i = 0; i < std::min(count, 3); ++i) {
        cgsize_t first = 1, last = zone.nodes;
        file_.check(cg_coord_read(id(), kBase, zone.index, names[i], CGNS_ENUMV(RealDouble), &first,
                                  &last, c.data()),
                    fmt::format("reading {} (neomesh reads Cartesian coordinates)", names[i]));
        for (cgsize_t v = 0; v < zone.nodes; ++v) xyz[3 * (zone.first_node + v) + i] = c[v];
      }
    }
    return xyz;
  }

 private:
  std::vector<Section> sections(int zone) {
    int count = 0;
    file_.check(cg_nsections(id(), kBase, zone, &count), "reading the sections");
    std::vector<Section> out;
    for (int s = 1; s <= count; ++s) out.push_back(section(zone, s));
    std::sort(out.begin(), out.end(),
              [](const auto& a, const auto& b) { return a.start < b.start; });
    return out;
  }

  Section section(int zone, int s) {
    Section out;
    char name[33] = {};
    CGNS_ENUMT(ElementType_t) type;
    int boundary = 0, parents = 0;
    file_.check(cg_section_read(id(), kBase, zone, s, name, &type, &out.start, &out.end, &boundary,
                                &parents),
                "reading a section");
    out.name = name;
    cgsize_t size = 0;
    file_.check(cg_ElementDataSize(id(), kBase, zone, s, &size), "reading a section");
    const auto kind = cgns_element(type);
    if (!kind && type != CGNS_ENUMV(MIXED)) refuse(out.name, type);
    const cgsize_t n = out.end - out.start + 1;
    std::vector<cgsize_t> data(size), offsets(n + 1);
    if (type == CGNS_ENUMV(MIXED)) {
      file_.check(cg_poly_elements_read(id(), kBase, zone, s, data.data(), offsets.data(), nullptr),
                  fmt::format("reading section '{}'", out.name));
    } else {
      file_.check(cg_elements_read(id(), kBase, zone, s, data.data(), nullptr),
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
        "TETRA_4, PYRA_5, PENTA_6, HEXA_8) and second-order ones (BAR_3, TRI_6, QUAD_8, QUAD_9, "
        "TETRA_10, HEXA_20, HEXA_27), alone or in MIXED sections",
        name(), section, cg_ElementTypeName(type));
  }

  CgnsFile file_;
  std::vector<Zone> zones_;
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

// The element of id `e` of a zone: its section and index there, or none.
std::optional<std::pair<const Section*, cgsize_t>> element(const std::vector<Section>& sections,
                                                           cgsize_t e) {
  const auto s = std::upper_bound(sections.begin(), sections.end(), e,
                                  [](cgsize_t x, const Section& y) { return x < y.start; });
  if (s == sections.begin() || e > (s - 1)->end) return std::nullopt;
  return std::pair(&*(s - 1), e - (s - 1)->start);
}

// The arrays of one zone's flow solutions: per node of the zone and per cell of the zone.
struct ZoneData {
  std::vector<DataArray> point, cell;
};

class MeshBuilder {
 public:
  MeshBuilder(CgnsReader& reader, InputMesh& mesh) : reader_(reader), mesh_(mesh) {}

  // Joins the zones' nodes (by their 1-to-1 connectivities, or where their coordinates are
  // equal) and numbers those cells use.
  void number_vertices(const std::vector<double>& xyz) {
    const std::int64_t nn = reader_.num_nodes();
    // (joined nodes are named by their smallest node: their first zone's)
    UnionFind joined(nn);
    if (reader_.zones().size() > 1 && !join_by_connectivity(joined)) join_coinciding(xyz, joined);
    vertex_.assign(nn, -1);
    node_.assign(nn, -1);
    std::optional<std::string> first;  // a section of cells, and whether they are curved
    bool curved = false;
    for (const Zone& zone : reader_.zones())
      for (const Section& s : zone.sections)
        for (std::size_t e = 0; e < s.elements.size(); ++e) {
          const CgnsElement& kind = s.elements[e];
          if (kind.dim != mesh_.dim) continue;
          if (first && curved != kind.curved.has_value())
            fail(
                "{}: mixes first-order and second-order cells (sections '{}' and '{}'); neomesh "
                "reads meshes of one order",
                reader_.name(), *first, s.name);
          if (!first) first = s.name, curved = kind.curved.has_value();
          for (cgsize_t k = s.offsets[e]; k < s.offsets[e + 1]; ++k) {
            if (s.nodes[k] < 1 || s.nodes[k] > zone.nodes)
              fail(
                  "{}: element {} of section '{}' refers to node {}, which is out of range "
                  "(1..{})",
                  reader_.name(), s.start + static_cast<cgsize_t>(e), s.name, s.nodes[k],
                  zone.nodes);
            (k - s.offsets[e] < kind.corners
                 ? vertex_
                 : node_)[joined.find(zone.first_node + s.nodes[k] - 1)] = 0;
          }
        }
    number_used_vertices(vertex_, xyz, reader_.name(), mesh_);
    number_high_order_nodes(node_, vertex_, xyz, reader_.name(), mesh_);
    for (std::int64_t n = 0; n < nn; ++n) {
      vertex_[n] = vertex_[joined.find(n)];
      node_[n] = node_[joined.find(n)];
    }
  }

  void add_cells() {
    for (Zone& zone : reader_.zones()) {
      PetscInt cells = 0;
      for (const Section& s : zone.sections)
        for (std::size_t e = 0; e < s.elements.size(); ++e) {
          const CgnsElement& kind = s.elements[e];
          if (kind.dim != mesh_.dim) continue;
          const cgsize_t* nodes = s.nodes.data() + s.offsets[e];
          if (kind.curved && std::set<cgsize_t>(nodes, nodes + kind.nodes).size() !=
                                 static_cast<std::size_t>(kind.nodes))
            fail("{}: element {} of section '{}' has a repeated node", reader_.name(),
                 s.start + static_cast<cgsize_t>(e), s.name);
          PetscInt v[8];
          for (int j = 0; j < kind.corners; ++j)
            v[gmsh_from_canonical(*kind.cell)[j]] = vertex(zone, nodes[j]);
          mesh_.add_cell(*kind.cell, v, cell_names_.of(s.name, mesh_.dim, mesh_));
          if (kind.curved) {
            PetscInt gmsh[kMaxCurvedNodes];
            for (int j = kind.corners; j < kind.nodes; ++j)
              gmsh[facts(*kind.curved).cgns_order[j]] = node_[zone.first_node + nodes[j] - 1];
            mesh_.high_order.add(*kind.curved, gmsh + kind.corners);
          }
          mesh_.element_tag.push_back(zone.first_element + s.start + static_cast<std::int64_t>(e));
          ++cells;
        }
      cells_.push_back(cells);
    }
  }

  // The boundary conditions of each zone, or in a zone without any, its sections' facets.
  void add_boundaries() {
    for (const Zone& zone : reader_.zones())
      if (add_boundary_conditions(zone) == 0) add_section_facets(zone);
  }

  // The FlowSolutions at vertices and cell centres: the input's point and cell data (neomesh
  // writes them back). Fields named vX, vY(, vZ) or v_0, v_1, ... in a row are one array of
  // that many components, as write_cgns writes them; solutions elsewhere (faces) are left out.
  // Of several zones, the arrays every zone has (by name and components); a vertex that zones
  // share takes its first zone's value.
  void add_solutions() {
    std::vector<ZoneData> zones;
    for (const Zone& zone : reader_.zones()) zones.push_back(solutions(zone));
    auto in_every_zone = [&](const DataArray& a, std::vector<DataArray> ZoneData::*where) {
      std::vector<const DataArray*> found;
      for (const ZoneData& z : zones) {
        const auto it = std::find_if((z.*where).begin(), (z.*where).end(), [&](const auto& b) {
          return b.name == a.name && b.components == a.components;
        });
        if (it == (z.*where).end()) return std::vector<const DataArray*>{};
        found.push_back(&*it);
      }
      return found;
    };
    for (std::size_t i = 0; i < zones[0].point.size(); ++i) {
      const DataArray& first = zones[0].point[i];
      // (a zone's own array where it has one; the first of a name in the others)
      std::vector<const DataArray*> parts = in_every_zone(first, &ZoneData::point);
      if (parts.empty()) continue;
      parts[0] = &first;
      const int m = first.components;
      DataArray a{.name = first.name, .components = m, .type = first.type, .values = {}};
      a.values.assign(static_cast<std::size_t>(mesh_.num_vertices()) * m, 0.0);
      for (std::size_t z = parts.size(); z-- > 0;) {  // the first zone written last
        const Zone& zone = reader_.zones()[z];
        for (cgsize_t n = 0; n < zone.nodes; ++n)
          if (const PetscInt v = vertex_[zone.first_node + n]; v >= 0)
            std::copy_n(parts[z]->values.begin() + n * m, m, a.values.begin() + v * m);
      }
      mesh_.point_data.push_back(std::move(a));
    }
    for (std::size_t i = 0; i < zones[0].cell.size(); ++i) {
      const DataArray& first = zones[0].cell[i];
      std::vector<const DataArray*> parts = in_every_zone(first, &ZoneData::cell);
      if (parts.empty()) continue;
      parts[0] = &first;
      DataArray a{
          .name = first.name, .components = first.components, .type = first.type, .values = {}};
      for (const DataArray* p : parts)
        a.values.insert(a.values.end(), p->values.begin(), p->values.end());
      mesh_.cell_data.push_back(std::move(a));
    }
  }

 private:
  void check(int status, std::string_view what) const { reader_.check(status, what); }

  // The vertex of a zone's node (1-based): -1 for one no cell uses.
  PetscInt vertex(const Zone& zone, cgsize_t node) const {
    return node >= 1 && node <= zone.nodes ? vertex_[zone.first_node + node - 1] : -1;
  }

  // Joins the nodes that the zones' 1-to-1 connectivities pair (Abutting1to1 at Vertex, a
  // PointList or PointRange with a PointListDonor, as Pointwise writes between its blocks).
  // Returns whether there were any.
  bool join_by_connectivity(UnionFind& joined) {
    const int id = reader_.id();
    const std::vector<Zone>& zones = reader_.zones();
    bool any = false;
    for (const Zone& zone : zones) {
      int count = 0;
      check(cg_nconns(id, kBase, zone.index, &count), "reading the zone connectivity");
      for (int c = 1; c <= count; ++c) {
        char name[33] = {}, donor[33] = {};
        CGNS_ENUMT(GridLocation_t) location;
        CGNS_ENUMT(GridConnectivityType_t) type;
        CGNS_ENUMT(PointSetType_t) set, donor_set;
        CGNS_ENUMT(ZoneType_t) donor_type;
        CGNS_ENUMT(DataType_t) donor_data_type;
        cgsize_t size = 0, donor_size = 0;
        check(cg_conn_info(id, kBase, zone.index, c, name, &location, &type, &set, &size, donor,
                           &donor_type, &donor_set, &donor_data_type, &donor_size),
              "reading the zone connectivity");
        if (type != CGNS_ENUMV(Abutting1to1) || location != CGNS_ENUMV(Vertex) ||
            donor_set != CGNS_ENUMV(PointListDonor) ||
            (set != CGNS_ENUMV(PointList) && set != CGNS_ENUMV(PointRange)))
          continue;
        const auto other = std::find_if(zones.begin(), zones.end(),
                                        [&](const Zone& z) { return z.name == donor; });
        if (other == zones.end())
          fail("{}: the connectivity '{}' of zone '{}' names the zone '{}', which the base lacks",
               reader_.name(), name, zone.name, donor);
        std::vector<cgsize_t> points(std::max<cgsize_t>(size, 2)), donors(donor_size);
        check(cg_conn_read(id, kBase, zone.index, c, points.data(), kSizeType, donors.data()),
              fmt::format("reading the connectivity '{}'", name));
        if (set == CGNS_ENUMV(PointRange)) {
          const cgsize_t first = points[0], last = points[1];
          points.clear();
          for (cgsize_t p = first; p <= last; ++p) points.push_back(p);
        } else {
          points.resize(size);
        }
        if (points.size() != donors.size())
          fail("{}: the connectivity '{}' of zone '{}' pairs {} points with {} donor points",
               reader_.name(), name, zone.name, points.size(), donors.size());
        for (std::size_t k = 0; k < points.size(); ++k) {
          if (points[k] < 1 || points[k] > zone.nodes || donors[k] < 1 || donors[k] > other->nodes)
            fail("{}: the connectivity '{}' of zone '{}' names a node out of range", reader_.name(),
                 name, zone.name);
          joined.join(zone.first_node + points[k] - 1, other->first_node + donors[k] - 1);
        }
        any = true;
      }
    }
    return any;
  }

  // Joins each node to an earlier zone's node of bitwise equal coordinates (nodes of one zone
  // stay apart, as meshers may repeat nodes along a cut).
  void join_coinciding(const std::vector<double>& xyz, UnionFind& joined) {
    using Key = std::array<std::uint64_t, 3>;
    struct Hash {
      std::size_t operator()(const Key& k) const {
        return std::hash<std::uint64_t>()(k[0] ^ (k[1] * 0x9e3779b97f4a7c15ULL) ^
                                          (k[2] * 0xc2b2ae3d27d4eb4fULL));
      }
    };
    std::unordered_map<Key, std::int64_t, Hash> earlier;
    for (const Zone& zone : reader_.zones()) {
      std::vector<std::pair<Key, std::int64_t>> own;
      for (std::int64_t n = zone.first_node; n < zone.first_node + zone.nodes; ++n) {
        const Key key = {std::bit_cast<std::uint64_t>(xyz[3 * n]),
                         std::bit_cast<std::uint64_t>(xyz[3 * n + 1]),
                         std::bit_cast<std::uint64_t>(xyz[3 * n + 2])};
        if (const auto it = earlier.find(key); it != earlier.end()) joined.join(it->second, n);
        own.emplace_back(key, n);
      }
      for (const auto& [key, n] : own) earlier.try_emplace(key, n);
    }
  }

  // Returns how many there are.
  int add_boundary_conditions(const Zone& zone) {
    int count = 0;
    const int id = reader_.id(), z = zone.index;
    check(cg_nbocos(id, kBase, z, &count), "reading the boundary conditions");
    for (int bc = 1; bc <= count; ++bc) {
      char name[33] = {};
      CGNS_ENUMT(BCType_t) type;
      CGNS_ENUMT(PointSetType_t) set;
      CGNS_ENUMT(GridLocation_t) location;
      CGNS_ENUMT(DataType_t) normal_type;
      cgsize_t size = 0, normals = 0;
      int normal_index[3], datasets = 0;
      check(cg_boco_info(id, kBase, z, bc, name, &type, &set, &size, normal_index, &normals,
                         &normal_type, &datasets),
            "reading a boundary condition");
      check(cg_boco_gridlocation_read(id, kBase, z, bc, &location), "reading a boundary condition");
      std::vector<cgsize_t> points(std::max<cgsize_t>(size, 2));
      check(cg_boco_read(id, kBase, z, bc, points.data(), nullptr),
            fmt::format("reading boundary condition '{}'", name));
      const bool range = set == CGNS_ENUMV(PointRange) || set == CGNS_ENUMV(ElementRange);
      if (range) {
        const cgsize_t first = points[0], last = points[1];
        points.clear();
        for (cgsize_t p = first; p <= last; ++p) points.push_back(p);
      } else {
        points.resize(size);
      }
      const std::string group = family(z, bc).value_or(name);
      const bool at_vertices = location == CGNS_ENUMV(Vertex) && set != CGNS_ENUMV(ElementRange) &&
                               set != CGNS_ENUMV(ElementList);
      if (at_vertices)
        add_vertex_set(zone, group, points);
      else
        add_facets(zone, name, names_.of(group, mesh_.dim - 1, mesh_), points);
    }
    return count;
  }

  // For a zone without BCs: the facet elements, a group per section. (With BCs, sections of
  // facets often repeat a BC's patch, which would make it two boundary parts.)
  void add_section_facets(const Zone& zone) {
    for (const Section& s : zone.sections)
      for (std::size_t e = 0; e < s.elements.size(); ++e)
        if (s.elements[e].dim == mesh_.dim - 1)
          add_facet(zone, s, e, names_.of(s.name, mesh_.dim - 1, mesh_));
  }

  // A zone's arrays at vertices (per node of the zone) and at cell centres.
  ZoneData solutions(const Zone& zone) {
    const int id = reader_.id(), z = zone.index;
    int count = 0;
    check(cg_nsols(id, kBase, z, &count), "reading the flow solutions");
    ZoneData out;
    for (int s = 1; s <= count; ++s) {
      char solution[33] = {};
      CGNS_ENUMT(GridLocation_t) location;
      check(cg_sol_info(id, kBase, z, s, solution, &location), "reading a flow solution");
      const bool at_vertices = location == CGNS_ENUMV(Vertex);
      if (!at_vertices && location != CGNS_ENUMV(CellCenter)) continue;
      const cgsize_t n = at_vertices ? zone.nodes : zone.cells;
      if (!at_vertices && n != cells_[z - 1]) continue;
      int fields = 0;
      check(cg_nfields(id, kBase, z, s, &fields), "reading a flow solution");
      std::vector<DataArray> arrays;
      for (int f = 1; f <= fields; ++f) {
        char name[33] = {};
        CGNS_ENUMT(DataType_t) type;
        check(cg_field_info(id, kBase, z, s, f, &type, name), "reading a flow solution");
        std::vector<double> values(n);
        cgsize_t first = 1, last = n;
        check(cg_field_read(id, kBase, z, s, name, CGNS_ENUMV(RealDouble), &first, &last,
                            values.data()),
              fmt::format("reading the field '{}' of '{}'", name, solution));
        arrays.push_back(
            {.name = name, .components = 1, .type = value_type(type), .values = std::move(values)});
      }
      std::vector<DataArray>& to = at_vertices ? out.point : out.cell;
      for (DataArray& a : join_components(std::move(arrays))) to.push_back(std::move(a));
    }
    return out;
  }

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

  std::optional<std::string> family(int zone, int bc) {
    char name[33] = {};
    if (cg_goto(reader_.id(), kBase, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", bc, "end") != CG_OK ||
        cg_famname_read(name) != CG_OK || name[0] == '\0')
      return std::nullopt;
    return std::string(name);
  }

  void add_facets(const Zone& zone, const std::string& bc, int tag,
                  const std::vector<cgsize_t>& ids) {
    for (cgsize_t e : ids) {
      const auto found = element(zone.sections, e);
      if (!found || found->first->elements[found->second].dim != mesh_.dim - 1)
        fail("{}: boundary condition '{}' names element {}, which is not a {}", reader_.name(), bc,
             e, mesh_.dim == 3 ? "face (TRI_3, QUAD_4)" : "edge (BAR_2)");
      add_facet(zone, *found->first, found->second, tag);
    }
  }

  void add_facet(const Zone& zone, const Section& s, std::size_t e, int tag) {
    PetscInt v[4];
    const int n = s.elements[e].corners;
    for (int j = 0; j < n; ++j) {
      const PetscInt p = vertex(zone, s.nodes[s.offsets[e] + j]);
      if (p < 0)
        fail("{}: the facet element {} of section '{}' is not a facet of any cell", reader_.name(),
             s.start + static_cast<cgsize_t>(e), s.name);
      v[j] = p;
    }
    mesh_.facets.add(v, n, tag);
  }

  // BCs at vertices: vertex sets, whose boundary facets input_topology finds.
  void add_vertex_set(const Zone& zone, const std::string& group,
                      const std::vector<cgsize_t>& nodes) {
    const int tag = names_.of(group, mesh_.dim - 1, mesh_);
    auto set = std::find_if(mesh_.vertex_sets.begin(), mesh_.vertex_sets.end(),
                            [&](const VertexSet& s) { return s.tag == tag; });
    if (set == mesh_.vertex_sets.end()) {
      mesh_.vertex_sets.push_back({group, tag, {}, ""});
      set = mesh_.vertex_sets.end() - 1;
    }
    for (cgsize_t n : nodes)
      if (const PetscInt v = vertex(zone, n); v >= 0) set->vertices.push_back(v);
  }

  CgnsReader& reader_;
  InputMesh& mesh_;
  std::vector<PetscInt> vertex_;  // per node of the file (all zones): its vertex, or -1
  std::vector<PetscInt> node_;    // likewise its high-order node
  std::vector<PetscInt> cells_;   // per zone: how many cells it has
  Names cell_names_, names_;      // of the cell and facet groups
};

}  // namespace

InputMesh read_cgns(const std::filesystem::path& path) {
  check_regular_file(path);
  CgnsReader reader(path);
  InputMesh mesh;
  mesh.dim = 0;
  for (const Zone& zone : reader.zones())
    for (const Section& s : zone.sections)
      for (const CgnsElement& e : s.elements) mesh.dim = std::max(mesh.dim, e.dim);
  if (mesh.dim < 2) fail("{}: has no 2D or 3D elements", reader.name());
  MeshBuilder builder(reader, mesh);
  builder.number_vertices(reader.coordinates());
  builder.add_cells();
  builder.add_boundaries();
  builder.add_solutions();
  check_high_order_nodes(mesh, reader.name());
  // (A curved mesh's point data would need its nodes' values too: it is not carried.)
  if (mesh.curved()) mesh.point_data.clear();
  std::sort(mesh.groups.begin(), mesh.groups.end(), [](const auto& a, const auto& b) {
    return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
  });
  return mesh;
}

}  // namespace neomesh
