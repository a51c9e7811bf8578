#include "report/colormap.hpp"

#include <algorithm>
#include <array>

namespace neomesh {

namespace {

// Entries 0, 16, ..., 240, 255 of matplotlib's _viridis_data, at t = index / 255.
constexpr std::array<ColormapStop, 17> kViridis = {{
    {0.0 / 255, {0.267004, 0.004874, 0.329415}},
    {16.0 / 255, {0.282327, 0.094955, 0.417331}},
    {32.0 / 255, {0.278826, 0.175490, 0.483397}},
    {48.0 / 255, {0.258965, 0.251537, 0.524736}},
    {64.0 / 255, {0.229739, 0.322361, 0.545706}},
    {80.0 / 255, {0.199430, 0.387607, 0.554642}},
    {96.0 / 255, {0.172719, 0.448791, 0.557885}},
    {112.0 / 255, {0.149039, 0.508051, 0.557250}},
    {128.0 / 255, {0.127568, 0.566949, 0.550556}},
    {144.0 / 255, {0.120638, 0.625828, 0.533488}},
    {160.0 / 255, {0.157851, 0.683765, 0.501686}},
    {176.0 / 255, {0.246070, 0.738910, 0.452024}},
    {192.0 / 255, {0.369214, 0.788888, 0.382914}},
    {208.0 / 255, {0.515992, 0.831158, 0.294279}},
    {224.0 / 255, {0.678489, 0.863742, 0.189503}},
    {240.0 / 255, {0.845561, 0.887322, 0.099702}},
    {255.0 / 255, {0.993248, 0.906157, 0.143936}},
}};

}  // namespace

std::span<const ColormapStop> viridis_stops() {
  return kViridis;
}

Rgb viridis(double t) {
  t = t > 0 ? std::min(t, 1.0) : 0.0;  // NaN too: callers colour invalid values themselves
  auto upper = std::upper_bound(kViridis.begin() + 1, kViridis.end() - 1, t,
                                [](double v, const ColormapStop& s) { return v < s.t; });
  const ColormapStop& a = *(upper - 1);
  const ColormapStop& b = *upper;
  const double w = (t - a.t) / (b.t - a.t);
  return {a.colour.r + w * (b.colour.r - a.colour.r), a.colour.g + w * (b.colour.g - a.colour.g),
          a.colour.b + w * (b.colour.b - a.colour.b)};
}

}  // namespace neomesh
