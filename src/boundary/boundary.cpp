#include "boundary/boundary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace neomesh {

namespace {

// A facet as its sorted local vertex indices; edges and triangles have fewer than 4 vertices
// and fill the unused slots with kNone, which sorts last.
using Facet = std::array<PetscInt, 4>;
constexpr PetscInt kNone = std::numeric_limits<PetscInt>::max();

// The facets of a cell in canonical order (cell_type.hpp): a simplex' facet leaves out one
// vertex; a Q1 cell's facet ξ_j = ±1 holds the vertices whose bit j is 0 or 1.
void add_facets(CellType type, const PetscInt* cell, std::vector<Facet>& facets) {
  const int nv = num_vertices(type);
  const int d = dimension(type);
  auto add = [&](auto&& in_facet) {
    Facet f{kNone, kNone, kNone, kNone};
    int n = 0;
    for (int i = 0; i < nv; ++i)
      if (in_facet(i)) f[n++] = cell[i];
    std::sort(f.begin(), f.end());
    facets.push_back(f);
  };
  if (is_simplex(type)) {
    for (int left_out = 0; left_out < nv; ++left_out) add([&](int i) { return i != left_out; });
  } else {
    for (int j = 0; j < d; ++j)
      for (int side = 0; side < 2; ++side) add([&](int i) { return ((i >> j) & 1) == side; });
  }
}

// Facets of exactly one cell whose vertices all lie on the boundary. A facet between two
// ranks' cells appears once on each rank: the candidates of all ranks are compared by their
// global vertex numbers, and only those that appear once in the whole mesh are kept.
std::vector<Facet> boundary_facets(const MeshView& view, const DofMap& dofs) {
  std::vector<Facet> facets;
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c) add_facets(block.type, block.cell(c), facets);
  std::sort(facets.begin(), facets.end());
  std::vector<Facet> candidates;
  for (std::size_t i = 0; i < facets.size();) {
    std::size_t j = i + 1;
    while (j < facets.size() && facets[j] == facets[i]) ++j;
    const bool on_boundary = std::all_of(facets[i].begin(), facets[i].end(), [&](PetscInt v) {
      return v == kNone || view.on_boundary[v];
    });
    if (j == i + 1 && on_boundary) candidates.push_back(facets[i]);
    i = j;
  }

  auto global_key = [&](const Facet& f) {
    Facet key;
    for (int i = 0; i < 4; ++i)
      key[i] = f[i] == kNone ? kNone : dofs.global_dof()[f[i] * view.dim] / view.dim;
    std::sort(key.begin(), key.end());
    return key;
  };
  std::vector<PetscInt> mine;
  for (const Facet& f : candidates) {
    const Facet key = global_key(f);
    mine.insert(mine.end(), key.begin(), key.end());
  }
  int ranks = 1;
  MPI_Comm_size(dofs.comm(), &ranks);
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(ranks), offsets(ranks, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, dofs.comm());
  for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<PetscInt> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(mine.data(), count, MPIU_INT, all.data(), counts.data(), offsets.data(), MPIU_INT,
                 dofs.comm());
  std::vector<Facet> everywhere(all.size() / 4);
  for (std::size_t i = 0; i < everywhere.size(); ++i)
    std::copy_n(all.begin() + 4 * i, 4, everywhere[i].begin());
  std::sort(everywhere.begin(), everywhere.end());

  std::vector<Facet> boundary;
  for (const Facet& f : candidates) {
    const auto [first, last] =
        std::equal_range(everywhere.begin(), everywhere.end(), global_key(f));
    if (last - first == 1) boundary.push_back(f);
  }
  return boundary;
}

// The axis j with x_j equal at all vertices of the facet (up to round-off relative to its
// size), or −1 if the facet is not in an axis-aligned plane.
int normal_axis(const MeshView& view, const Facet& facet) {
  const int d = view.dim;
  const double* x0 = &view.coords[facet[0] * d];
  std::array<double, 3> spread{};
  for (PetscInt v : facet) {
    if (v == kNone) break;
    for (int j = 0; j < d; ++j)
      spread[j] = std::max(spread[j], std::abs(view.coords[v * d + j] - x0[j]));
  }
  const double size = *std::max_element(spread.begin(), spread.begin() + d);
  for (int j = 0; j < d; ++j)
    if (spread[j] <= 1e-12 * size) return j;
  return -1;
}

}  // namespace

BoundaryMode parse_boundary_mode(std::string_view name) {
  if (name == "fixed") return BoundaryMode::Fixed;
  if (name == "slide") return BoundaryMode::Slide;
  fail("unknown boundary mode '{}' (expected fixed or slide)", name);
}

std::string_view name(BoundaryMode mode) {
  return mode == BoundaryMode::Fixed ? "fixed" : "slide";
}

std::vector<std::uint8_t> fixed_dofs(const MeshView& view, const DofMap& dofs, BoundaryMode mode) {
  const int d = view.dim;
  std::vector<double> fixed(static_cast<std::size_t>(view.num_vertices) * d, 0.0);
  if (mode == BoundaryMode::Fixed) {
    for (PetscInt v = 0; v < view.num_vertices; ++v)
      if (view.on_boundary[v]) std::fill_n(fixed.begin() + v * d, d, 1.0);
  } else {
    for (const Facet& facet : boundary_facets(view, dofs)) {
      const int axis = normal_axis(view, facet);
      for (PetscInt v : facet) {
        if (v == kNone) break;
        for (int j = 0; j < d; ++j)
          if (axis < 0 || j == axis) fixed[v * d + j] = 1.0;
      }
    }
  }
  // A coordinate is fixed if any rank fixes it: sum the flags at the owners, send them back.
  OwnedVec global = dofs.create_global_vector();
  dofs.add_local_to_global(fixed, global);
  dofs.global_to_local(global, fixed);
  std::vector<std::uint8_t> result(fixed.size());
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    // A boundary vertex without a boundary facet on any rank (should not happen in a valid
    // mesh) stays put rather than roam freely.
    const bool free = std::all_of(fixed.begin() + v * d, fixed.begin() + (v + 1) * d,
                                  [](double f) { return f == 0.0; });
    for (int j = 0; j < d; ++j)
      result[v * d + j] = fixed[v * d + j] > 0.0 || (view.on_boundary[v] && free);
  }
  return result;
}

}  // namespace neomesh
