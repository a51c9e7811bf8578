#include "geometry/node_mesh.hpp"

#include <algorithm>
#include <array>

#include "core/error.hpp"
#include "geometry/curved_cell.hpp"
#include "mesh/gather.hpp"
#include "mesh/nodes_by_corners.hpp"

namespace neomesh {

namespace {

// The corners (node numbers, sorted) of the smallest face of the reference cell that holds
// node i: an edge's two for a mid-edge node, a face's corners for a face node, all for the
// centre, the corner itself for a corner.
template <CurvedType Type>
std::vector<int> carrier(const Vector<CurvedTraits<Type>::dim>& p) {
  using Traits = CurvedTraits<Type>;
  std::vector<int> corners;
  for (int k = 0; k < Traits::corners; ++k) {
    const auto q = reference_node<Type>(k);
    bool in = true;
    if constexpr (Traits::simplex) {
      // Barycentric λ_k(p) > 0: corner 0 at the origin, corner k at e_k.
      const double lambda = k == 0 ? 1.0 - p.sum() : p[k - 1];
      in = lambda > 1e-12;
    } else if constexpr (Traits::wedge) {
      // The triangle's barycentric λ_{k mod 3}(p) > 0, and p at the corner's level or between.
      const double lambda = k % 3 == 0 ? 1.0 - p[0] - p[1] : p[k % 3 - 1];
      in = lambda > 1e-12 && (p[2] == 0.0 || p[2] == q[2]);
    } else {
      for (int j = 0; j < Traits::dim; ++j)
        if (p[j] != 0.0 && p[j] != q[j]) in = false;
    }
    if (in) corners.push_back(k);
  }
  return corners;
}

// The sub-cells of a simplex in node numbers (either orientation; fixed below); the triangle's
// are positively oriented (the wedge's sub-cells are built on them).
constexpr std::array<std::array<int, 3>, 4> kTriangleSubcells = {
    {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}}};
// Gmsh's edges 4:(0,1) 5:(1,2) 6:(2,0) 7:(3,0) 8:(3,2) 9:(3,1): the corners' tetrahedra, and the
// inner octahedron cut along its diagonal 6–9, the cycle 4 5 8 7 around it.
constexpr std::array<std::array<int, 4>, 8> kTetrahedronSubcells = {{{0, 4, 6, 7},
                                                                     {4, 1, 5, 9},
                                                                     {6, 5, 2, 8},
                                                                     {7, 9, 8, 3},
                                                                     {6, 9, 4, 5},
                                                                     {6, 9, 5, 8},
                                                                     {6, 9, 8, 7},
                                                                     {6, 9, 7, 4}}};

class Builder {
 public:
  explicit Builder(const InputMesh& curved)
      : curved_(curved), x_(curved_point_coordinates(curved)), d_(curved.coord_dim()) {
    out_.mesh.dim = curved.dim;
    out_.mesh.plane = curved.plane;
    out_.mesh.coords = x_;
    out_.points = curved.num_points();
  }

  NodeMesh build() {
    for (PetscInt c = 0; c < curved_.num_cells(); ++c) {
      visit_curved_type(curved_.high_order.types[c],
                        [&]<CurvedType Type>(CurvedTag<Type>) { add_cell<Type>(c); });
      out_.subcells.push_back(out_.mesh.num_cells());
    }
    subdivide_facets();
    out_.mesh.points = curved_.points;
    out_.mesh.groups = curved_.groups;
    return std::move(out_);
  }

 private:
  template <CurvedType Type>
  void add_cell(PetscInt c) {
    using Traits = CurvedTraits<Type>;
    constexpr int dim = Traits::dim;
    PetscInt points[kMaxCurvedNodes];
    curved_cell_points(curved_, c, points);
    typename Traits::Nodes nodes;
    for (int i = 0; i < Traits::nodes; ++i)
      for (int j = 0; j < dim; ++j) nodes(j, i) = x_[points[i] * d_ + j];
    // The nodes of its edges and faces, for the facets' subdivision.
    face_node_.add_cell(Type, points);
    const int tag = curved_.cell_tags[c];
    if constexpr (Traits::simplex) {
      const auto add = [&](const auto& sub) {
        std::array<PetscInt, dim + 1> v;
        Matrix<dim> edges;
        for (int i = 0; i <= dim; ++i) v[i] = points[sub[i]];
        for (int i = 1; i <= dim; ++i)
          edges.col(i - 1) = reference_node<Type>(sub[i]) - reference_node<Type>(sub[0]);
        if (edges.determinant() < 0.0) std::swap(v[0], v[1]);
        out_.mesh.add_cell(Traits::linear, v.data(), tag);
      };
      if constexpr (dim == 2)
        for (const auto& sub : kTriangleSubcells) add(sub);
      else
        for (const auto& sub : kTetrahedronSubcells) add(sub);
    } else if constexpr (Traits::wedge) {
      // The triangle6 lattice at ζ = −1, 0, 1 (the wedge15's face centres virtual): 8 wedges,
      // the triangle's 4 sub-triangles between two consecutive levels.
      std::array<std::array<PetscInt, 6>, 3> lattice;  // [level][triangle6 node]
      for (auto& level : lattice) level.fill(-1);
      const auto triangle_node = [](const Vector<3>& p) {
        const int a = static_cast<int>(std::lround(2.0 * p[0])),
                  b = static_cast<int>(std::lround(2.0 * p[1]));
        // Triangle6: corners (0,0) (2,0) (0,2), then mid-edges (1,0) (1,1) (0,1), in halves.
        constexpr int kNode[3][3] = {{0, 5, 2}, {3, 4, -1}, {1, -1, -1}};
        return kNode[a][b];
      };
      for (int i = 0; i < Traits::nodes; ++i) {
        const Vector<3> p = reference_node<Type>(i);
        lattice[std::lround(p[2]) + 1][triangle_node(p)] = points[i];
      }
      for (int level = 0; level < 3; ++level)
        for (int t = 0; t < 6; ++t) {
          if (lattice[level][t] >= 0) continue;
          const Vector<2> uv = reference_node<CurvedType::Triangle6>(t);
          lattice[level][t] =
              virtual_vertex<Type>(Vector<3>(uv[0], uv[1], level - 1.0), nodes, points);
        }
      for (int level = 0; level < 2; ++level)
        for (const auto& sub : kTriangleSubcells) {
          std::array<PetscInt, 6> v;
          for (int i = 0; i < 3; ++i) {
            v[i] = lattice[level][sub[i]];
            v[i + 3] = lattice[level + 1][sub[i]];
          }
          out_.mesh.add_cell(Traits::linear, v.data(), tag);
        }
    } else {
      // The lattice {−1, 0, 1}^d of the tensor cell, the serendipity cell's missing points
      // filled with virtual vertices.
      constexpr int size = dim == 2 ? 9 : 27;
      std::array<PetscInt, size> lattice;
      lattice.fill(-1);
      const auto index = [](const Vector<dim>& p) {
        int k = 0;
        for (int j = dim - 1; j >= 0; --j) k = 3 * k + static_cast<int>(std::lround(p[j])) + 1;
        return k;
      };
      for (int i = 0; i < Traits::nodes; ++i) lattice[index(reference_node<Type>(i))] = points[i];
      for (int k = 0; k < size; ++k) {
        if (lattice[k] >= 0) continue;
        Vector<dim> p;
        for (int j = 0, r = k; j < dim; ++j, r /= 3) p[j] = r % 3 - 1.0;
        lattice[k] = virtual_vertex<Type>(p, nodes, points);
      }
      for (int s = 0; s < (1 << dim); ++s) {
        std::array<PetscInt, 1 << dim> v;
        for (int i = 0; i < (1 << dim); ++i) {
          int k = 0;
          for (int j = dim - 1; j >= 0; --j) k = 3 * k + ((s >> j) & 1) + ((i >> j) & 1);
          v[i] = lattice[k];
        }
        out_.mesh.add_cell(Traits::linear, v.data(), tag);
      }
    }
  }

  // The vertex at reference point p of a serendipity cell: a face's centre is shared by the
  // cells on both sides; the cell's own centre is its alone.
  template <CurvedType Type>
  PetscInt virtual_vertex(const Vector<CurvedTraits<Type>::dim>& p,
                          const typename CurvedTraits<Type>::Nodes& nodes, const PetscInt* points) {
    std::vector<PetscInt> corners;
    for (int k : carrier<Type>(p)) corners.push_back(points[k]);
    const bool shared = static_cast<int>(corners.size()) < CurvedTraits<Type>::corners;
    if (shared)
      if (const PetscInt v = face_node_.find(corners); v >= 0) return v;
    const PetscInt v = out_.mesh.num_vertices();
    const auto at = curved_map<Type>(nodes, p);
    for (int j = 0; j < d_; ++j) out_.mesh.coords.push_back(at[j]);
    if (shared) face_node_.add(corners, v);
    return v;
  }

  PetscInt node_of(std::initializer_list<PetscInt> corners) const {
    const PetscInt node = face_node_.find({corners.begin(), corners.size()});
    if (node < 0) fail("internal error: a boundary facet of a curved mesh that no cell has");
    return node;
  }

  // Facets in physical groups: an edge into its two halves, a triangle into 4, a
  // quadrilateral into 4 around its centre.
  void subdivide_facets() {
    const TaggedEntities& in = curved_.facets;
    TaggedEntities& out = out_.mesh.facets;
    for (PetscInt f = 0; f < in.size(); ++f) {
      const PetscInt* v = in.vertices.data() + in.offsets[f];
      const PetscInt n = in.offsets[f + 1] - in.offsets[f];
      const int tag = in.tags[f];
      if (n == 2) {
        const PetscInt m = node_of({v[0], v[1]});
        const PetscInt a[2] = {v[0], m}, b[2] = {m, v[1]};
        out.add(a, 2, tag);
        out.add(b, 2, tag);
      } else if (n == 3) {
        const PetscInt m01 = node_of({v[0], v[1]}), m12 = node_of({v[1], v[2]}),
                       m20 = node_of({v[2], v[0]});
        const PetscInt subs[4][3] = {
            {v[0], m01, m20}, {m01, v[1], m12}, {m20, m12, v[2]}, {m01, m12, m20}};
        for (const auto& s : subs) out.add(s, 3, tag);
      } else {
        // As a cycle: in the order given if its sides are edges, else in tensor order.
        const bool cycle = face_node_.find(std::array{v[1], v[2]}) >= 0;
        const std::array<PetscInt, 4> q =
            cycle ? std::array{v[0], v[1], v[2], v[3]} : std::array{v[0], v[1], v[3], v[2]};
        const PetscInt centre = node_of({q[0], q[1], q[2], q[3]});
        for (int k = 0; k < 4; ++k) {
          const PetscInt next = node_of({q[k], q[(k + 1) % 4]});
          const PetscInt previous = node_of({q[k], q[(k + 3) % 4]});
          const std::array<PetscInt, 4> s = cycle ? std::array{q[k], next, centre, previous}
                                                  : std::array{q[k], next, previous, centre};
          out.add(s.data(), 4, tag);
        }
      }
    }
  }

  const InputMesh& curved_;
  const std::vector<double> x_;
  const int d_;
  NodeMesh out_;
  NodesByCorners face_node_;  // the cells' edge and face nodes, and the virtual face centres
};

// A process' curved cells: those whose sub-cells its part of the node mesh has, in increasing
// number, each with its points (input numbers, as curved_cell_points gives them).
struct CurvedCells {
  std::vector<PetscInt> number;  // in the curved mesh
  std::vector<CurvedType> types;
  std::vector<PetscInt> offsets = {0};  // into `points`
  std::vector<PetscInt> points;
};

// `nodes`' local vertices by their input numbers.
class LocalVertices {
 public:
  explicit LocalVertices(const MeshView& nodes) {
    by_input_.reserve(nodes.num_vertices);
    for (PetscInt v = 0; v < nodes.num_vertices; ++v)
      by_input_.emplace_back(nodes.input_vertex[v], v);
    std::sort(by_input_.begin(), by_input_.end());
  }
  PetscInt operator()(PetscInt input) const {
    const auto it =
        std::lower_bound(by_input_.begin(), by_input_.end(), std::pair(input, PetscInt{0}));
    if (it == by_input_.end() || it->first != input)
      fail("internal error: node {} of a local curved cell is not a local vertex", input);
    return it->second;
  }

 private:
  std::vector<std::pair<PetscInt, PetscInt>> by_input_;
};

// The view of `nodes` with blocks of the curved cells `cells`, per type: every node
// (`corners_only` false) or the corners in canonical order.
MeshView view_of_cells(const MeshView& nodes, const CurvedCells& cells, bool corners_only) {
  MeshView view = nodes;
  view.blocks.clear();
  view.global_cell.clear();
  view.num_cells = 0;
  const LocalVertices local(nodes);
  for (CurvedType type : kCurvedTypes) {
    CellBlock block{
        facts(type).linear, view.num_cells, {}, corners_only ? std::nullopt : std::optional(type)};
    visit_curved_type(type, [&]<CurvedType Type>(CurvedTag<Type>) {
      for (std::size_t k = 0; k < cells.types.size(); ++k) {
        if (cells.types[k] != type) continue;
        const PetscInt* points = cells.points.data() + cells.offsets[k];
        if (corners_only)
          for (int i : linear_corners<Type>()) block.vertices.push_back(local(points[i]));
        else
          for (int i = 0; i < CurvedTraits<Type>::nodes; ++i)
            block.vertices.push_back(local(points[i]));
        view.global_cell.push_back(cells.number[k]);
      }
    });
    if (block.vertices.empty()) continue;
    view.num_cells += block.size();
    view.blocks.push_back(std::move(block));
  }
  return view;
}

// Rank 0's answer to process r's sub-cells `subcells` (node mesh cell numbers): their curved
// cells, as a count, then per cell its number, type, and points.
void pack_curved_cells(std::span<const PetscInt> subcells, const NodeMesh& node_mesh,
                       const InputMesh& curved, std::vector<PetscInt>& out) {
  std::vector<PetscInt> cells;
  for (PetscInt s : subcells) {
    const auto& first = node_mesh.subcells;
    cells.push_back(std::upper_bound(first.begin(), first.end(), s) - first.begin() - 1);
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  out.push_back(static_cast<PetscInt>(cells.size()));
  PetscInt points[kMaxCurvedNodes];
  for (PetscInt c : cells) {
    const int n = curved_cell_points(curved, c, points);
    out.insert(out.end(), {c, static_cast<PetscInt>(curved.high_order.types[c]), n});
    out.insert(out.end(), points, points + n);
  }
}

// Collective: the curved cells of this process' part `nodes` of the node mesh (distributed with
// NodeMesh::subcells kept together); `node_mesh` and the curved mesh `curved` are read on rank 0
// (empty elsewhere), which sends each process its cells.
CurvedCells local_curved_cells(const MeshView& nodes, const NodeMesh& node_mesh,
                               const InputMesh& curved, MPI_Comm comm) {
  const int size = mpi_size(comm);
  // Every process' sub-cells on rank 0, each list after its length.
  std::vector<PetscInt> mine = {nodes.num_cells};
  mine.insert(mine.end(), nodes.global_cell.begin(), nodes.global_cell.end());
  const std::vector<PetscInt> all = gatherv(comm, mine, MPIU_INT);
  std::vector<PetscInt> send;
  std::vector<int> counts(size, 0), offsets(size, 0);
  if (mpi_rank(comm) == 0) {
    for (std::size_t at = 0, r = 0; r < static_cast<std::size_t>(size); ++r) {
      const PetscInt n = all[at];
      offsets[r] = static_cast<int>(send.size());
      pack_curved_cells(std::span(all).subspan(at + 1, n), node_mesh, curved, send);
      counts[r] = static_cast<int>(send.size()) - offsets[r];
      at += 1 + n;
    }
  }
  int count = 0;
  MPI_Scatter(counts.data(), 1, MPI_INT, &count, 1, MPI_INT, 0, comm);
  std::vector<PetscInt> received(count);
  MPI_Scatterv(send.data(), counts.data(), offsets.data(), MPIU_INT, received.data(), count,
               MPIU_INT, 0, comm);
  CurvedCells cells;
  for (PetscInt k = 0, at = 1; k < received[0]; ++k) {
    const PetscInt n = received[at + 2];
    cells.number.push_back(received[at]);
    cells.types.push_back(static_cast<CurvedType>(received[at + 1]));
    cells.points.insert(cells.points.end(), received.begin() + at + 3,
                        received.begin() + at + 3 + n);
    cells.offsets.push_back(static_cast<PetscInt>(cells.points.size()));
    at += 3 + n;
  }
  return cells;
}

}  // namespace

NodeMesh node_mesh(const InputMesh& curved) {
  if (!curved.curved()) fail("internal error: the node mesh of a straight mesh");
  return Builder(curved).build();
}

std::vector<double> gather_points(const MeshView& nodes, std::span<const double> coords,
                                  PetscInt points, MPI_Comm comm) {
  const int d = nodes.dim;
  std::vector<PetscInt> numbers;
  std::vector<double> values;
  for (PetscInt v = 0; v < nodes.num_vertices; ++v)
    if (nodes.owned[v] && nodes.input_vertex[v] < points) {
      numbers.push_back(nodes.input_vertex[v]);
      values.insert(values.end(), coords.begin() + d * v, coords.begin() + d * (v + 1));
    }
  const std::vector<PetscInt> all_numbers = gatherv(comm, std::move(numbers), MPIU_INT);
  const std::vector<double> all_values = gatherv(comm, std::move(values), MPI_DOUBLE);
  if (mpi_rank(comm) != 0) return {};
  std::vector<double> out(static_cast<std::size_t>(d * points));
  for (std::size_t k = 0; k < all_numbers.size(); ++k)
    std::copy_n(all_values.begin() + d * k, d, out.begin() + d * all_numbers[k]);
  return out;
}

std::vector<double> curved_cell_volumes(const MeshView& cells, std::span<const double> coords) {
  std::vector<double> volumes(cells.num_cells);
  const int d = cells.dim;
  for (const CellBlock& block : cells.blocks) {
    if (!block.curved) fail("internal error: the curved volume of a straight cell");
    visit_curved_type(*block.curved, [&]<CurvedType Type>(CurvedTag<Type>) {
      typename CurvedTraits<Type>::Nodes x;
      for (PetscInt c = 0; c < block.size(); ++c) {
        for (int i = 0; i < CurvedTraits<Type>::nodes; ++i)
          for (int j = 0; j < d; ++j) x(j, i) = coords[d * block.cell(c)[i] + j];
        volumes[block.first_cell + c] = curved_volume<Type>(x);
      }
    });
  }
  return volumes;
}

DistributedNodeMesh distribute_node_mesh(const InputMesh& curved, const std::string& name,
                                         MPI_Comm comm) {
  NodeMesh nodes = mpi_rank(comm) == 0 ? node_mesh(curved) : NodeMesh{};
  PlexMesh plex = PlexMesh::from_input(nodes.mesh, name, comm, true, nodes.subcells);
  const CurvedCells cells = local_curved_cells(plex.view(), nodes, curved, comm);
  MeshView curved_view = view_of_cells(plex.view(), cells, false);
  MeshView corners = view_of_cells(plex.view(), cells, true);
  MPI_Bcast(&nodes.points, 1, MPIU_INT, 0, comm);
  return {std::move(plex), std::move(curved_view), std::move(corners), nodes.points};
}

}  // namespace neomesh
