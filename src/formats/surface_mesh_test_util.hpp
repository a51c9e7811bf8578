// Surface meshes as Gmsh files, for the tests of the layers that read them.
#pragma once

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "core/testing/test_data.hpp"

namespace neomesh::testing {

// A quarter of the cylinder x² + y² = 1, 0 ≤ z ≤ 1, as a Gmsh 2.2 file: n × n quadrilaterals
// (the lower half in group 1, the upper in group 2), the quads of row 0 split into two
// triangles each. With `flip`, one triangle runs the other way round.
inline std::string cylinder_patch(int n, bool flip = false) {
  std::string nodes, elements;
  const auto id = [n](int i, int j) { return 1 + i + (n + 1) * j; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double theta = std::numbers::pi / 2 * i / n;
      nodes += fmt::format("{} {:.17g} {:.17g} {:.17g}\n", id(i, j), std::cos(theta),
                           std::sin(theta), static_cast<double>(j) / n);
    }
  int count = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int group = j < n / 2 ? 1 : 2;
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (j == 0) {
        elements += fmt::format("{} 2 2 {} {} {} {} {}\n", ++count, group, group, a, b, c);
        if (flip && i == 0)
          elements += fmt::format("{} 2 2 {} {} {} {} {}\n", ++count, group, group, a, d, c);
        else
          elements += fmt::format("{} 2 2 {} {} {} {} {}\n", ++count, group, group, a, c, d);
      } else {
        elements += fmt::format("{} 3 2 {} {} {} {} {} {}\n", ++count, group, group, a, b, c, d);
      }
    }
  return fmt::format(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"low\"\n2 2 \"high\"\n"
      "$EndPhysicalNames\n$Nodes\n{}\n{}$EndNodes\n$Elements\n{}\n{}$EndElements\n",
      (n + 1) * (n + 1), nodes, count, elements);
}

// `text` in a scratch file `name`.
inline std::filesystem::path write_scratch(const std::string& name, const std::string& text) {
  const auto path = scratch_dir("SurfaceMesh") / name;
  std::ofstream(path) << text;
  return path;
}

// The surface of the cube [0,1]³, n × n quadrilaterals per face, one group, facing outwards.
inline std::string cube_surface(int n) {
  std::string nodes, elements;
  int nodes_count = 0, count = 0;
  std::map<std::array<int, 3>, int> id;  // by integer position
  const auto node = [&](int i, int j, int k) {
    const auto [it, added] = id.try_emplace({i, j, k}, nodes_count + 1);
    if (added)
      nodes +=
          fmt::format("{} {:.17g} {:.17g} {:.17g}\n", ++nodes_count, static_cast<double>(i) / n,
                      static_cast<double>(j) / n, static_cast<double>(k) / n);
    return it->second;
  };
  // Each face: its fixed axis and side, and two in-face axes (a, b) with a × b along the outside.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      int a = (axis + 1) % 3, b = (axis + 2) % 3;
      if (side == 0) std::swap(a, b);
      for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
          int corner[4];
          const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
          for (int q = 0; q < 4; ++q) {
            std::array<int, 3> p{};
            p[axis] = side * n;
            p[a] = u + du[q];
            p[b] = v + dv[q];
            corner[q] = node(p[0], p[1], p[2]);
          }
          elements += fmt::format("{} 3 2 1 1 {} {} {} {}\n", ++count, corner[0], corner[1],
                                  corner[2], corner[3]);
        }
    }
  return fmt::format(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n{}\n{}$EndNodes\n$Elements\n{}\n{}"
      "$EndElements\n",
      nodes_count, nodes, count, elements);
}

}  // namespace neomesh::testing
