// What rank 0 works out from the whole mesh before distributing it: the facets of the physical
// groups (for the writers) and, per vertex, the boundary and boundary parts (for MeshView).
// Found with a FacetTable, so the DMPlex never needs its edges and faces.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/facet_table.hpp"
#include "mesh/input_mesh.hpp"

namespace neomesh {

struct InputTopology {
  // Facets and points of physical groups, sorted by (tag, vertices): facet vertices in the
  // order DMPlex's facet closure gives (FacetTable::vertices).
  TaggedEntities facets;
  TaggedEntities points;
  // Per input vertex, as in MeshView.
  std::vector<std::uint8_t> on_boundary;
  std::vector<int> boundary_part;
  std::vector<std::uint8_t> part_count;
};

// Vertex sets become the boundary facets all of whose vertices are in the set; set vertices on
// no such facet (an isolated corner) become points, and mesh.groups gets a point group for
// them. Throws Error naming `source` if a facet of mesh.facets is not a facet of its cells.
InputTopology input_topology(InputMesh& mesh, const FacetTable& table, const std::string& source);

}  // namespace neomesh
