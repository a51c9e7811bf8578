// SizeField::vertex_metric and read_vertex_metric: a metric per vertex of a mesh, interpolated
// over the mesh as it is when the field is made (targets/background_metric.hpp).
#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>

#include <neomesh/mesh.hpp>
#include <neomesh/size_field.hpp>

#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "mesh/gather.hpp"
#include "mesh/plex_mesh.hpp"
#include "targets/background_metric.hpp"

namespace neomesh {

namespace {

// The whole mesh (`gathered` on rank 0) with a metric per vertex from `numbers(v)` (the numbers
// given for input vertex v), checked; then on every process. Collective; an error on rank 0 is
// thrown on every process.
template <typename Numbers>
BackgroundMesh background(const PlexMesh& plex, const GatheredMesh& gathered,
                          const Numbers& numbers) {
  BackgroundMesh mesh;
  std::string error;
  if (mpi_rank(plex.comm()) == 0) try {
      const InputMesh& m = gathered.mesh;
      const int d = m.dim;
      mesh.dim = d;
      mesh.coords = m.coords;
      mesh.types = m.cell_types;
      mesh.offsets.assign(m.cell_offsets.begin(), m.cell_offsets.end());
      mesh.vertices.assign(m.cell_vertices.begin(), m.cell_vertices.end());
      mesh.metrics.resize(static_cast<std::size_t>(m.num_vertices()) * d * d);
      for (PetscInt v = 0; v < m.num_vertices(); ++v)
        unpack_metric(d, numbers(v, d), std::span(mesh.metrics).subspan(v * d * d, d * d),
                      fmt::format("vertex {} ({:.4g})", v,
                                  fmt::join(std::span(m.coords).subspan(v * d, d), ", ")));
    } catch (const Error& e) {
      error = e.what();
    }
  throw_if_any(plex.comm(), error);
  broadcast(mesh, plex.comm());
  return mesh;
}

}  // namespace

SizeField SizeField::vertex_metric(const Mesh& mesh, const std::string& array) {
  const PlexMesh& plex = mesh.plex();
  const GatheredMesh gathered = gather_mesh(plex, {});  // with the input's arrays, on rank 0
  const DataArray* data = nullptr;
  std::string error;
  if (mpi_rank(plex.comm()) == 0) {
    const auto& arrays = gathered.mesh.point_data;
    const auto it = std::find_if(arrays.begin(), arrays.end(),
                                 [&](const DataArray& a) { return a.name == array; });
    if (it == arrays.end()) {
      std::vector<std::string> names;
      for (const DataArray& a : arrays) names.push_back(a.name);
      error = fmt::format("{} has no point data '{}' (it has: {})", mesh.name(), array,
                          names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", ")));
    } else {
      data = &*it;
    }
  }
  throw_if_any(plex.comm(), error);
  BackgroundMesh background_mesh =
      background(plex, gathered, [data](PetscInt v, int) -> std::span<const double> {
        return std::span(data->values).subspan(v * data->components, data->components);
      });
  auto metric = std::make_shared<const BackgroundMetric>(std::move(background_mesh));
  SizeField field(fmt::format("the metric '{}' per vertex of {}", array, mesh.name()),
                  metric->dim(), {});
  field.metric_ = [metric](std::span<const double> p, std::span<double> m) { (*metric)(p, m); };
  return field;
}

SizeField SizeField::read_vertex_metric(const Mesh& mesh, const std::filesystem::path& file) {
  const PlexMesh& plex = mesh.plex();
  std::vector<std::vector<double>> lines;
  std::string error;
  if (mpi_rank(plex.comm()) == 0) try {
      std::ifstream in(file);
      if (!in) fail("cannot open the metric file {}", file.string());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank lines
        std::istringstream words(line);
        std::vector<double> values;
        std::string word;
        while (words >> word) {
          char* end = nullptr;
          values.push_back(std::strtod(word.c_str(), &end));
          if (end != word.c_str() + word.size())
            fail("{}:{}: expected numbers, got '{}'", file.string(), number, word);
        }
        lines.push_back(std::move(values));
      }
      if (static_cast<PetscInt>(lines.size()) != plex.global_num_vertices())
        fail("the metric file {} has {} metrics but the mesh has {} vertices", file.string(),
             lines.size(), plex.global_num_vertices());
    } catch (const Error& e) {
      error = e.what();
    }
  throw_if_any(plex.comm(), error);
  BackgroundMesh background_mesh =
      background(plex, gather_mesh(plex, {}),
                 [&lines](PetscInt v, int) -> std::span<const double> { return lines[v]; });
  auto metric = std::make_shared<const BackgroundMetric>(std::move(background_mesh));
  SizeField field(fmt::format("the metric per vertex from {}", file.string()), metric->dim(), {});
  field.metric_ = [metric](std::span<const double> p, std::span<double> m) { (*metric)(p, m); };
  return field;
}

}  // namespace neomesh
