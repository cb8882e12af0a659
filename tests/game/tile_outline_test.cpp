// Tile merging: outlines traced around solid tiles against a brute force over the grid. Every
// side of a solid cell that faces an empty cell is covered by exactly one outline edge,
// directed with the solid on its left as drawn, and no edge lies anywhere else; straight runs
// are single edges.
#include "game/level/tile_outline.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <tuple>

#include "physics/random.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace tile_outline_test {

using game::GridCorner;

struct Grid {
  int width, height;
  std::vector<std::uint8_t> cells;
  bool at(int x, int y) const {
    return x >= 0 && y >= 0 && x < width && y < height && cells[y * width + x] != 0;
  }
};

Grid parse(const std::vector<std::string>& rows) {
  Grid g{static_cast<int>(rows[0].size()), static_cast<int>(rows.size()), {}};
  for (const std::string& r : rows)
    for (const char c : r)
      g.cells.push_back(c == '#' ? 1 : 0);
  return g;
}

Grid block(int width, int height, int x0, int y0, int w, int h) {
  Grid g{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height, 0)};
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      g.cells[y * width + x] = 1;
  return g;
}

using UnitEdge = std::tuple<int, int, int, int>;  // from (x, y) to (x', y'), one cell long

// What the outlines must cover: each solid cell's sides that face an empty cell, directed
// with the cell on the left as drawn (row 0 at the top): the top side westward, the left side
// southward (down the screen), the bottom eastward, the right side northward.
std::map<UnitEdge, int> boundaryByBruteForce(const Grid& g) {
  std::map<UnitEdge, int> edges;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      if (!g.at(x, y)) continue;
      if (!g.at(x, y - 1)) edges[{x + 1, y, x, y}] = 0;
      if (!g.at(x - 1, y)) edges[{x, y, x, y + 1}] = 0;
      if (!g.at(x, y + 1)) edges[{x, y + 1, x + 1, y + 1}] = 0;
      if (!g.at(x + 1, y)) edges[{x + 1, y + 1, x + 1, y}] = 0;
    }
  return edges;
}

// Checks the loops against the brute force; returns the loops' sizes.
std::vector<int> checkOutlines(const Grid& g) {
  const auto loops = game::traceOutlines(g.width, g.height, g.cells);
  std::map<UnitEdge, int> expected = boundaryByBruteForce(g);
  std::vector<int> sizes;
  std::size_t corners = 0;
  for (const auto& loop : loops) {
    sizes.push_back(static_cast<int>(loop.size()));
    corners += loop.size();
    EXPECT_GE(loop.size(), 4u);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const GridCorner a = loop[i], b = loop[(i + 1) % loop.size()],
                       c = loop[(i + 2) % loop.size()];
      // Axis-aligned, and a corner at every vertex: no straight-through vertex is left.
      EXPECT_TRUE((a.x == b.x) != (a.y == b.y)) << "edge " << i << " is not axis-aligned";
      const int dx1 = (b.x > a.x) - (b.x < a.x), dy1 = (b.y > a.y) - (b.y < a.y);
      const int dx2 = (c.x > b.x) - (c.x < b.x), dy2 = (c.y > b.y) - (c.y < b.y);
      EXPECT_NE(dx1 * dy2 - dy1 * dx2, 0) << "vertex " << (i + 1) % loop.size() << " is straight";
      for (int x = a.x, y = a.y; x != b.x || y != b.y; x += dx1, y += dy1) {
        auto it = expected.find({x, y, x + dx1, y + dy1});
        if (it == expected.end()) {
          ADD_FAILURE() << "edge (" << x << "," << y << ")->(" << x + dx1 << "," << y + dy1
                        << ") is not a boundary edge with the solid on its left";
          continue;
        }
        ++it->second;
      }
    }
  }
  for (const auto& [edge, count] : expected)
    EXPECT_EQ(count, 1) << "boundary edge (" << std::get<0>(edge) << "," << std::get<1>(edge)
                        << ")->(" << std::get<2>(edge) << "," << std::get<3>(edge) << ")";
  EXPECT_EQ(game::countOutlineCorners(g.width, g.height, g.cells), corners);
  return sizes;
}

TEST(TileOutline, SolidBlockIsOneLoopOfFourLinks) {
  const Grid g = block(40, 40, 0, 0, 40, 40);
  EXPECT_EQ(checkOutlines(g), (std::vector<int>{4}));
  const auto loops = game::traceOutlines(g.width, g.height, g.cells);
  // Down the left side first: counter-clockwise as drawn.
  EXPECT_EQ(loops[0], (std::vector<GridCorner>{{0, 0}, {0, 40}, {40, 40}, {40, 0}}));
  // The same block inside a larger grid, away from its edges.
  EXPECT_EQ(checkOutlines(block(50, 45, 3, 2, 40, 40)), (std::vector<int>{4}));
}

TEST(TileOutline, LShapeIsOneLoopOfSix) {
  EXPECT_EQ(checkOutlines(parse({"#...",  //
                                 "#...",  //
                                 "####"})),
            (std::vector<int>{6}));
}

TEST(TileOutline, RingIsAnOuterLoopAndAHole) {
  const Grid g = parse({"#####",  //
                        "#...#",  //
                        "#...#",  //
                        "#####"});
  EXPECT_EQ(checkOutlines(g), (std::vector<int>{4, 4}));
  const auto loops = game::traceOutlines(g.width, g.height, g.cells);
  // The hole runs the other way round: clockwise as drawn.
  EXPECT_EQ(loops[1], (std::vector<GridCorner>{{1, 1}, {4, 1}, {4, 3}, {1, 3}}));
}

TEST(TileOutline, CellsTouchingAtACornerKeepTheirOwnLoops) {
  EXPECT_EQ(checkOutlines(parse({"#.",  //
                                 ".#"})),
            (std::vector<int>{4, 4}));
  EXPECT_EQ(checkOutlines(parse({".#",  //
                                 "#."})),
            (std::vector<int>{4, 4}));
  // A ring whose hole touches the outside at a corner, and a checkerboard.
  checkOutlines(parse({"###.",  //
                       "#.#.",  //
                       "###.",  //
                       "...#"}));
  checkOutlines(parse({"#.#.#",  //
                       ".#.#.",  //
                       "#.#.#"}));
}

TEST(TileOutline, EmptyAndFullGrids) {
  EXPECT_TRUE(checkOutlines(parse({"....", "...."})).empty());
  EXPECT_EQ(checkOutlines(parse({"#"})), (std::vector<int>{4}));
  EXPECT_THROW(game::traceOutlines(3, 3, std::vector<std::uint8_t>(8)), std::invalid_argument);
}

TEST(TileOutline, RandomGridsAgainstBruteForce) {
  rc::Random random(19);
  for (int round = 0; round < 300; ++round) {
    const int w = 1 + static_cast<int>(random.below(24)),
              h = 1 + static_cast<int>(random.below(24));
    const float density = random.uniform(0.1f, 0.9f);
    Grid g{w, h, {}};
    for (int i = 0; i < w * h; ++i)
      g.cells.push_back(random.uniform() < density ? 1 : 0);
    SCOPED_TRACE("round " + std::to_string(round));
    checkOutlines(g);
    if (HasFailure()) return;
  }
}

}  // namespace tile_outline_test
