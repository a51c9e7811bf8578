#include <neomesh/curve.hpp>

#include "boundary/curve_boundary.hpp"
#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "formats/mesh_io.hpp"
#include "mesh/plex_mesh.hpp"
#include "mesh/raise_order.hpp"

namespace neomesh {

Mesh curve_mesh(const std::vector<std::filesystem::path>& inputs, const CurveOptions& options,
                CurveSummary* summary, MPI_Comm comm) {
  if (inputs.empty()) fail("no mesh file given");
  if (options.order != 2) fail("--order {}: neomesh raises meshes to order 2 only", options.order);
  const double before = resident_bytes();
  CurvedBoundarySummary placed;
  auto plex = std::make_unique<PlexMesh>(load_mesh(inputs, comm, false, [&](InputMesh& input) {
    raise_to_second_order(input);
    placed = place_boundary_nodes(input, options.shapes);
  }));
  if (summary) {
    double values[5] = {static_cast<double>(placed.vertices_on_geometry),
                        static_cast<double>(placed.nodes_on_geometry),
                        static_cast<double>(placed.nodes_straight), placed.max_vertex_move,
                        placed.max_off_geometry};
    MPI_Bcast(values, 5, MPI_DOUBLE, 0, comm);
    *summary = {static_cast<std::int64_t>(values[0]), static_cast<std::int64_t>(values[1]),
                static_cast<std::int64_t>(values[2]), values[3], values[4]};
  }
  return Mesh(std::move(plex), before);
}

}  // namespace neomesh
