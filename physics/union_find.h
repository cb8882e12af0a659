// Ricochet physics: the root of a union-find forest's tree (parent[x] == x at a root), the path
// halved on the way (each entry visited pointed at its grandparent) so that trees stay shallow.
// Islands, restitution's groups and the stack solve's piles each keep their own forest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rc {

inline std::int32_t unionFindRoot(std::vector<std::int32_t>& parent, std::int32_t x) {
  while (parent[static_cast<std::size_t>(x)] != x) {
    parent[static_cast<std::size_t>(x)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    x = parent[static_cast<std::size_t>(x)];
  }
  return x;
}

}  // namespace rc
