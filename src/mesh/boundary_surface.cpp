#include "mesh/boundary_surface.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace neomesh {

PetscInt BoundarySurface::find(PetscInt input_number) const {
  const auto it = std::lower_bound(input_vertex.begin(), input_vertex.end(), input_number);
  return it != input_vertex.end() && *it == input_number ? it - input_vertex.begin() : -1;
}

namespace {

// Per facet of the table: the index into MeshView::parts of its facet group, or -1. Parts are
// the facet and point groups in the order of mesh.groups (as input_topology's mark_parts).
std::vector<int> facet_parts(const InputMesh& mesh, const FacetTable& table,
                             const InputTopology& topology, std::vector<std::string>& part_chart) {
  std::vector<int> part(mesh.surface ? mesh.num_cells() : table.size(), -1);
  int index = 0;
  const int part_dim = mesh.surface ? mesh.dim : mesh.dim - 1;
  for (const PhysicalGroup& g : mesh.groups) {
    if (g.dim != part_dim && g.dim != 0) continue;
    std::string chart;
    for (const VertexSet& set : mesh.vertex_sets)
      if (set.tag == g.tag) chart = set.chart;
    part_chart.push_back(chart);
    if (mesh.surface && g.dim == mesh.dim) {
      for (PetscInt c = 0; c < mesh.num_cells(); ++c)
        if (mesh.cell_tags[c] == g.tag && part[c] < 0) part[c] = index;
    } else if (g.dim == mesh.dim - 1) {
      const TaggedEntities& f = topology.facets;
      for (PetscInt k = 0; k < f.size(); ++k) {
        if (f.tags[k] != g.tag) continue;
        const PetscInt t = table.find(f.vertices.data() + f.offsets[k],
                                      static_cast<int>(f.offsets[k + 1] - f.offsets[k]));
        if (t >= 0 && part[t] < 0) part[t] = index;
      }
    }
    ++index;
  }
  return part;
}

template <typename T>
void broadcast_vector(std::vector<T>& v, MPI_Datatype type, MPI_Comm comm) {
  long long n = static_cast<long long>(v.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, comm);
  v.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(v.data(), static_cast<int>(n), type, 0, comm);
}

nlohmann::json to_json(const Chart& c) {
  return {{"name", c.name},          {"kind", static_cast<int>(c.kind)},
          {"extruded", c.extruded},  {"origin", c.origin},
          {"offset", c.offset},      {"angles", c.angles},
          {"centre", c.centre},      {"radius", c.radius},
          {"points", c.points},      {"vertices", c.vertices},
          {"triangles", c.triangles}};
}

Chart chart_from_json(const nlohmann::json& j) {
  Chart c;
  c.name = j["name"];
  c.kind = static_cast<Chart::Kind>(j["kind"].get<int>());
  c.centre = j["centre"];
  c.radius = j["radius"];
  c.points = j["points"].get<std::vector<double>>();
  c.extruded = j["extruded"];
  c.origin = j["origin"];
  c.offset = j["offset"];
  c.angles = j["angles"];
  c.vertices = j["vertices"].get<std::vector<std::int64_t>>();
  c.triangles = j["triangles"].get<std::vector<std::int64_t>>();
  return c;
}

// A surface mesh's own cells, its facets: quadrilaterals in cyclic order (tensor order 0 1 3 2).
void add_cells_as_facets(const InputMesh& mesh, const std::vector<int>& part, BoundarySurface& s) {
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const PetscInt* v = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    if (mesh.cell_types[c] == CellType::Triangle)
      s.facet_vertices.insert(s.facet_vertices.end(), {v[0], v[1], v[2]});
    else
      s.facet_vertices.insert(s.facet_vertices.end(), {v[0], v[1], v[3], v[2]});
    s.facet_offsets.push_back(static_cast<PetscInt>(s.facet_vertices.size()));
    s.facet_part.push_back(part[c]);
  }
}

}  // namespace

BoundarySurface boundary_surface(const InputMesh& mesh, const FacetTable& table,
                                 const InputTopology& topology) {
  BoundarySurface s;
  s.dim = mesh.coord_dim();
  s.charts = mesh.charts;
  const std::vector<int> part = facet_parts(mesh, table, topology, s.part_chart);
  for (PetscInt v = 0; v < mesh.num_vertices(); ++v)
    if (topology.on_boundary[v]) {
      s.input_vertex.push_back(v);
      s.coords.insert(s.coords.end(), mesh.coords.begin() + v * s.dim,
                      mesh.coords.begin() + (v + 1) * s.dim);
    }
  if (mesh.surface) {  // every vertex, in input order: boundary vertex v is input vertex v
    add_cells_as_facets(mesh, part, s);
    return s;
  }
  for (PetscInt f = 0; f < table.size(); ++f) {
    if (!table.on_boundary(f)) continue;
    PetscInt v[4];
    const int n = table.vertices(f, v);
    for (int i = 0; i < n; ++i) s.facet_vertices.push_back(s.find(v[i]));
    s.facet_offsets.push_back(static_cast<PetscInt>(s.facet_vertices.size()));
    s.facet_part.push_back(part[f]);
  }
  return s;
}

void broadcast(BoundarySurface& s, MPI_Comm comm) {
  MPI_Bcast(&s.dim, 1, MPI_INT, 0, comm);
  broadcast_vector(s.input_vertex, MPIU_INT, comm);
  broadcast_vector(s.coords, MPI_DOUBLE, comm);
  broadcast_vector(s.facet_offsets, MPIU_INT, comm);
  broadcast_vector(s.facet_vertices, MPIU_INT, comm);
  broadcast_vector(s.facet_part, MPI_INT, comm);
  // Names and charts are small: sent as JSON text.
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string text;
  if (rank == 0) {
    nlohmann::json j = {{"part_chart", s.part_chart}, {"charts", nlohmann::json::array()}};
    for (const Chart& c : s.charts) j["charts"].push_back(to_json(c));
    text = j.dump();
  }
  std::vector<char> bytes(text.begin(), text.end());
  broadcast_vector(bytes, MPI_CHAR, comm);
  if (rank != 0) {
    const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end());
    s.part_chart = j["part_chart"].get<std::vector<std::string>>();
    s.charts.clear();
    for (const auto& c : j["charts"]) s.charts.push_back(chart_from_json(c));
  }
}

}  // namespace neomesh
