// The quality of a whole (possibly distributed) mesh: cell counts and the min/mean/max of each
// metric (docs/user-guide.md defines them).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <neomesh/cell_type.hpp>

namespace neomesh {

struct MetricStats {
  double min = 0.0, mean = 0.0, max = 0.0;
};

// The curved cells of a mesh of second-order cells (docs/user-guide.md, "Curved meshes";
// docs/method.md §11): validity by the Bézier certificate of det J > 0 everywhere, and the
// curved scaled Jacobian, whose minimum over a cell is bounded by sampling and by the
// certificate's Bézier coefficients.
struct CurvedQualitySummary {
  std::vector<std::pair<std::string, std::int64_t>> cells_by_type;  // ("triangle6", 12), ...
  std::int64_t not_valid = 0;  // cells not certified valid: invalid or undecided
  std::int64_t invalid = 0;    // det J ≤ 0 at a sample point
  std::int64_t undecided = 0;  // neither at the certificate's depth limit
  // Per cell the least sampled scaled Jacobian: the minimum over the cell up to the
  // certificate's resolution (a value the cell takes, so never below the true minimum).
  MetricStats scaled_jacobian;
  // The least certified lower bound of the minimum over a cell (−1/optimal value for a cell not
  // certified valid).
  double scaled_jacobian_lower_bound = 0.0;
};

struct QualitySummary {
  std::int64_t cells = 0;
  std::array<std::int64_t, kNumCellTypes> cells_by_type{};  // indexed by CellType
  MetricStats volume, min_corner_det, min_gauss_det, scaled_jacobian, min_angle, max_angle,
      edge_ratio, inverse_mean_ratio;
  std::int64_t inverted = 0;    // det J ≤ 0 at a corner or Gauss point
  std::int64_t degenerate = 0;  // |volume| < 1e-14 · mean |volume|, or an edge of length 0
  // A mesh of second-order cells: the metrics above are those of the straight cells on their
  // corners, these of the curved cells.
  std::optional<CurvedQualitySummary> curved;

  // The metrics with their names (as in the table and the JSON), in display order.
  std::vector<std::pair<std::string_view, MetricStats>> metrics() const;
};

// How well an adapted mesh meets its desired volumes: the distribution of Q = actual volume /
// desired volume (thesis §6.2); Q = 1 is a perfect fit.
struct VolumeRatioStats {
  std::int64_t cells = 0;
  double within = 0.0;  // fraction of cells with Q in [1/2, 2]
  double min = 0.0, median = 0.0, max = 0.0;
};

}  // namespace neomesh
