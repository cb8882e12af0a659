#include "game/level/tile_outline.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace game {

namespace {

// Directions in the grid's y-down frame; turning right (clockwise on screen) is +1.
constexpr int kDx[4] = {1, 0, -1, 0};  // east, south, west, north
constexpr int kDy[4] = {0, 1, 0, -1};

}  // namespace

std::vector<std::vector<GridCorner>> traceOutlines(int width, int height,
                                                   std::span<const std::uint8_t> solid) {
  if (width < 0 || height < 0 ||
      solid.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("traceOutlines: the grid holds " + std::to_string(solid.size()) +
                                " cells, not width * height");
  const int stride = width + 1;  // corners per row
  auto cell = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width && y < height &&
           solid[static_cast<std::size_t>(y) * width + x] != 0;
  };
  // out[c]: a bit per direction in which an unused boundary edge leaves corner c.
  std::vector<std::uint8_t> out(static_cast<std::size_t>(stride) * (height + 1), 0);
  auto at = [&](int x, int y) -> std::uint8_t& {
    return out[static_cast<std::size_t>(y) * stride + x];
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!cell(x, y)) continue;
      if (!cell(x, y - 1)) at(x, y) |= 1 << 0;          // top side, eastward
      if (!cell(x + 1, y)) at(x + 1, y) |= 1 << 1;      // right side, southward
      if (!cell(x, y + 1)) at(x + 1, y + 1) |= 1 << 2;  // bottom side, westward
      if (!cell(x - 1, y)) at(x, y + 1) |= 1 << 3;      // left side, northward
    }

  std::vector<std::vector<GridCorner>> loops;
  for (int sy = 0; sy <= height; ++sy)
    for (int sx = 0; sx <= width; ++sx) {
      while (at(sx, sy) != 0) {
        // Follow edges until back at the start, one unit step at a time, keeping the corners
        // where the direction changes.
        int dir = 0;
        while ((at(sx, sy) & (1 << dir)) == 0)
          ++dir;
        const int firstDir = dir;
        std::vector<GridCorner> loop;
        int x = sx, y = sy;
        while (true) {
          at(x, y) &= static_cast<std::uint8_t>(~(1 << dir));
          x += kDx[dir];
          y += kDy[dir];
          if (x == sx && y == sy) break;
          const std::uint8_t options = at(x, y);
          // At a corner shared by two diagonal cells both ways are open: turning right keeps
          // to the cell this edge belongs to. Elsewhere exactly one way is open.
          int next = (dir + 1) % 4;
          if ((options & (1 << next)) == 0) next = dir;
          if ((options & (1 << next)) == 0) next = (dir + 3) % 4;
          if ((options & (1 << next)) == 0)
            throw std::logic_error("traceOutlines: an outline does not close");
          if (next != dir) loop.push_back({x, y});
          dir = next;
        }
        // The start is a corner unless the loop arrives going its first way.
        if (dir != firstDir) loop.insert(loop.begin(), GridCorner{sx, sy});
        // Traced with the solid on the right; handed back the other way round, solid on the
        // left, which is the side a one-sided chain link does not collide on.
        std::reverse(loop.begin() + 1, loop.end());
        loops.push_back(std::move(loop));
      }
    }
  return loops;
}

std::size_t countOutlineCorners(int width, int height, std::span<const std::uint8_t> solid) {
  if (width < 0 || height < 0 ||
      solid.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("countOutlineCorners: the grid holds " +
                                std::to_string(solid.size()) + " cells, not width * height");
  auto cell = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width && y < height &&
           solid[static_cast<std::size_t>(y) * width + x] != 0;
  };
  std::size_t corners = 0;
  for (int y = 0; y <= height; ++y)
    for (int x = 0; x <= width; ++x) {
      const bool nw = cell(x - 1, y - 1), ne = cell(x, y - 1), sw = cell(x - 1, y), se = cell(x, y);
      const int n = int(nw) + int(ne) + int(sw) + int(se);
      if (n == 1 || n == 3) corners += 1;
      if (n == 2 && nw == se) corners += 2;
    }
  return corners;
}

}  // namespace game
