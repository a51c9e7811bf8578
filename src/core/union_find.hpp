// Disjoint sets of the elements 0..n-1 (union-find with path halving), each named by its
// smallest element: the boundary's patches and ridges, the joined nodes of a CGNS file's zones.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace neomesh {

struct UnionFind {
  explicit UnionFind(std::size_t n) : parent(n) {
    std::iota(parent.begin(), parent.end(), std::size_t{0});
  }
  // The smallest element of i's set.
  std::size_t find(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  // Per element: its set, numbered 0, 1, ... in order of the sets' smallest elements.
  std::vector<int> labels(int& count) {
    std::vector<int> label(parent.size(), -1), of_root(parent.size(), -1);
    count = 0;
    for (std::size_t i = 0; i < parent.size(); ++i) {
      const std::size_t r = find(i);
      if (of_root[r] < 0) of_root[r] = count++;
      label[i] = of_root[r];
    }
    return label;
  }
  std::vector<std::size_t> parent;
};

}  // namespace neomesh
