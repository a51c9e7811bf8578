// Colours for pictures: the viridis colormap (perceptually uniform, readable in grey and by
// colour-blind viewers), as control points sampled from matplotlib's table (CC0) every 16
// of its 256 entries, linearly interpolated in between.
#pragma once

#include <span>

namespace neomesh {

struct Rgb {
  double r = 0, g = 0, b = 0;
};

struct ColormapStop {
  double t;  // position in [0, 1]
  Rgb colour;
};

// The control points, t ascending from 0 to 1 (for gradients that reproduce viridis()).
std::span<const ColormapStop> viridis_stops();

// viridis at t, clamped to [0, 1]; t = 0 is dark purple, t = 1 yellow.
Rgb viridis(double t);

}  // namespace neomesh
