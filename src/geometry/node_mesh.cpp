#include "geometry/node_mesh.hpp"

#include <algorithm>
#include <array>
#include <map>

#include "core/error.hpp"
#include "geometry/curved_cell.hpp"

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

// A face of the mesh by its corner points, as every cell holding it names it.
using FaceKey = std::array<PetscInt, 8>;
template <typename Corners>
FaceKey face_key(const Corners& corners) {
  FaceKey key;
  key.fill(-1);
  const int size = static_cast<int>(corners.size());
  std::copy(corners.begin(), corners.end(), key.begin());
  // By insertion, as sort_facet_key (cell_type.hpp): GCC 12 warns wrongly about std::sort on
  // part of an array.
  for (int k = 1; k < size; ++k)
    for (int i = k; i > 0 && key[i - 1] > key[i]; --i) std::swap(key[i - 1], key[i]);
  return key;
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
    for (PetscInt c = 0; c < curved_.num_cells(); ++c)
      visit_curved_type(curved_.high_order.types[c],
                        [&]<CurvedType Type>(CurvedTag<Type>) { add_cell<Type>(c); });
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
    // Every node's face, for the facets' subdivision.
    for (int i = Traits::corners; i < Traits::nodes; ++i) {
      std::vector<PetscInt> corners;
      for (int k : carrier<Type>(reference_node<Type>(i))) corners.push_back(points[k]);
      face_node_.emplace(face_key(corners), points[i]);
    }
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
    const FaceKey key = face_key(corners);
    if (shared)
      if (const auto it = face_node_.find(key); it != face_node_.end()) return it->second;
    const PetscInt v = out_.mesh.num_vertices();
    const auto at = curved_map<Type>(nodes, p);
    for (int j = 0; j < d_; ++j) out_.mesh.coords.push_back(at[j]);
    if (shared) face_node_.emplace(key, v);
    return v;
  }

  PetscInt node_of(std::initializer_list<PetscInt> corners) const {
    const auto it = face_node_.find(face_key(std::vector<PetscInt>(corners)));
    if (it == face_node_.end())
      fail("internal error: a boundary facet of a curved mesh that no cell has");
    return it->second;
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
        const bool cycle = face_node_.contains(face_key(std::array{v[1], v[2]}));
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
  std::map<FaceKey, PetscInt> face_node_;  // by its face's corner points
};

// `nodes`' local vertex of each vertex of the node mesh.
std::vector<PetscInt> local_of_input(const MeshView& nodes) {
  std::vector<PetscInt> local(nodes.input_vertex.size(), -1);
  for (PetscInt v = 0; v < nodes.num_vertices; ++v) local[nodes.input_vertex[v]] = v;
  return local;
}

// The view of `nodes` with blocks of the curved cells of `curved`, per type: every node
// (`corners_only` false) or the corners in canonical order.
MeshView view_of_cells(const MeshView& nodes, const InputMesh& curved, bool corners_only) {
  if (!curved.curved()) fail("internal error: the curved cells of a straight mesh");
  MeshView view = nodes;
  view.blocks.clear();
  view.global_cell.clear();
  view.num_cells = 0;
  const std::vector<PetscInt> local = local_of_input(nodes);
  for (CurvedType type : kCurvedTypes) {
    CellBlock block{
        facts(type).linear, view.num_cells, {}, corners_only ? std::nullopt : std::optional(type)};
    visit_curved_type(type, [&]<CurvedType Type>(CurvedTag<Type>) {
      PetscInt points[kMaxCurvedNodes];
      for (PetscInt c = 0; c < curved.num_cells(); ++c) {
        if (curved.high_order.types[c] != type) continue;
        curved_cell_points(curved, c, points);
        if (corners_only)
          for (int k : linear_corners<Type>()) block.vertices.push_back(local[points[k]]);
        else
          for (int i = 0; i < CurvedTraits<Type>::nodes; ++i)
            block.vertices.push_back(local[points[i]]);
        view.global_cell.push_back(c);
      }
    });
    if (block.vertices.empty()) continue;
    view.num_cells += block.size();
    view.blocks.push_back(std::move(block));
  }
  return view;
}

}  // namespace

NodeMesh node_mesh(const InputMesh& curved) {
  if (!curved.curved()) fail("internal error: the node mesh of a straight mesh");
  return Builder(curved).build();
}

MeshView curved_cells_view(const MeshView& nodes, const InputMesh& curved) {
  return view_of_cells(nodes, curved, false);
}

MeshView corner_cells_view(const MeshView& nodes, const InputMesh& curved) {
  return view_of_cells(nodes, curved, true);
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

}  // namespace neomesh
