// Tables that rank 0 holds by input vertex (MeshView::input_vertex), fetched to each process'
// local vertices: the boundary found on the whole input, a curved mesh's points gathered from
// another partition.
#pragma once

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/petsc.hpp"
#include "mesh/mesh_view.hpp"

namespace neomesh {

class FromInputVertices {
 public:
  // Collective: for the local vertices of `view` (which must outlive this), from tables of
  // `input_vertices` input vertices (rank 0's; 0 elsewhere). The star forest from rank 0 to
  // the local vertices is built here, once for every table fetched; on one process there is
  // none, a fetch is a copy.
  FromInputVertices(const MeshView& view, PetscInt input_vertices, MPI_Comm comm);

  // Collective: `table` (rank 0: k values per input vertex; empty elsewhere) at the local
  // vertices, k values per vertex. T: double, int or std::uint8_t.
  template <typename T>
  std::vector<T> operator()(const std::vector<T>& table, int k = 1) const {
    const std::vector<PetscInt>& input = view_.input_vertex;
    std::vector<T> out(static_cast<std::size_t>(k) * input.size());
    if (!sf_) {
      for (std::size_t v = 0; v < input.size(); ++v)
        std::copy_n(table.begin() + k * input[v], k, out.begin() + k * v);
    } else if constexpr (std::is_same_v<T, double>) {
      broadcast(table.data(), out.data(), MPI_DOUBLE, k);
    } else if constexpr (std::is_same_v<T, int>) {
      broadcast(table.data(), out.data(), MPI_INT, k);
    } else {
      static_assert(std::is_same_v<T, std::uint8_t>, "a table of double, int or std::uint8_t");
      broadcast(table.data(), out.data(), MPI_UNSIGNED_CHAR, k);
    }
    return out;
  }

 private:
  void broadcast(const void* table, void* out, MPI_Datatype type, int k) const;

  const MeshView& view_;
  OwnedSF sf_;  // a leaf per local vertex, its input vertex the root on rank 0
};

}  // namespace neomesh
