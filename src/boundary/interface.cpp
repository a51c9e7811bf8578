#include "boundary/interface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/collective_error.hpp"
#include "core/error.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/partition_facets.hpp"

namespace neomesh {

namespace {

// Passes of the clean-up before it gives up (each pass flips every cell that asks for it).
constexpr int kMaxCleanupPasses = 200;

// The local cell of each block-relative cell number, with its type and vertices.
struct LocalCell {
  CellType type;
  const PetscInt* vertices;  // canonical order
};

std::vector<LocalCell> local_cells(const MeshView& view) {
  std::vector<LocalCell> cells(view.num_cells);
  for (const CellBlock& block : view.blocks)
    for (PetscInt c = 0; c < block.size(); ++c)
      cells[block.first_cell + c] = {block.type, block.cell(c)};
  return cells;
}

// Local vertex k of facet f of the cell, in the facet's cyclic order.
PetscInt facet_vertex(const LocalCell& cell, int f, int k) {
  return cell.vertices[facts(cell.type).facets[f].vertices[k]];
}

int facet_count(const LocalCell& cell) {
  return facts(cell.type).num_facets;
}
int facet_size(const LocalCell& cell, int f) {
  return facts(cell.type).facets[f].size;
}

Point local_point(const MeshView& view, std::span<const double> coords, PetscInt u) {
  Point p = Point::Zero();
  for (int j = 0; j < view.dim; ++j) p[j] = coords[u * view.dim + j];
  return p;
}

// For each facet of each cell, the local cell on its other side (-1 if there is none here):
// neighbour[c * kMaxFacets + f].
constexpr int kMaxFacets = PartitionFacets::kMaxFacets;
std::vector<PetscInt> facet_neighbours(const std::vector<LocalCell>& cells) {
  std::vector<PetscInt> neighbour(cells.size() * kMaxFacets, -1);
  std::map<std::array<PetscInt, 4>, PetscInt> first;  // sorted vertices → c * kMaxFacets + f
  for (PetscInt c = 0; c < static_cast<PetscInt>(cells.size()); ++c) {
    for (int f = 0; f < facet_count(cells[c]); ++f) {
      const int size = facet_size(cells[c], f);
      std::array<PetscInt, 4> key = {-1, -1, -1, -1};
      for (int k = 0; k < size; ++k) key[k] = facet_vertex(cells[c], f, k);
      sort_facet_key(key, size);
      const auto [it, added] = first.emplace(key, c * kMaxFacets + f);
      if (added) continue;
      neighbour[c * kMaxFacets + f] = it->second / kMaxFacets;
      neighbour[it->second] = c;
    }
  }
  return neighbour;
}

// Which side of the interface each cell is on, and the clean-up. `side` holds the local cells'
// sides, then those of the cells across the partition's facets (a copy, refreshed by
// exchanging them); neighbour[c * kMaxFacets + f] indexes it, so that the rules see across.
struct Cleanup {
  const MeshView& view;
  std::span<const double> coords;
  const LevelSetFunction& phi;
  const std::vector<LocalCell>& cells;
  std::vector<PetscInt> neighbour;
  const PartitionFacets& partition;
  std::vector<std::uint8_t> side;

  std::vector<int> interface_facets(PetscInt c) const {
    std::vector<int> out;
    for (int f = 0; f < facet_count(cells[c]); ++f) {
      const PetscInt other = neighbour[c * kMaxFacets + f];
      if (other >= 0 && side[other] != side[c]) out.push_back(f);
    }
    return out;
  }

  bool share_a_vertex(PetscInt c, int f, int g) const {
    for (int a = 0; a < facet_size(cells[c], f); ++a)
      for (int b = 0; b < facet_size(cells[c], g); ++b)
        if (facet_vertex(cells[c], f, a) == facet_vertex(cells[c], g, b)) return true;
    return false;
  }

  // Whether the zero set bends towards cell c: the mean of its interface vertices' feet on
  // the zero set lies on c's side (a chord of a circle lies inside it).
  bool zero_set_bends_towards(PetscInt c, const std::vector<int>& facets) const {
    Point mean = Point::Zero();
    int n = 0;
    for (int f : facets)
      for (int k = 0; k < facet_size(cells[c], f); ++k) {
        mean += phi.to_level(local_point(view, coords, facet_vertex(cells[c], f, k)));
        ++n;
      }
    return (phi.value(mean / n) < 0) == (side[c] != 0);
  }

  bool must_flip(PetscInt c) const {
    const std::vector<int> facets = interface_facets(c);
    if (facets.size() < 2) return false;
    if (is_simplex(cells[c].type)) return true;
    for (std::size_t i = 0; i < facets.size(); ++i)
      for (std::size_t j = i + 1; j < facets.size(); ++j)
        if (!share_a_vertex(c, facets[i], facets[j])) return true;  // opposite facets
    return !zero_set_bends_towards(c, facets);
  }

  // Collective: the sides of the cells across the partition, as they are now.
  void refresh_remote_sides() {
    const auto& facets = partition.facets();
    std::vector<std::uint8_t> mine(facets.size());
    for (std::size_t k = 0; k < facets.size(); ++k) mine[k] = side[facets[k].cell];
    const std::vector<std::uint8_t> theirs = partition.exchange(mine);
    std::copy(theirs.begin(), theirs.end(), side.begin() + view.num_cells);
  }

  // Collective: per local cell, whether it may flip in this pass. Two cells on either side of
  // the partition must not flip together (each decides on the other's old side): a cell next
  // to the partition flips only if it asked to at the start of the pass and no cell across
  // that also asked goes first. The one that goes first is the one that did not just flip,
  // then the one with the smaller input number: a cell that flipped answers its neighbour's
  // flip before it flips back, as it would one after the other on one process. Cells inside
  // the partition flip as they are found, one after the other, as on one process.
  std::vector<std::uint8_t> allowed_to_flip(const std::vector<std::uint8_t>& just_flipped) const {
    std::vector<std::uint8_t> allowed(view.num_cells, 1);
    const auto& facets = partition.facets();
    enum : std::uint8_t { kStays = 0, kAsks = 1, kAsksAgain = 2 };  // again: flipped last pass
    std::vector<std::uint8_t> asks(facets.size());
    for (std::size_t k = 0; k < facets.size(); ++k) {
      const PetscInt c = facets[k].cell;
      asks[k] = !must_flip(c) ? kStays : just_flipped[c] ? kAsksAgain : kAsks;
    }
    const std::vector<std::uint8_t> across = partition.exchange(asks);
    for (std::size_t k = 0; k < facets.size(); ++k) {
      const PetscInt c = facets[k].cell;
      const bool other_first =
          across[k] != kStays &&
          (across[k] < asks[k] ||
           (across[k] == asks[k] && facets[k].remote_cell < view.global_cell[c]));
      if (asks[k] == kStays || other_first) allowed[c] = 0;
    }
    return allowed;
  }

  // Collective: flips cells until no rule asks for it; returns how many flips there were.
  // Throws Error if that does not happen within kMaxCleanupPasses.
  int run() {
    int flipped = 0;
    std::vector<std::uint8_t> just_flipped(view.num_cells, 0);
    for (int pass = 0; pass < kMaxCleanupPasses; ++pass) {
      refresh_remote_sides();
      const std::vector<std::uint8_t> allowed = allowed_to_flip(just_flipped);
      int now = 0;
      for (PetscInt c = 0; c < view.num_cells; ++c) {
        just_flipped[c] = allowed[c] && must_flip(c);
        if (just_flipped[c]) {
          side[c] = !side[c];
          ++now;
        }
      }
      MPI_Allreduce(MPI_IN_PLACE, &now, 1, MPI_INT, MPI_SUM, partition.comm());
      if (now == 0) return flipped;
      flipped += now;
    }
    fail(
        "fit: the interface of {} did not settle: cells were still moved across it after {} "
        "passes of the clean-up",
        phi.expression(), kMaxCleanupPasses);
  }
};

// Collective.
void check_two_sides(MPI_Comm comm, std::span<const std::uint8_t> inside,
                     const LevelSetFunction& phi, const char* when) {
  std::int64_t counts[2] = {std::count(inside.begin(), inside.end(), 1),
                            static_cast<std::int64_t>(inside.size())};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT64_T, MPI_SUM, comm);
  if (counts[0] == 0 || counts[0] == counts[1])
    fail(
        "fit: the level set {} is {} at every cell centre{}: there is no interface inside the "
        "mesh to fit",
        phi.expression(), counts[0] == 0 ? "≥ 0" : "< 0", when);
}

// Marks of local vertices, made complete on every rank that has them: a vertex is marked if
// any rank marked it (a rank sees only the facets of its own cells). Collective.
void share_marks(const DofMap& dofs, std::vector<std::uint8_t>& marks) {
  if (mpi_size(dofs.comm()) == 1) return;
  const int d = dofs.dim();
  std::vector<double> local(marks.size() * d, 0.0);
  for (std::size_t u = 0; u < marks.size(); ++u) local[u * d] = marks[u];
  dofs.sum_over_ranks(local);
  for (std::size_t u = 0; u < marks.size(); ++u) marks[u] = local[u * d] > 0 ? 1 : 0;
}

}  // namespace

Interface find_interface(const MeshView& view, const DofMap& dofs, std::span<const double> coords,
                         const LevelSetFunction& phi) {
  // A surface's facets are its edges, which a level set of space does not cut into two sides.
  if (view.surface)
    fail(
        "fit: a surface mesh (2D cells in space) is not fitted to a level set: adapt it without "
        "--fit");
  const std::vector<LocalCell> cells = local_cells(view);
  std::vector<std::uint8_t> inside(view.num_cells);
  for (PetscInt c = 0; c < view.num_cells; ++c) {
    Point centroid = Point::Zero();
    const int n = num_vertices(cells[c].type);
    for (int i = 0; i < n; ++i) centroid += local_point(view, coords, cells[c].vertices[i]);
    inside[c] = phi.value(centroid / n) < 0;
  }
  check_two_sides(dofs.comm(), inside, phi, "");

  std::vector<PetscInt> neighbour = facet_neighbours(cells);
  std::vector<std::uint8_t> open(neighbour.size());
  for (std::size_t i = 0; i < neighbour.size(); ++i) open[i] = neighbour[i] < 0;
  const PartitionFacets partition(view, dofs.comm(), open);
  for (std::size_t k = 0; k < partition.facets().size(); ++k) {
    const PartitionFacets::Facet& facet = partition.facets()[k];
    neighbour[facet.cell * kMaxFacets + facet.facet] = view.num_cells + static_cast<PetscInt>(k);
  }
  inside.resize(view.num_cells + partition.facets().size());
  Cleanup cleanup{view, coords, phi, cells, std::move(neighbour), partition, std::move(inside)};
  Interface out;
  out.cells_flipped = cleanup.run();
  out.inside.assign(cleanup.side.begin(), cleanup.side.begin() + view.num_cells);
  check_two_sides(dofs.comm(), out.inside, phi,
                  " once the cells with two facets on it are moved across");

  std::vector<std::uint8_t> on_interface(view.num_vertices, 0);
  for (PetscInt c = 0; c < view.num_cells; ++c)
    for (int f : cleanup.interface_facets(c)) {
      for (int k = 0; k < facet_size(cells[c], f); ++k) {
        const PetscInt u = facet_vertex(cells[c], f, k);
        on_interface[u] = 1;
        if (out.inside[c]) out.facet_vertices.push_back(u);  // each facet once: its inside cell's
      }
      if (out.inside[c]) out.offsets.push_back(static_cast<PetscInt>(out.facet_vertices.size()));
    }
  share_marks(dofs, on_interface);
  std::string error;
  for (PetscInt u = 0; u < view.num_vertices; ++u) {
    if (!on_interface[u]) continue;
    if (view.on_boundary[u] && error.empty()) {
      const Point p = local_point(view, coords, u);
      error = fmt::format(
          "fit: the interface of {} reaches the domain's boundary at ({:.4g}, {:.4g}{}); "
          "fitting needs it inside the domain",
          phi.expression(), p[0], p[1], view.dim == 3 ? fmt::format(", {:.4g}", p[2]) : "");
    }
    out.vertices.push_back(u);
  }
  throw_if_any(dofs.comm(), error);
  return out;
}

InterfaceConstraint::InterfaceConstraint(const MeshView& view, const DofMap& dofs,
                                         const LevelSetFunction& phi,
                                         std::vector<PetscInt> vertices, Vec x)
    : view_(view), dofs_(dofs), phi_(phi), vertices_(std::move(vertices)) {
  std::vector<double> local(static_cast<std::size_t>(dofs.num_local_dofs()));
  dofs.global_to_local(x, local);
  for (PetscInt u : vertices_)
    start_level_.push_back(phi.value(point(local.data() + u * view.dim)));
}

Point InterfaceConstraint::point(const double* at) const {
  Point p = Point::Zero();
  for (int j = 0; j < view_.dim; ++j) p[j] = at[j];
  return p;
}

void InterfaceConstraint::set_stage(double s) {
  stage_ = s;
}

// P = I − n nᵀ, w = −n, M = the level set's shape operator (sliding_vertices.hpp), as for a
// boundary that is a surface.
void InterfaceConstraint::tangent_spaces(std::span<const double> x, std::span<double> out) const {
  const int d = view_.dim;
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    const Point p = point(x.data() + vertices_[i] * d);
    const Point n = phi_.gradient(p).normalized();
    const Matrix3 shape = phi_.shape_operator(p);
    double* P = out.data() + i * tangent_space_size(d);
    double* w = P + d * d;
    double* M = w + d;
    for (int a = 0; a < d; ++a) {
      w[a] = -n[a];
      for (int c = 0; c < d; ++c) {
        P[a * d + c] = (a == c ? 1.0 : 0.0) - n[a] * n[c];
        M[a * d + c] = shape(a, c);
      }
    }
  }
}

void InterfaceConstraint::project(Vec x) const {
  const int d = view_.dim;
  PetscInt first = 0;
  NM_PETSC(VecGetOwnershipRange(x, &first, nullptr));
  double* a = nullptr;
  NM_PETSC(VecGetArray(x, &a));
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    const PetscInt u = vertices_[i];
    if (!view_.owned[u]) continue;
    double* at = a + dofs_.global_dof()[u * d] - first;
    const Point q = phi_.to_level(point(at), (1.0 - stage_) * start_level_[i]);
    for (int j = 0; j < d; ++j) at[j] = q[j];
  }
  NM_PETSC(VecRestoreArray(x, &a));
}

double InterfaceConstraint::max_distance(Vec x) const {
  std::vector<double> local(static_cast<std::size_t>(dofs_.num_local_dofs()));
  dofs_.global_to_local(x, local);
  double largest = 0.0;
  for (PetscInt u : vertices_) {
    const Point p = point(local.data() + u * view_.dim);
    largest = std::max(largest, std::abs(phi_.value(p)) / phi_.gradient(p).norm());
  }
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, dofs_.comm());
  return largest;
}

SlidingVertices sliding_vertices(std::shared_ptr<const InterfaceConstraint> constraint) {
  SlidingVertices s;
  s.vertices = constraint->vertices_;
  s.tangent_spaces = [constraint](std::span<const double> x, std::span<double> out) {
    constraint->tangent_spaces(x, out);
  };
  s.project = [constraint](Vec x) { constraint->project(x); };
  return s;
}

SlidingVertices join(SlidingVertices a, SlidingVertices b) {
  if (b.vertices.empty()) return a;
  if (a.vertices.empty()) return b;
  // Position of each joined vertex in a (≥ 0) or b (−1 − position).
  std::vector<PetscInt> from;
  SlidingVertices out;
  std::size_t i = 0, j = 0;
  while (i < a.vertices.size() || j < b.vertices.size()) {
    const bool take_a =
        j == b.vertices.size() || (i < a.vertices.size() && a.vertices[i] < b.vertices[j]);
    if (!take_a && i < a.vertices.size() && a.vertices[i] == b.vertices[j])
      fail("internal error: a vertex slides on two geometries");
    out.vertices.push_back(take_a ? a.vertices[i] : b.vertices[j]);
    from.push_back(take_a ? static_cast<PetscInt>(i++) : -1 - static_cast<PetscInt>(j++));
  }
  const std::size_t na = a.vertices.size(), nb = b.vertices.size();
  out.tangent_spaces = [a = a.tangent_spaces, b = b.tangent_spaces, from, na, nb](
                           std::span<const double> x, std::span<double> values) {
    const std::size_t size = values.size() / from.size();
    std::vector<double> va(na * size), vb(nb * size);
    a(x, va);
    b(x, vb);
    for (std::size_t k = 0; k < from.size(); ++k) {
      const double* source =
          from[k] >= 0 ? va.data() + from[k] * size : vb.data() + (-1 - from[k]) * size;
      std::copy_n(source, size, values.data() + k * size);
    }
  };
  out.project = [a = a.project, b = b.project](Vec x) {
    a(x);
    b(x);
  };
  return out;
}

}  // namespace neomesh
