#include "mesh/validate.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "mesh/collective_error.hpp"

namespace neomesh {

namespace {

// Below this scaled Jacobian a cell counts as degenerate: its volume is rounding noise.
constexpr double kDegenerateJacobian = 1e-12;

double norm(const double* a, int dim) {
  double s = 0;
  for (int d = 0; d < dim; ++d) s += a[d] * a[d];
  return std::sqrt(s);
}

// det[e0, e1(, e2)] / (|e0| |e1| (|e2|)): the sine-like corner quality of edges from a vertex.
double scaled_det(const double (*e)[3], int dim) {
  double det = dim == 2 ? e[0][0] * e[1][1] - e[0][1] * e[1][0]
                        : e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                              e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                              e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  double scale = 1;
  for (int i = 0; i < dim; ++i) scale *= norm(e[i], dim);
  return scale > 0 ? det / scale : 0.0;
}

}  // namespace

double min_scaled_corner_jacobian(CellType type, const double* x) {
  const int dim = dimension(type);
  double e[3][3] = {};
  if (is_simplex(type)) {  // one Jacobian, the edge matrix [x1-x0, x2-x0(, x3-x0)]
    for (int i = 0; i < dim; ++i)
      for (int d = 0; d < dim; ++d) e[i][d] = x[(i + 1) * dim + d] - x[d];
    return scaled_det(e, dim);
  }
  // Tensor order: the neighbour of vertex v along direction j is v ^ (1 << j), and the edge
  // points along +ξ_j when bit j of v is 0.
  double worst = INFINITY;
  for (int v = 0; v < num_vertices(type); ++v) {
    for (int j = 0; j < dim; ++j) {
      const int w = v ^ (1 << j);
      const double sign = (v >> j) & 1 ? -1.0 : 1.0;
      for (int d = 0; d < dim; ++d) e[j][d] = sign * (x[w * dim + d] - x[v * dim + d]);
    }
    worst = std::min(worst, scaled_det(e, dim));
  }
  return worst;
}

std::string find_defect(const InputMesh& mesh) {
  const PetscInt nv = mesh.num_vertices();
  for (PetscInt v = 0; v < nv; ++v)
    for (int d = 0; d < mesh.dim; ++d)
      if (!std::isfinite(mesh.coords[v * mesh.dim + d]))
        return fmt::format("vertex {} (0-based) has a non-finite coordinate ({})", v,
                           mesh.coords[v * mesh.dim + d]);
  for (const VertexSet& set : mesh.vertex_sets)
    for (auto v : set.vertices)
      if (v < 0 || v >= nv)
        return fmt::format("boundary part '{}' refers to vertex {}, but there are {} vertices",
                           set.name, v, nv);
  double x[8 * 3];
  for (PetscInt c = 0; c < mesh.num_cells(); ++c) {
    const CellType type = mesh.cell_types[c];
    if (dimension(type) != mesh.dim)
      return fmt::format("cell {} (0-based) is a {} in a {}D mesh", c, name(type), mesh.dim);
    const PetscInt* cell = mesh.cell_vertices.data() + mesh.cell_offsets[c];
    const int n = num_vertices(type);
    for (int i = 0; i < n; ++i) {
      if (cell[i] < 0 || cell[i] >= nv)
        return fmt::format("cell {} (0-based) refers to vertex {}, but there are {} vertices", c,
                           cell[i], nv);
      for (int j = 0; j < i; ++j)
        if (cell[i] == cell[j])
          return fmt::format("cell {} (0-based) has a repeated vertex ({})", c, cell[i]);
      std::copy_n(mesh.coords.data() + cell[i] * mesh.dim, mesh.dim, x + i * mesh.dim);
    }
    const double q = min_scaled_corner_jacobian(type, x);
    if (q <= kDegenerateJacobian)
      return fmt::format("cell {} (0-based, a {}) is {} (scaled det J = {:.3g})", c, name(type),
                         q < -kDegenerateJacobian ? "inverted" : "degenerate", q);
  }
  return "";
}

void validate(const InputMesh& mesh, const std::string& source, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string defect = rank == 0 ? find_defect(mesh) : "";
  throw_if_any(comm, defect.empty() ? "" : source + ": " + defect);
}

}  // namespace neomesh
