#include "solver/curved_repair.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <vector>

#include "geometry/curved_cell.hpp"
#include "geometry/quality.hpp"
#include "solver/repair_search.hpp"

namespace neomesh {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// How far below every valid cell measure() puts a cell not certified valid (q ≥ −2 for all).
constexpr double kNotValid = 3.0;

// The search on rank 0, over the nodes of the whole mesh.
class CurvedRepair {
 public:
  CurvedRepair(WholeMesh& m, const RepairFreedom& freedom)
      : m_(m),
        project_(freedom.project),
        star_first_(m.vertex_id.size() + 1, 0),
        star_(m.vertices.size()),
        q_(m.types.size()),
        start_(m.coords) {
    for (std::int64_t v : m.vertices) ++star_first_[v + 1];
    std::partial_sum(star_first_.begin(), star_first_.end(), star_first_.begin());
    std::vector<std::int64_t> next(star_first_.begin(), star_first_.end() - 1);
    for (std::size_t c = 0; c < m.types.size(); ++c) {
      for (std::int64_t k = m.offsets[c]; k < m.offsets[c + 1]; ++k)
        star_[next[m.vertices[k]]++] = static_cast<std::int64_t>(c);
      q_[c] = measure(static_cast<std::int64_t>(c));
      budget_ += kCurvedRepairPerCell * jacobian_bezier_size(type(c));
    }
    rank();
  }

  double min_quality() const { return worst_.empty() ? kInfinity : q_[worst_[0]]; }
  bool spent() const { return spent_ >= budget_; }
  // No sweep after the coefficients allowed are spent, nor on an optimal worst cell (the curved
  // scaled Jacobian is at most 1).
  bool done() const { return spent() || !(min_quality() < 1.0 - kRepairGain); }

  void begin_sweep() { undo_.clear(); }
  void undo_sweep() {
    const int d = m_.dim;
    for (std::size_t k = undo_.size(); k-- > 0;) {
      std::copy_n(undo_[k].x.begin(), d, m_.coords.begin() + d * undo_[k].vertex);
      for (std::int64_t c : star(undo_[k].vertex)) q_[c] = measure(c);
    }
    undo_.clear();
    rank();
  }

  // One sweep over the worst cells' nodes and the nodes of the cells around those, ascending;
  // appends the nodes it moves to `moved`.
  void sweep(std::span<const double> steps, std::vector<std::int64_t>& moved) {
    std::vector<std::int64_t> candidates;
    for (std::int64_t w : worst_)
      for (std::int64_t v : cell_nodes(w))
        for (std::int64_t c : star(v))
          for (std::int64_t u : cell_nodes(c))
            if (movable(u)) candidates.push_back(u);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (std::int64_t v : candidates) {
      if (spent()) break;
      if (improve(v, steps)) moved.push_back(v);
    }
    rank();
  }

 private:
  CurvedType type(std::int64_t c) const { return static_cast<CurvedType>(m_.curved[c]); }

  std::span<const std::int64_t> cell_nodes(std::int64_t c) const {
    return {m_.vertices.data() + m_.offsets[c],
            static_cast<std::size_t>(m_.offsets[c + 1] - m_.offsets[c])};
  }
  std::span<const std::int64_t> star(std::int64_t v) const {
    return {star_.data() + star_first_[v],
            static_cast<std::size_t>(star_first_[v + 1] - star_first_[v])};
  }
  bool movable(std::int64_t v) const {
    const auto f = m_.fixed.begin() + m_.dim * v;
    return std::find(f, f + m_.dim, 0) != f + m_.dim;
  }

  // Cell c's least curved scaled Jacobian (its sampled bound, as the quality tables give it); a
  // cell the certificate does not find Valid ranks below all that it does, by how far its
  // sampled value is below 0; the coefficients computed are spent.
  double measure(std::int64_t c) {
    return visit_curved_type(type(c), [&]<CurvedType Type>(CurvedTag<Type>) {
      typename CurvedTraits<Type>::Nodes x;
      int i = 0;
      for (std::int64_t v : cell_nodes(c)) {
        for (int a = 0; a < CurvedTraits<Type>::dim; ++a) x(a, i) = m_.coords[m_.dim * v + a];
        ++i;
      }
      const CurvedScaledJacobian q = curved_scaled_jacobian<Type>(x);
      spent_ += static_cast<std::int64_t>(q.certificate.subcells) * jacobian_bezier_size(Type);
      return q.certificate.validity == Validity::Valid ? q.upper : q.scaled_jacobian - kNotValid;
    });
  }

  // The worst cells, by (quality, number) ascending.
  void rank() {
    std::vector<std::int64_t> cells(q_.size());
    std::iota(cells.begin(), cells.end(), 0);
    const std::size_t n = std::min<std::size_t>(kRepairWorstCells, cells.size());
    std::partial_sort(cells.begin(), cells.begin() + n, cells.end(), [this](auto a, auto b) {
      return q_[a] < q_[b] || (q_[a] == q_[b] && a < b);
    });
    worst_.assign(cells.begin(), cells.begin() + n);
  }

  // Whether v, where it is now, keeps kRepairMinDistanceFraction of its start distance from every
  // node of its cells.
  bool admissible(std::int64_t v) const {
    const int d = m_.dim;
    for (std::int64_t c : star(v))
      for (std::int64_t u : cell_nodes(c)) {
        if (u == v) continue;
        const double now = edge_length(m_.coords.data() + d * u, m_.coords.data() + d * v, d);
        const double then = edge_length(start_.data() + d * u, start_.data() + d * v, d);
        if (!(now >= kRepairMinDistanceFraction * then)) return false;
      }
    return true;
  }

  // The worst quality of v's cells where v is now, or nothing once one is at most `beat`; the
  // cells' values into star_q_.
  std::optional<double> around(std::int64_t v, double beat) {
    const std::span<const std::int64_t> cells = star(v);
    star_q_.resize(cells.size());
    double worst = kInfinity;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      star_q_[i] = measure(cells[i]);
      if (!(star_q_[i] > beat)) return std::nullopt;
      worst = std::min(worst, star_q_[i]);
    }
    return worst;
  }

  // Moves v to the best trial point if that raises the worst cell around it.
  bool improve(std::int64_t v, std::span<const double> steps) {
    const int d = m_.dim;
    const std::span<const std::int64_t> cells = star(v);
    double best = kInfinity;
    for (std::int64_t c : cells) best = std::min(best, q_[c]);
    const double base = best;
    std::array<double, 3> from{}, best_x{};
    std::copy_n(m_.coords.begin() + d * v, d, from.begin());
    double h = kInfinity;  // the shortest distance from v to another node of its cells
    for (std::int64_t c : cells)
      for (std::int64_t u : cell_nodes(c))
        if (u != v) h = std::min(h, edge_length(m_.coords.data() + d * u, from.data(), d));
    if (!(h > 0.0) || !std::isfinite(h)) return false;
    std::span<double> p(m_.coords.data() + d * v, d);
    bool found = false;
    for (double step : steps) {
      for (const std::array<double, 3>& dir : dirs_) {
        if (spent()) break;
        for (int a = 0; a < d; ++a)
          p[a] = from[a] + (m_.fixed[d * v + a] ? 0.0 : step * h * dir[a]);
        if (m_.geometry[v] >= 0) project_(m_.geometry[v], p);
        if (!admissible(v)) continue;
        const std::optional<double> q = around(v, best + kRepairGain);
        if (!q) continue;
        best = *q;
        std::copy_n(p.begin(), d, best_x.begin());
        found = true;
      }
      if (found) break;
    }
    if (!found || !(best > base + kRepairGain)) {
      std::copy_n(from.begin(), d, p.begin());
      return false;
    }
    undo_.push_back({v, from});
    std::copy_n(best_x.begin(), d, p.begin());
    for (std::int64_t c : cells) q_[c] = measure(c);
    return true;
  }

  WholeMesh& m_;
  const std::function<void(int, std::span<double>)>& project_;
  std::vector<std::int64_t> star_first_, star_;  // the cells of node v: star_[first[v], [v+1])
  std::vector<double> q_;                        // per cell: measure()
  std::vector<double> star_q_;                   // around()'s scratch
  std::vector<std::int64_t> worst_;              // rank()'s
  const std::vector<double> start_;              // the coordinates at the repair's start
  struct Undo {
    std::int64_t vertex;
    std::array<double, 3> x;
  };
  std::vector<Undo> undo_;  // the sweep's moves, in order
  std::int64_t budget_ = kCurvedRepairAllowance, spent_ = 0;
  std::vector<std::array<double, 3>> dirs_ = repair_directions(m_.dim);
};

}  // namespace

int jacobian_bezier_size(CurvedType type) {
  return visit_curved_type(type, []<CurvedType Type>(CurvedTag<Type>) {
    using T = CurvedTraits<Type>;
    const int n = T::det_degree;
    if constexpr (T::wedge) return (n + 1) * (n + 2) / 2 * (T::det_axis_degree + 1);
    if constexpr (T::simplex)
      return T::dim == 2 ? (n + 1) * (n + 2) / 2 : (n + 1) * (n + 2) * (n + 3) / 6;
    return T::dim == 2 ? (n + 1) * (n + 1) : (n + 1) * (n + 1) * (n + 1);
  });
}

WorstCellRepair repair_worst_curved_cells(const MeshView& view, const DofMap& dofs,
                                          const RepairFreedom& freedom, Vec x) {
  return repair_in_sweeps(view, dofs, freedom, x,
                          [&](WholeMesh& mesh) { return CurvedRepair(mesh, freedom); });
}

}  // namespace neomesh
