// The quality of a whole (possibly distributed) mesh: cell counts and the min/mean/max of each
// metric (docs/user-guide.md defines them).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include <neomesh/cell_type.hpp>

namespace neomesh {

struct MetricStats {
  double min = 0.0, mean = 0.0, max = 0.0;
};

struct QualitySummary {
  std::int64_t cells = 0;
  std::array<std::int64_t, kNumCellTypes> cells_by_type{};  // indexed by CellType
  MetricStats volume, min_corner_det, min_gauss_det, scaled_jacobian, min_angle, max_angle,
      edge_ratio, inverse_mean_ratio;
  std::int64_t inverted = 0;    // det J ≤ 0 at a corner or Gauss point
  std::int64_t degenerate = 0;  // |volume| < 1e-14 · mean |volume|, or an edge of length 0

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
