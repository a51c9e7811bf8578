#include "geometry/surface_orientation.hpp"

#include <cmath>

#include <mpi.h>

#include "core/error.hpp"
#include "geometry/surface_frame.hpp"

namespace neomesh {

namespace {

// A fold k cells across is found in about k rounds; one round confirms an unfolded surface.
constexpr int kFoldRounds = 16;

Vector<3> point(std::span<const double> coords, PetscInt v) {
  return Eigen::Map<const Vector<3>>(coords.data() + 3 * v);
}

// Per polygon its own unit normal (Newell's; zero without area) and per vertex slot its
// interior angle there.
struct OwnNormals {
  std::vector<Vector<3>> normal;
  std::vector<double> angle;
};

OwnNormals own_normals(std::span<const PetscInt> offsets, std::span<const PetscInt> vertices,
                       std::span<const double> coords) {
  const std::size_t polygons = offsets.size() - 1;
  OwnNormals own{std::vector<Vector<3>>(polygons, Vector<3>::Zero()),
                 std::vector<double>(vertices.size())};
#pragma omp parallel for schedule(static)
  for (std::size_t p = 0; p < polygons; ++p) {
    const PetscInt first = offsets[p], n = offsets[p + 1] - first;
    Vector<3> newell = Vector<3>::Zero();
    for (PetscInt i = 0; i < n; ++i) {
      const Vector<3> x = point(coords, vertices[first + i]);
      const Vector<3> next = point(coords, vertices[first + (i + 1) % n]);
      const Vector<3> previous = point(coords, vertices[first + (i + n - 1) % n]);
      newell += x.cross(next);
      const Vector<3> a = next - x, b = previous - x;
      own.angle[first + i] = std::atan2(a.cross(b).norm(), a.dot(b));
    }
    const double length = newell.norm();
    if (length > 0.0) own.normal[p] = newell / length;
  }
  return own;
}

// Per vertex the sum of the angle-weighted normals of its polygons, each reversed where
// `folded`.
std::vector<double> vertex_normals(std::span<const PetscInt> offsets,
                                   std::span<const PetscInt> vertices, std::size_t num_vertices,
                                   const OwnNormals& own, const std::vector<std::uint8_t>& folded,
                                   const DofMap* dofs) {
  std::vector<double> sum(3 * num_vertices, 0.0);
  for (std::size_t p = 0; p + 1 < offsets.size(); ++p) {
    const Vector<3> normal = folded[p] ? Vector<3>(-own.normal[p]) : own.normal[p];
    for (PetscInt s = offsets[p]; s < offsets[p + 1]; ++s)
      Eigen::Map<Vector<3>>(sum.data() + 3 * vertices[s]) += own.angle[s] * normal;
  }
  if (dofs) dofs->sum_over_ranks(sum);
  return sum;
}

}  // namespace

std::vector<std::uint8_t> folded_polygons(std::span<const PetscInt> offsets,
                                          std::span<const PetscInt> vertices,
                                          std::span<const double> coords, const DofMap* dofs) {
  const OwnNormals own = own_normals(offsets, vertices, coords);
  std::vector<std::uint8_t> folded(offsets.size() - 1, 0);
  for (int round = 0; round < kFoldRounds; ++round) {
    const std::vector<double> vertex_normal =
        vertex_normals(offsets, vertices, coords.size() / 3, own, folded, dofs);
    int changed = 0;
#pragma omp parallel for schedule(static) reduction(| : changed)
    for (std::size_t p = 0; p < folded.size(); ++p) {
      Vector<3> around = Vector<3>::Zero();
      for (PetscInt s = offsets[p]; s < offsets[p + 1]; ++s)
        around += point(vertex_normal, vertices[s]);
      const std::uint8_t against = own.normal[p].dot(around) < 0.0;
      changed |= against != folded[p];
      folded[p] = against;
    }
    if (dofs) MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT, MPI_MAX, dofs->comm());
    if (!changed) break;
  }
  return folded;
}

std::vector<double> surface_reference_normals(const MeshView& view, std::span<const double> coords,
                                              const DofMap* dofs) {
  if (!view.surface) fail("surface_reference_normals: not a surface mesh");
  if (coords.size() != 3 * static_cast<std::size_t>(view.num_vertices))
    fail("surface_reference_normals: {} coordinates for {} vertices", coords.size(),
         view.num_vertices);
  // The cells in cyclic order (a quadrilateral's tensor order 0 1 2 3 runs 0 1 3 2).
  std::vector<PetscInt> offsets{0}, vertices;
  for (const CellBlock& block : view.blocks) {
    const bool quadrilateral = block.type == CellType::Quadrilateral;
    if (!quadrilateral && block.type != CellType::Triangle)
      fail("a surface cell is a triangle or a quadrilateral, not a {}", name(block.type));
    for (PetscInt c = 0; c < block.size(); ++c) {
      const PetscInt* cell = block.cell(c);
      if (quadrilateral)
        vertices.insert(vertices.end(), {cell[0], cell[1], cell[3], cell[2]});
      else
        vertices.insert(vertices.end(), cell, cell + 3);
      offsets.push_back(static_cast<PetscInt>(vertices.size()));
    }
  }
  const std::vector<std::uint8_t> folded = folded_polygons(offsets, vertices, coords, dofs);
  std::vector<double> normals(3 * static_cast<std::size_t>(view.num_cells), 0.0);
  for (const CellBlock& block : view.blocks)
    visit_cell_type(block.type, [&]<CellType Type>(CellTag<Type>) {
      if constexpr (CellTraits<Type>::dim == 2) {
        constexpr int n = CellTraits<Type>::vertices;
        for (PetscInt c = 0; c < block.size(); ++c) {
          Eigen::Matrix<double, 3, n> x;
          for (int i = 0; i < n; ++i) x.col(i) = point(coords, block.cell(c)[i]);
          const PetscInt cell = block.first_cell + c;
          if (const std::optional<Vector<3>> normal = surface_cell_normal<Type>(x))
            Eigen::Map<Vector<3>>(normals.data() + 3 * cell) = folded[cell] ? -*normal : *normal;
        }
      }
    });
  return normals;
}

}  // namespace neomesh
