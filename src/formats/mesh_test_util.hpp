// Checks shared by the tests of the formats layer (readers, writers, reading a PlexMesh).
#pragma once

#include <algorithm>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/testing/test_data.hpp"

#include "mesh/plex_mesh.hpp"
#include "mesh/validate.hpp"

namespace neomesh::testing {

// The smallest scaled corner Jacobian over the rank's cells, in MeshView's canonical order:
// positive iff every cell is positively oriented.
inline double min_view_jacobian(const MeshView& view) {
  double worst = 1.0;
  double x[8 * 3];
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) {
      for (int i = 0; i < num_vertices(block.type); ++i)
        std::copy_n(view.coords.data() + block.cell(c)[i] * view.dim, view.dim, x + i * view.dim);
      worst = std::min(worst, min_scaled_corner_jacobian(block.type, x));
    }
  return worst;
}

// The message of the Error that `read(path)` throws for a scratch file `name` holding `text`
// ("" if none): how the readers' tests try a bad input.
template <typename Reader>
std::string read_error(const std::string& text, const std::string& name, Reader read) {
  const auto path = scratch_dir("ReaderErrors") / name;
  std::ofstream(path, std::ios::binary) << text;
  try {
    read(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace neomesh::testing
