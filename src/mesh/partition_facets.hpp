// PartitionFacets: the facets a rank's cells share with cells of other ranks. Cells are
// partitioned without overlap (mesh_view.hpp), so a cell next to the partition's edge does not
// see its neighbour; algorithms that look across facets (the interface of a level set,
// boundary/interface.hpp) exchange per-facet values through this instead.
//
// Facets are matched by their vertices' input numbers, which every rank knows: each rank sends
// the facets its cells have no local neighbour across to a rank chosen by their vertices, which
// pairs the ones two ranks sent. On one process there are none and nothing is communicated.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/mesh_view.hpp"

namespace neomesh {

class PartitionFacets {
 public:
  struct Facet {
    PetscInt cell = 0;         // the local cell
    int facet = 0;             // its facet (CellFacts::facets)
    int rank = 0;              // the rank of the cell across it
    PetscInt remote_cell = 0;  // that cell's input number (MeshView::global_cell)
  };

  // Collective. `open[c * kMaxFacets + f]` is 1 for the facets of local cells with no local cell
  // across them (the domain's boundary and the partition's).
  PartitionFacets(const MeshView& view, MPI_Comm comm, std::span<const std::uint8_t> open);

  static constexpr int kMaxFacets = 6;

  MPI_Comm comm() const { return comm_; }
  // The facets shared with other ranks, in the same order on both sides of each rank pair.
  const std::vector<Facet>& facets() const { return facets_; }

  // Collective: the values the other side passed for facets(), in the same order.
  std::vector<std::uint8_t> exchange(std::span<const std::uint8_t> values) const;

 private:
  MPI_Comm comm_;
  std::vector<Facet> facets_;
  std::vector<int> send_counts_, send_offsets_;  // per rank, into facets_ (grouped by rank)
};

}  // namespace neomesh
