#include "solver/worst_cell_repair.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <vector>

#include "geometry/quality.hpp"
#include "geometry/surface_frame.hpp"
#include "mesh/cell_type.hpp"
#include "mesh/gather.hpp"
#include "solver/repair_search.hpp"

namespace neomesh {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The search on rank 0. Returns the indices of the moved vertices.
class Repair {
 public:
  Repair(WholeMesh& m, const RepairFreedom& freedom, double min_mean, double max_mean_imr)
      : m_(m),
        project_(freedom.project),
        star_first_(m.vertex_id.size() + 1, 0),
        star_(m.vertices.size()),
        sj_(m.types.size()),
        corner_(m.types.size()),
        start_(m.coords) {
    min_sum_ = min_mean * static_cast<double>(m.types.size());
    max_imr_sum_ = max_mean_imr * static_cast<double>(m.types.size());
    for (CellType type : kAllCellTypes) {
      for (int k = 0; k < facts(type).vertices; ++k)
        corners_at_[static_cast<int>(type)][k] = scaled_jacobian_corners_at(type, k);
      // Every edge lies on a facet, so the facets' cycles visit them all (as the edge ratio).
      for (int f = 0; f < facts(type).num_facets; ++f) {
        const FacetVertices& facet = facts(type).facets[f];
        for (int i = 0; i < facet.size; ++i)
          edges_[static_cast<int>(type)].push_back(
              {facet.vertices[i], facet.vertices[(i + 1) % facet.size]});
      }
    }
    for (std::int64_t v : m.vertices) ++star_first_[v + 1];
    std::partial_sum(star_first_.begin(), star_first_.end(), star_first_.begin());
    std::vector<std::int64_t> next(star_first_.begin(), star_first_.end() - 1);
    for (std::size_t c = 0; c < m.types.size(); ++c) {
      for (std::int64_t k = m.offsets[c]; k < m.offsets[c + 1]; ++k)
        star_[next[m.vertices[k]]++] = static_cast<std::int64_t>(c);
      const std::array<double, 3 * 8> x = cell_coords(c);
      if (m.surface) normals_.push_back(start_normal(m.types[c], x.data()));
      sj_[c] = evaluate(c, x.data());
      sum_ += sj_[c];
      if (imr_ceiling()) {
        imr_.push_back(inverse_mean_ratio(c, x.data()));
        imr_sum_ += imr_.back();
      }
      max_edge_ratio_ = std::max(max_edge_ratio_, edge_ratio(c, x.data()));
    }
    rank();
  }

  double min_quality() const { return worst_count_ == 0 ? kInfinity : sj_[worst_[0]]; }
  bool done() const { return false; }  // until the sweeps stall

  // What a sweep changes, to undo it: each move's vertex and its cells' values before it, in
  // order, and the sums at the sweep's start (the same bits as a copy of the whole mesh's).
  void begin_sweep() {
    undo_coords_.clear();
    undo_cells_.clear();
    undo_sum_ = sum_;
    undo_imr_sum_ = imr_sum_;
  }
  void undo_sweep() {
    const int d = m_.dim;
    for (std::size_t k = undo_cells_.size(); k-- > 0;) {
      const UndoCell& u = undo_cells_[k];
      sj_[u.cell] = u.sj;
      corner_[u.cell] = u.corners;
      if (imr_ceiling()) imr_[u.cell] = u.imr;
    }
    for (std::size_t k = undo_coords_.size(); k-- > 0;)
      std::copy_n(undo_coords_[k].x.begin(), d, m_.coords.begin() + d * undo_coords_[k].vertex);
    sum_ = undo_sum_;
    imr_sum_ = undo_imr_sum_;
    undo_coords_.clear();
    undo_cells_.clear();
    failed_at_.assign(failed_at_.size(), 0);  // judged against positions undone
    rank();
  }

  // One sweep over the worst cells' neighbourhood with these step lengths; appends the vertices
  // it moves to `moved` (ascending).
  void sweep(std::span<const double> steps, std::vector<std::int64_t>& moved) {
    if (steps.data() != failed_steps_) {  // a failure with other steps tells nothing
      failed_at_.assign(failed_at_.size(), 0);
      failed_steps_ = steps.data();
    }
    // The worst cells' vertices and the vertices of the cells around those, ascending.
    candidates_.clear();
    for (std::size_t w = 0; w < worst_count_; ++w)
      for (std::int64_t v : cell_vertices(worst_[w]))
        for (std::int64_t c : star(v))
          for (std::int64_t u : cell_vertices(c))
            if (!candidate_[u] && movable(u)) {
              candidate_[u] = 1;
              candidates_.push_back(u);
            }
    std::sort(candidates_.begin(), candidates_.end());
    for (std::int64_t v : candidates_) {
      candidate_[v] = 0;
      if (improve(v, steps)) moved.push_back(v);
    }
    rank();
  }

 private:
  // Finds the worst cells, by (scaled Jacobian, number) ascending, in one pass, the few kept
  // sorted: for min_quality() and the next sweep.
  void rank() {
    const std::size_t worst = std::min<std::size_t>(kRepairWorstCells, sj_.size());
    const auto before = [this](std::int64_t a, std::int64_t b) {
      return sj_[a] < sj_[b] || (sj_[a] == sj_[b] && a < b);
    };
    std::size_t kept = 0;
    double bar = kInfinity;  // once `worst` are kept, a later cell must be below the last
    for (std::int64_t c = 0; c < static_cast<std::int64_t>(sj_.size()); ++c) {
      if (kept == worst && !(sj_[c] < bar)) continue;
      std::size_t at = kept < worst ? kept++ : kept - 1;
      for (; at > 0 && before(c, worst_[at - 1]); --at) worst_[at] = worst_[at - 1];
      worst_[at] = c;
      if (kept == worst) bar = sj_[worst_[kept - 1]];
    }
    worst_count_ = worst;
  }

  std::span<const std::int64_t> cell_vertices(std::int64_t c) const {
    return {m_.vertices.data() + m_.offsets[c],
            static_cast<std::size_t>(m_.offsets[c + 1] - m_.offsets[c])};
  }

  // The cells of vertex v.
  std::span<const std::int64_t> star(std::int64_t v) const {
    return {star_.data() + star_first_[v],
            static_cast<std::size_t>(star_first_[v + 1] - star_first_[v])};
  }

  bool movable(std::int64_t v) const {
    const auto f = m_.fixed.begin() + m_.dim * v;
    return std::find(f, f + m_.dim, 0) != f + m_.dim;
  }

  // Where v lands for the move `by`: its fixed coordinates stay, then onto its geometry.
  void move(std::int64_t v, std::span<const double> from, std::span<const double> by) {
    const int d = m_.dim;
    std::span<double> p(m_.coords.data() + d * v, d);
    for (int a = 0; a < d; ++a) p[a] = from[a] + (m_.fixed[d * v + a] ? 0.0 : by[a]);
    if (m_.geometry[v] >= 0) project_(m_.geometry[v], p);
  }

  // The coordinates of cell c's vertices, dim per vertex.
  std::array<double, 3 * 8> cell_coords(std::int64_t c) const {
    const int d = m_.dim;
    std::array<double, 3 * 8> x{};
    int i = 0;
    for (std::int64_t v : cell_vertices(c)) {
      for (int a = 0; a < d; ++a) x[d * i + a] = m_.coords[d * v + a];
      ++i;
    }
    return x;
  }
  // A surface cell is judged along its normal at the repair's start, so that a move that
  // folds it (turns it against that normal) makes it inverted, not as good as it was; where
  // it tilts, the measure is below the one along its own normal that the quality tables take.
  // Cell c's scaled Jacobian at coordinates x (dim per vertex, in its vertex order: cell_coords or
  // the star's gathered ones), over `corners`, if above `bar` (cell_scaled_jacobian_above).
  double scaled_jacobian(std::int64_t c, const double* x, double bar = -kInfinity,
                         std::uint32_t corners = kAllCorners) const {
    return m_.surface ? surface_cell_scaled_jacobian_above(m_.types[c], x, normals_[c].data(), bar,
                                                           corners)
                      : cell_scaled_jacobian_above(m_.types[c], x, bar, corners);
  }
  // Cell c's scaled Jacobian, its corners' values kept in corner_[c].
  double evaluate(std::int64_t c, const double* x) {
    const CellType type = m_.types[c];
    double* corners = corner_[c].data();
    const int n = m_.surface
                      ? surface_cell_scaled_jacobian_corners(type, x, normals_[c].data(), corners)
                      : cell_scaled_jacobian_corners(type, x, corners);
    corner_count_[static_cast<int>(type)] = n;
    return *std::min_element(corners, corners + n);
  }
  double edge_ratio(std::int64_t c, const double* x) const {
    return m_.surface ? surface_cell_edge_ratio(m_.types[c], x) : cell_edge_ratio(m_.types[c], x);
  }
  double inverse_mean_ratio(std::int64_t c, const double* x) const {
    return m_.surface ? surface_cell_inverse_mean_ratio(m_.types[c], x, normals_[c].data())
                      : cell_inverse_mean_ratio(m_.types[c], x);
  }
  bool imr_ceiling() const { return max_imr_sum_ < kInfinity; }
  // The inverse mean ratios of v's cells summed, v placed in each (after around()).
  double star_imr(std::int64_t v) const {
    double sum = 0.0;
    const std::span<const std::int64_t> cells = star(v);
    for (std::size_t i = 0; i < cells.size(); ++i)
      sum += inverse_mean_ratio(cells[i], cache_.coords[i].data());
    return sum;
  }
  // The unit normal of a surface cell from its vertex coordinates (surface_frame.hpp); zero for
  // one without area, which then measures as flat.
  static std::array<double, 3> start_normal(CellType type, const double* coords) {
    return visit_cell_type(type, [&]<CellType Type>(CellTag<Type>) {
      std::array<double, 3> n{};
      if constexpr (Type == CellType::Triangle || Type == CellType::Quadrilateral) {
        const Eigen::Map<const Eigen::Matrix<double, 3, CellTraits<Type>::vertices>> x(coords);
        if (const std::optional<Vector<3>> normal = surface_cell_normal<Type>(x))
          n = {(*normal)[0], (*normal)[1], (*normal)[2]};
      }
      return n;
    });
  }
  double distance(std::span<const double> x, std::int64_t u, std::int64_t v) const {
    return edge_length(x.data() + m_.dim * u, x.data() + m_.dim * v, m_.dim);
  }

  // What improve(v) keeps of v's cells (per position in star(v)) while v alone moves: their
  // vertices' coordinates, gathered once rather than per trial point, with v's own written in by
  // place() when the cell is judged; the positions of v in each; the corners of its scaled
  // Jacobian that v moves, and the value over the others, which it does not; the longest and
  // shortest of its edges that v does not move, and its edges at v by their other end (a cell's
  // edge ratio from these is the same bits as from all its edges: edge_length); and the other
  // vertices of v's cells, each once, with the shortest distance from v each allows.
  struct StarCache {
    std::vector<std::array<double, 3 * 8>> coords;
    std::vector<std::array<std::int8_t, 8>> v_at;  // v's positions in the cell, then -1
    std::vector<std::uint32_t> corners;            // scaled_jacobian_corners_at v
    std::vector<double> others;                    // the scaled Jacobian over the other corners
    std::vector<double> longest, shortest;         // of the cell's edges not at v
    std::vector<std::int32_t> edges_first, edges;  // cell i's edges at v: their other ends in
                                                   // `neighbours`, edges[edges_first[i], [i+1])
    std::vector<std::int64_t> neighbours;          // the other vertices of v's cells
    std::vector<double> min_distance;              // kRepairMinDistanceFraction × at the start
    std::vector<double> distance;                  // admissible()'s: from v, per neighbour
    std::int64_t admissible_for = -1;              // the vertex gather_edges() gathered for
  };
  // The positions of v in its cells, the corners it moves and the value over the others (from
  // the cells' corners kept); returns the least of those values.
  double gather_corners(std::int64_t v) {
    const std::span<const std::int64_t> cells = star(v);
    cache_.v_at.resize(cells.size());
    cache_.corners.assign(cells.size(), 0);
    cache_.others.resize(cells.size());
    double least = kInfinity;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const int type = static_cast<int>(m_.types[cells[i]]);
      cache_.v_at[i].fill(-1);
      int n = 0;
      int k = 0;
      for (std::int64_t u : cell_vertices(cells[i])) {
        if (u == v) {
          cache_.v_at[i][n++] = static_cast<std::int8_t>(k);
          cache_.corners[i] |= corners_at_[type][k];
        }
        ++k;
      }
      cache_.others[i] = kInfinity;
      for (int j = 0; j < corner_count_[type]; ++j)
        if (!((cache_.corners[i] >> j) & 1))
          cache_.others[i] = std::min(cache_.others[i], corner_[cells[i]][j]);
      least = std::min(least, cache_.others[i]);
    }
    return least;
  }
  void gather_star(std::int64_t v) {
    const std::span<const std::int64_t> cells = star(v);
    cache_.coords.resize(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) cache_.coords[i] = cell_coords(cells[i]);
    cache_.admissible_for = -1;
  }
  // The rest of the cache, for admissible(v): gathered on its first call for v, as most
  // vertices find no trial point that lifts their worst cell.
  void gather_edges(std::int64_t v) {
    const int d = m_.dim;
    const std::span<const std::int64_t> cells = star(v);
    cache_.longest.assign(cells.size(), 0.0);
    cache_.shortest.assign(cells.size(), kInfinity);
    cache_.edges_first.assign(1, 0);
    cache_.edges.clear();
    cache_.neighbours.clear();
    cache_.min_distance.clear();
    const auto neighbour = [&](std::int64_t u) {
      const auto at = std::find(cache_.neighbours.begin(), cache_.neighbours.end(), u);
      if (at != cache_.neighbours.end())
        return static_cast<std::int32_t>(at - cache_.neighbours.begin());
      cache_.neighbours.push_back(u);
      cache_.min_distance.push_back(kRepairMinDistanceFraction * distance(start_, u, v));
      return static_cast<std::int32_t>(cache_.neighbours.size() - 1);
    };
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::span<const std::int64_t> vertices = cell_vertices(cells[i]);
      const int type = static_cast<int>(m_.types[cells[i]]);
      const double* x = cache_.coords[i].data();  // (v's there may be a trial point's)
      for (std::int64_t u : vertices)
        if (u != v) neighbour(u);
      for (const auto [a, b] : edges_[type]) {
        if ((vertices[a] == v) != (vertices[b] == v)) {
          cache_.edges.push_back(neighbour(vertices[vertices[a] == v ? b : a]));
        } else {  // not at v (or from v to itself, which stays 0)
          const double length = edge_length(x + d * a, x + d * b, d);
          cache_.shortest[i] = std::min(cache_.shortest[i], length);
          cache_.longest[i] = std::max(cache_.longest[i], length);
        }
      }
      cache_.edges_first.push_back(static_cast<std::int32_t>(cache_.edges.size()));
    }
    cache_.distance.resize(cache_.neighbours.size());
    cache_.admissible_for = v;
  }
  // Writes v's coordinates into the gathered ones of its cell at position i in star(v).
  void place(std::int64_t v, std::size_t i) {
    const int d = m_.dim;
    const double* p = m_.coords.data() + d * v;
    for (const int k : cache_.v_at[i]) {
      if (k < 0) break;
      for (int a = 0; a < d; ++a) cache_.coords[i][d * k + a] = p[a];
    }
  }

  // The worst scaled Jacobian of v's cells and their sum; nothing as soon as one of them is at
  // most `beat` (the search's inner loop); of each cell only the corners v moves, and those
  // only until one shows it is at most `beat`. The
  // cells are judged in the order `worst_first` gives (positions in star(v), the worst cell
  // where v is first): a trial point mostly fails on the cell that was worst, so this is the
  // test that fails most, first (the annulus hexes of bench/peers.py: the repair's instructions
  // 5.3e9 -> 2.4e9; with only the corners v moves, from the star's coordinates gathered once,
  // 2.4e9 -> 1.05e9). The sum is taken in star order, so the order changes no result.
  struct Star {
    double worst = kInfinity, sum = 0.0;
  };
  std::optional<Star> around(std::int64_t v, double beat,
                             std::span<const std::uint32_t> worst_first) {
    const std::span<const std::int64_t> cells = star(v);
    star_sj_.resize(cells.size());
    for (std::uint32_t i : worst_first) {
      if (!(cache_.others[i] > beat)) return std::nullopt;
      place(v, i);
      star_sj_[i] = std::min(cache_.others[i], scaled_jacobian(cells[i], cache_.coords[i].data(),
                                                               beat, cache_.corners[i]));
      if (!(star_sj_[i] > beat)) return std::nullopt;
    }
    Star q;
    for (double sj : star_sj_) {
      q.worst = std::min(q.worst, sj);
      q.sum += sj;
    }
    return q;
  }

  // Whether v is at least kRepairMinDistanceFraction of its distance at the repair's start from
  // each vertex of its cells, and their edge ratios at most the mesh's largest at the start: from
  // the star's cache, each distance once, the edge ratios from the edges at v (an interior vertex
  // of hexahedra: 26 distances instead of 56, and no 8 whole edge ratios; with no check where v is,
  // the repair's instructions on the annulus hexes of bench/peers.py 1.05e9 -> 0.83e9).
  bool admissible(std::int64_t v) {
    if (cache_.admissible_for != v) gather_edges(v);
    const int d = m_.dim;
    const double* p = m_.coords.data() + d * v;
    for (std::size_t j = 0; j < cache_.neighbours.size(); ++j) {
      cache_.distance[j] = edge_length(m_.coords.data() + d * cache_.neighbours[j], p, d);
      if (!(cache_.distance[j] >= cache_.min_distance[j])) return false;
    }
    for (std::size_t i = 0; i + 1 < cache_.edges_first.size(); ++i) {
      double longest = cache_.longest[i], shortest = cache_.shortest[i];
      for (std::int32_t e = cache_.edges_first[i]; e < cache_.edges_first[i + 1]; ++e) {
        longest = std::max(longest, cache_.distance[cache_.edges[e]]);
        shortest = std::min(shortest, cache_.distance[cache_.edges[e]]);
      }
      if (!((shortest > 0.0 ? longest / shortest : kInfinity) <= max_edge_ratio_)) return false;
    }
    return true;
  }

  // Whether no vertex of v's cells moved since v's search last found nothing.
  bool unchanged_since_failure(std::int64_t v) const {
    for (std::int64_t c : star(v))
      for (std::int64_t u : cell_vertices(c))
        if (moved_at_[u] >= failed_at_[v]) return false;
    return true;
  }

  // Moves v to the best of the trial points if that raises the worst cell around it.
  bool improve(std::int64_t v, std::span<const double> steps) {
    if (failed_at_[v] > 0 && unchanged_since_failure(v)) return false;
    const std::span<const std::int64_t> cells = star(v);
    Star base;  // where v is: its cells' scaled Jacobians are up to date
    double base_imr = 0.0;
    for (std::int64_t c : cells) {
      base.worst = std::min(base.worst, sj_[c]), base.sum += sj_[c];
      if (imr_ceiling()) base_imr += imr_[c];
    }
    // No trial point lifts a cell above its corners that v does not move: once the best is
    // there, no trial can beat it, and a vertex whose worst cell's worst corner is one of those
    // makes no trial (the annulus hexes of bench/peers.py: 10,000 of 17,000 searches).
    const double ceiling = gather_corners(v);
    if (!(ceiling > base.worst + kRepairGain)) {
      failed_at_[v] = moves_ + 1;
      return false;
    }
    const int d = m_.dim;
    std::array<double, 3> from{};
    std::copy(m_.coords.begin() + d * v, m_.coords.begin() + d * (v + 1), from.begin());
    double h = kInfinity;  // the shortest edge length from v in its cells (an upper bound)
    for (std::int64_t c : cells)
      for (std::int64_t u : cell_vertices(c))
        if (u != v) h = std::min(h, distance(m_.coords, u, v));
    if (!(h > 0.0) || !std::isfinite(h)) return false;
    worst_first_.resize(cells.size());
    std::iota(worst_first_.begin(), worst_first_.end(), 0u);
    std::stable_sort(
        worst_first_.begin(), worst_first_.end(),
        [&](std::uint32_t a, std::uint32_t b) { return sj_[cells[a]] < sj_[cells[b]]; });
    gather_star(v);
    // Where v is, it is admissible: every move so far was, and each kept its cells' edge ratios
    // and its distances to their vertices within the bounds (a move of a neighbour u checked
    // the distance from u to v too).
    double best = base.worst;
    bool found = false, by_the_means = false;  // a trial refused by the floor or the ceiling
    std::array<double, 3> best_move{}, by{};
    const std::span<const double> from_d(from.data(), d), by_d(by.data(), d);
    for (double step : steps) {
      for (const std::array<double, 3>& dir : dirs_) {
        if (!(ceiling > best + kRepairGain)) break;
        for (int a = 0; a < d; ++a) by[a] = step * h * dir[a];
        move(v, from_d, by_d);
        const std::optional<Star> q = around(v, best + kRepairGain, worst_first_);
        if (!q) continue;
        // A move that lowers the mean may not take it below the floor.
        if (!(q->sum >= base.sum || sum_ - base.sum + q->sum >= min_sum_)) {
          by_the_means = true;
          continue;
        }
        if (!admissible(v)) continue;
        // ... nor one that raises the mean inverse mean ratio above its ceiling.
        if (imr_ceiling()) {
          const double imr = star_imr(v);
          if (!(imr <= base_imr || imr_sum_ - base_imr + imr <= max_imr_sum_)) {
            by_the_means = true;
            continue;
          }
        }
        best = q->worst;
        best_move = by;
        found = true;
      }
      if (found) break;
    }
    if (!found) {
      std::copy(from.begin(), from.begin() + d, m_.coords.begin() + d * v);
      // The same search gives the same answer until a vertex of v's cells moves, unless the
      // means, which every move changes, refused a trial.
      if (!by_the_means) failed_at_[v] = moves_ + 1;
      return false;
    }
    undo_coords_.push_back({v, from});
    move(v, from_d, std::span<const double>(best_move.data(), d));
    moved_at_[v] = ++moves_;
    for (std::int64_t c : cells) {
      undo_cells_.push_back({c, sj_[c], imr_ceiling() ? imr_[c] : 0.0, corner_[c]});
      const std::array<double, 3 * 8> x = cell_coords(c);
      sum_ -= sj_[c];
      sj_[c] = evaluate(c, x.data());
      sum_ += sj_[c];
      if (imr_ceiling()) {
        imr_sum_ -= imr_[c];
        imr_[c] = inverse_mean_ratio(c, x.data());
        imr_sum_ += imr_[c];
      }
    }
    return true;
  }

  WholeMesh& m_;
  const std::function<void(int, std::span<double>)>& project_;
  std::vector<std::int64_t> star_first_,
      star_;  // the cells of vertex v: star_[first[v], first[v+1])
  std::vector<std::array<double, 3>> normals_;  // per cell of a surface: at the start
  std::vector<double> sj_;                      // per cell
  // Per cell, its scaled Jacobian's value at each corner; their count per cell type.
  std::vector<std::array<double, kMaxScaledJacobianCorners>> corner_;
  std::array<int, kNumCellTypes> corner_count_{};
  std::vector<double> star_sj_;             // around()'s scratch: per cell of the star
  StarCache cache_;                         // improve()'s: of the vertex it moves
  std::vector<std::uint32_t> worst_first_;  // improve()'s: its star's cells, worst first
  std::vector<std::int64_t> candidates_;    // sweep()'s: the vertices it tries
  std::array<std::int64_t, kRepairWorstCells> worst_{};  // rank()'s: the worst cells
  std::size_t worst_count_ = 0;
  std::vector<std::uint8_t> candidate_ = std::vector<std::uint8_t>(m_.vertex_id.size());
  // Moves counted; per vertex, the count at its last move, and (if not 0) the count + 1 when
  // its search with failed_steps_ last found nothing.
  std::uint64_t moves_ = 0;
  std::vector<std::uint64_t> moved_at_ = std::vector<std::uint64_t>(m_.vertex_id.size());
  std::vector<std::uint64_t> failed_at_ = std::vector<std::uint64_t>(m_.vertex_id.size());
  const double* failed_steps_ = nullptr;
  // The sweep's moves, to undo them: the vertex's coordinates and its cells' values before.
  struct UndoVertex {
    std::int64_t vertex;
    std::array<double, 3> x;
  };
  struct UndoCell {
    std::int64_t cell;
    double sj, imr;
    std::array<double, kMaxScaledJacobianCorners> corners;
  };
  std::vector<UndoVertex> undo_coords_;
  std::vector<UndoCell> undo_cells_;
  double undo_sum_ = 0.0, undo_imr_sum_ = 0.0;
  // scaled_jacobian_corners_at per cell type and vertex, taken once.
  std::array<std::array<std::uint32_t, 8>, kNumCellTypes> corners_at_{};
  // The edges per cell type, as pairs of vertex positions: each facet's cycle (an edge twice).
  std::array<std::vector<std::array<int, 2>>, kNumCellTypes> edges_;
  std::vector<double> imr_;          // per cell's inverse mean ratio, with a ceiling on the mean
  double imr_sum_ = 0.0;             // of imr_
  double max_imr_sum_ = kInfinity;   // the ceiling of imr_sum_ for a move that raises it
  double sum_ = 0.0;                 // of sj_
  double min_sum_ = 0.0;             // the floor of sum_ for a move that lowers it
  double max_edge_ratio_ = 0.0;      // the mesh's largest at the repair's start
  const std::vector<double> start_;  // the coordinates at the repair's start
  std::vector<std::array<double, 3>> dirs_ = repair_directions(m_.dim);
};

}  // namespace

WorstCellRepair repair_worst_cells(const MeshView& view, const DofMap& dofs,
                                   const RepairFreedom& freedom, Vec x, double min_mean,
                                   double max_mean_imr) {
  return repair_in_sweeps(view, dofs, freedom, x, [&](WholeMesh& mesh) {
    return Repair(mesh, freedom, min_mean, max_mean_imr);
  });
}

}  // namespace neomesh
