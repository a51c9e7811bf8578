// The surface (or, in 2D, the curve) a FEAT3 chart describes (mesh/chart.hpp), as a
// closest-point map: what boundary vertices of a part attached to the chart slide on and what
// `neomesh curve` puts the part's second-order nodes on.
#pragma once

#include <memory>
#include <string>

#include "boundary/shape.hpp"
#include "mesh/chart.hpp"

namespace neomesh {

// Throws Error naming the chart and `part` if the chart does not fit a mesh of dimension `dim`
// (a circle in 3D) or is malformed.
std::unique_ptr<Surface> chart_surface(const Chart& chart, int dim, const std::string& part);

}  // namespace neomesh
