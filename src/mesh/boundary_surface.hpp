// BoundarySurface: the boundary of the input mesh — its facets, the coordinates of their
// vertices, the physical group each facet is in and the FEAT3 charts — the same on every rank.
// It is what sliding boundary vertices slide on (boundary/): captured once, before the first
// step, so that vertices stay on the *input's* boundary however far they move, and built on
// rank 0 from the whole input mesh, so that serial and distributed runs see the same geometry.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <mpi.h>
#include <petscsys.h>

#include "mesh/chart.hpp"
#include "mesh/facet_table.hpp"
#include "mesh/input_mesh.hpp"
#include "mesh/input_topology.hpp"

namespace neomesh {

struct BoundarySurface {
  int dim = 2;
  std::vector<PetscInt> input_vertex;  // per boundary vertex: its input number, ascending
  std::vector<double> coords;          // per boundary vertex: `dim` input coordinates
  // Per facet (edge in 2D, triangle or quadrilateral in 3D): its boundary vertices (indices
  // into input_vertex) in cyclic order, CSR.
  std::vector<PetscInt> facet_offsets = {0};
  std::vector<PetscInt> facet_vertices;
  // Per facet: the index into MeshView::parts of the facet group it is in, or -1.
  std::vector<int> facet_part;
  // Per MeshView::parts entry: the name of the chart the part lies on, or empty.
  std::vector<std::string> part_chart;
  std::vector<Chart> charts;

  PetscInt num_vertices() const { return static_cast<PetscInt>(input_vertex.size()); }
  // Facet f's boundary vertices, in cyclic order.
  std::span<const PetscInt> facet(PetscInt f) const {
    return {facet_vertices.data() + facet_offsets[f],
            static_cast<std::size_t>(facet_offsets[f + 1] - facet_offsets[f])};
  }
  PetscInt num_facets() const { return static_cast<PetscInt>(facet_part.size()); }
  // The boundary vertex with this input number, or -1.
  PetscInt find(PetscInt input_number) const;
};

// From the whole input mesh (rank 0): its boundary facets and the groups input_topology found.
BoundarySurface boundary_surface(const InputMesh& mesh, const FacetTable& table,
                                 const InputTopology& topology);

// Sends rank 0's surface to every rank of `comm`.
void broadcast(BoundarySurface& surface, MPI_Comm comm);

}  // namespace neomesh
