// Ricochet physics: the broadphase. Proxies are shape AABBs; the broadphase finds the pairs
// whose AABBs overlap and answers AABB and point queries, so that exact geometry runs only on
// candidates.
//
// Two implementations with one interface:
//   Quadtree    a loose quadtree (Ulrich, "Loose Octrees", Game Programming Gems 2000) over a
//               fixed square world. A proxy lives in exactly one cell: the deepest level whose
//               cells are at least twice its size, the cell that holds its centre. A cell's
//               loose bounds are the cell grown by half a cell on every side, so a proxy always
//               lies inside the loose bounds of its cell: nothing straddles, nothing is indexed
//               by its centre alone (the Doom blockmap bug), and insert, remove and move are
//               O(1) with no rebalancing. Cells are a dense array per level with intrusive
//               doubly linked lists of proxies, so moving a proxy never allocates.
//   BruteForce  every proxy against every proxy: the reference for the tests, and the right
//               choice for scenes of a few dozen proxies.
//
// Why a loose quadtree: the scenes of a top-down shooter are a few hundred static walls and up
// to tens of thousands of similar-sized movers. Those all land on one or two levels, where a
// query visits a fixed 3x3 block of cells per level (loose bounds overlap the neighbours), so
// cost per proxy does not grow with N; a region quadtree with straddler lists costs the same
// per query but pays for splits and merges while things move.
//
// Static and moving proxies are kept apart: static proxies sit in their own tree and are never
// visited by the per-step loops except as partners of movers; static-static pairs are never
// reported. Every proxy's AABB is stored enlarged by a margin (fat AABB): moveProxy only
// touches the tree when the new AABB leaves the fat one.
//
// Proxies whose centre lies outside the world square, or that are larger than it, go to an
// "outside" list that every query scans: they are never lost, and the tree's depth stays
// bounded (maxDepth) whatever the input. NaN or infinite bounds are rejected with
// rc::InvalidProxy. Pairs come out sorted by (lower id, higher id): the order never depends
// on memory addresses.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/math.h"

namespace rc {

using ProxyId = std::int32_t;
inline constexpr ProxyId kNullProxy = -1;

// Collision filter: two proxies pair up when each one's category is in the other's mask.
struct ProxyFilter {
  std::uint32_t category = 1;
  std::uint32_t mask = 0xFFFFFFFFu;
};
constexpr bool shouldCollide(ProxyFilter a, ProxyFilter b) {
  return (a.category & b.mask) != 0 && (b.category & a.mask) != 0;
}

struct ProxyPair {
  ProxyId a, b;  // a < b
  friend constexpr bool operator==(const ProxyPair&, const ProxyPair&) = default;
  friend constexpr bool operator<(const ProxyPair& x, const ProxyPair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  }
};

class InvalidProxy : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Margin added around every AABB: a mover at 5 m/s and 60 Hz stays inside its fat AABB for
// about two steps.
inline constexpr float kAabbMargin = 0.1f;

struct ProxyDef {
  AABB aabb;
  ProxyFilter filter;
  bool isStatic = false;
  std::uint64_t userData = 0;
};

// What both implementations share: proxy storage with a free list and generational reuse.
struct ProxyData {
  AABB fat;
  ProxyFilter filter;
  std::uint64_t userData = 0;
  bool isStatic = false;
  bool alive = false;
  // Quadtree placement: level, cell, and links in the cell's list (-1: none). level -1 means
  // the outside list.
  std::int32_t level = 0;
  std::int32_t cell = 0;
  ProxyId prev = kNullProxy, next = kNullProxy;
};

class Quadtree {
 public:
  // worldBounds: the region most proxies live in (the level's bounds); it is made square.
  // maxDepth: deepest level (0 is the root); clamped to [0, 12].
  explicit Quadtree(const AABB& worldBounds, int maxDepth = 8);

  ProxyId createProxy(const ProxyDef& def);
  void destroyProxy(ProxyId id);
  // New tight AABB for a proxy. Returns true when it left its fat AABB and was re-inserted.
  bool moveProxy(ProxyId id, const AABB& aabb);

  const AABB& fatAABB(ProxyId id) const { return proxies_[checked(id)].fat; }
  std::uint64_t userData(ProxyId id) const { return proxies_[checked(id)].userData; }
  int proxyCount() const { return count_; }

  // Every pair of overlapping fat AABBs with at least one moving proxy that passes the
  // filters, each once, sorted. `pairs` is cleared first.
  void findPairs(std::vector<ProxyPair>& pairs) const;

  // Calls visit(id) for every proxy whose fat AABB overlaps `box` and passes the filter
  // (category against the proxies' masks and the reverse); visit returns false to stop.
  template <class Visit>
  void queryAABB(const AABB& box, ProxyFilter filter, Visit&& visit) const;
  std::vector<ProxyId> queryAABB(const AABB& box, ProxyFilter filter = {}) const;
  std::vector<ProxyId> queryPoint(Vec2 p, ProxyFilter filter = {}) const;

  // Checks every invariant (links, placement, counts); throws std::logic_error naming the
  // first broken one.
  void validate() const;

 private:
  struct Level {
    float cellSize = 0.0f;
    int side = 0;                // cells per row
    std::vector<ProxyId> heads;  // first proxy of each cell
    int population = 0;          // proxies on this level
  };
  struct Tree {
    std::vector<Level> levels;
    ProxyId outside = kNullProxy;  // list of proxies kept outside the cells
    int outsideCount = 0;
  };

  std::size_t checked(ProxyId id) const;
  void place(ProxyId id);
  void unlink(ProxyId id);
  void link(ProxyId id, Tree& tree, int level, int cell);
  ProxyId& headOf(Tree& tree, int level, int cell);
  Tree& treeOf(const ProxyData& p) { return p.isStatic ? static_ : moving_; }
  const Tree& treeOf(const ProxyData& p) const { return p.isStatic ? static_ : moving_; }
  template <class Visit>
  bool queryTree(const Tree& tree, const AABB& box, Visit& visit) const;

  Vec2 origin_{};
  float size_ = 0.0f;
  int maxDepth_ = 0;
  Tree static_, moving_;
  std::vector<ProxyData> proxies_;
  std::vector<ProxyId> free_;
  int count_ = 0;
};

// The reference: the same interface, every proxy against every proxy.
class BruteForce {
 public:
  ProxyId createProxy(const ProxyDef& def);
  void destroyProxy(ProxyId id);
  bool moveProxy(ProxyId id, const AABB& aabb);
  const AABB& fatAABB(ProxyId id) const { return proxies_[checked(id)].fat; }
  int proxyCount() const { return count_; }
  void findPairs(std::vector<ProxyPair>& pairs) const;
  std::vector<ProxyId> queryAABB(const AABB& box, ProxyFilter filter = {}) const;
  std::vector<ProxyId> queryPoint(Vec2 p, ProxyFilter filter = {}) const;

 private:
  std::size_t checked(ProxyId id) const;
  std::vector<ProxyData> proxies_;
  std::vector<ProxyId> free_;
  int count_ = 0;
};

// ---------------------------------------------------------------------------------------------

template <class Visit>
bool Quadtree::queryTree(const Tree& tree, const AABB& box, Visit& visit) const {
  for (ProxyId id = tree.outside; id != kNullProxy; id = proxies_[id].next)
    if (overlaps(proxies_[id].fat, box) && !visit(id)) return false;
  for (int l = 0; l < static_cast<int>(tree.levels.size()); ++l) {
    const Level& level = tree.levels[l];
    if (level.population == 0) continue;
    // Cells whose loose bounds (the cell grown by half a cell) overlap the box.
    const float inv = 1.0f / level.cellSize;
    // A hair over half a cell: placement rounds the proxy's centre, and a proxy an ulp outside
    // its loose bounds must still be found.
    const float half = 0.5001f * level.cellSize;
    auto index = [&](float v) {
      float f = std::floor(v * inv);
      return f < 0.0f                              ? 0
             : f >= static_cast<float>(level.side) ? level.side - 1
                                                   : static_cast<int>(f);
    };
    const int x0 = index(box.lower.x - origin_.x - half),
              x1 = index(box.upper.x - origin_.x + half);
    const int y0 = index(box.lower.y - origin_.y - half),
              y1 = index(box.upper.y - origin_.y + half);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        for (ProxyId id = level.heads[static_cast<std::size_t>(y * level.side + x)];
             id != kNullProxy; id = proxies_[id].next)
          if (overlaps(proxies_[id].fat, box) && !visit(id)) return false;
      }
    }
  }
  return true;
}

template <class Visit>
void Quadtree::queryAABB(const AABB& box, ProxyFilter filter, Visit&& visit) const {
  if (!(box.lower.x <= box.upper.x) || !(box.lower.y <= box.upper.y))  // false for NaN too
    throw InvalidProxy("Quadtree::queryAABB: NaN or inverted query box");
  auto filtered = [&](ProxyId id) {
    return !shouldCollide(filter, proxies_[id].filter) || visit(id);
  };
  if (queryTree(moving_, box, filtered)) queryTree(static_, box, filtered);
}

}  // namespace rc
