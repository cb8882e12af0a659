// Ricochet physics: the broadphase. Proxies are shape AABBs; the broadphase finds the pairs
// whose AABBs overlap and answers AABB, point, ray and swept-circle queries, so that exact
// geometry runs only on candidates.
//
// Two implementations with one interface:
//   Quadtree    a loose quadtree (Ulrich, "Loose Octrees", Game Programming Gems 2000) over a
//               fixed square world. A proxy lives in exactly one cell: the deepest level whose
//               cells are at least as large as it, the cell that holds its centre. A cell's
//               loose bounds are the cell grown by half a cell on every side, so a proxy always
//               lies inside the loose bounds of its cell: nothing straddles, nothing is indexed
//               by its centre alone (the Doom blockmap bug), and insert, remove and move are
//               O(1) with no rebalancing. Cells are a dense array per level with intrusive
//               doubly linked lists of proxies, so moving a proxy never allocates.
//   BruteForce  every proxy against every proxy: the reference for the tests. The Quadtree
//               itself answers by brute force while it holds few proxies (kBruteForceBelow,
//               measured: see tests/bench/README.md, broadphase).
//
// Why a loose quadtree: the scenes of a top-down shooter are a few hundred static walls and up
// to tens of thousands of similar-sized movers. Those all land on one or two levels, where a
// query visits a fixed 3x3 block of cells per level (loose bounds overlap the neighbours), so
// cost per proxy does not grow with N; a region quadtree with straddler lists costs the same
// per query but pays for splits and merges while things move, and a tree rebuilt every step
// pays for all proxies when only a few left their fat AABBs.
//
// Static and moving proxies are kept apart: static proxies sit in their own tree and are never
// visited by the per-step loops except as partners of movers; static-static pairs are never
// reported. Every proxy's AABB is stored enlarged (fat AABB): by a margin on every side and,
// when the caller passes the step's displacement, stretched along the motion; moveProxy only
// touches the tree when the new AABB leaves the fat one. Proxies that did are buffered, and
// updatePairs reports the pairs that involve them: the new pairs a contact manager must add.
//
// Proxies whose centre lies outside the world square, or that are larger than it, go to an
// "outside" list that every query scans: they are never lost, and the tree's depth stays
// bounded (maxDepth) whatever the input. NaN or infinite bounds are rejected with
// rc::InvalidProxy. Pairs come out sorted by (lower id, higher id) and query results by id or
// by (fraction, id): no order depends on memory addresses.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/bytes.h"
#include "physics/math.h"
#include "physics/raycast.h"

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
// about two steps (the same margin as Box2D's b2_aabbExtension).
inline constexpr float kAabbMargin = 0.1f;
// A fat AABB is stretched along the step's displacement d by kDisplacementMultiplier times it,
// so that a steady mover re-enters the tree every few steps rather than every step (it must
// also hold the next step's sweep); but by no more than kMaxPrediction beyond d itself, so
// that a bullet's box covers its next step without reaching across the level. 6 measured
// best of 4, 5, 6, 8 for the pair update against what larger boxes cost (more pairs).
inline constexpr float kDisplacementMultiplier = 6.0f;
inline constexpr float kMaxPrediction = 1.0f;
// The stretch along the displacement d: d * min(multiplier, 1 + kMaxPrediction / |d|).
Vec2 cappedStretch(Vec2 displacement);  // where the cap bites (broadphase.cpp)
inline Vec2 predictedStretch(Vec2 displacement) {
  // Below this length the cap does not bite: no square root for the usual mover.
  constexpr float uncapped = kMaxPrediction / (kDisplacementMultiplier - 1.0f);
  if (lengthSquared(displacement) <= uncapped * uncapped)
    return kDisplacementMultiplier * displacement;
  return cappedStretch(displacement);
}
// The fat AABB for a tight one: the margin on every side, stretched along the displacement.
inline AABB fatten(const AABB& aabb, Vec2 displacement) {
  AABB fat = inflate(aabb, kAabbMargin);
  const Vec2 d = predictedStretch(displacement);
  (d.x < 0.0f ? fat.lower.x : fat.upper.x) += d.x;
  (d.y < 0.0f ? fat.lower.y : fat.upper.y) += d.y;
  return fat;
}

struct ProxyDef {
  AABB aabb;
  ProxyFilter filter;
  bool isStatic = false;
  std::uint64_t userData = 0;
};

// One proxy's storage, shared by both implementations: what the query loops read (the fat
// AABB, the next link, the filter and the flags) in 32 bytes, two proxies to a cache line and
// half the memory a query walks through; the rest beside it in ProxyLinks.
struct alignas(32) ProxyData {
  AABB fat;
  ProxyId next = kNullProxy;  // next proxy in the same cell (Quadtree)
  ProxyFilter filter;
  bool isStatic = false;
  bool alive = false;
  bool moved = false;  // created or re-inserted since the last updatePairs
};
static_assert(sizeof(ProxyData) == 32);

// Quadtree placement: level, cell and the link back in the cell's list (-1: none); level -1
// means the outside list. And the caller's data.
struct ProxyLinks {
  ProxyId prev = kNullProxy;
  std::int32_t level = 0;
  std::int32_t cell = 0;
  std::uint64_t userData = 0;
};

// A hit of a closest-hit or all-hits cast: the proxy and what the exact test reported.
struct ProxyHit {
  ProxyId id = kNullProxy;
  CastOutput out;
};

// The segment origin + t * translation, t in [0, maxFraction], against AABBs grown by a radius.
class SegmentProbe {
 public:
  SegmentProbe(const RayCastInput& in, float radius);
  // The fraction where the segment enters `box` grown by the radius, or a value above
  // maxFraction when it misses it before maxFraction.
  float entry(const AABB& box, float maxFraction) const {
    float t0, t1;
    return clip(box, maxFraction, t0, t1) ? t0 : maxFraction + 1.0f;
  }
  // The interval [t0, t1] of [0, maxFraction] inside `box` grown by the radius; false if none.
  bool clip(const AABB& box, float maxFraction, float& t0, float& t1) const;

 private:
  Vec2 origin_, inverse_;  // inverse: 1 / translation per axis, +inf where it is 0
  float radius_;
};

// Proxy storage, ids, fat AABBs and the move buffer: what Quadtree and BruteForce share.
class ProxyStore {
 public:
  const AABB& fatAABB(ProxyId id) const { return proxies_[checked(id)].fat; }
  // Whether the proxy's fat AABB stays as it is for a move to `aabb` (moveProxy's displacement):
  // it holds the tight box swept by the displacement, so that a fast mover's pairs exist before
  // it moves, and is not far larger than a new one, which a fast mover that slowed down would
  // leave (it would pair with everything around it). A NaN anywhere fails a comparison. Inline
  // for callers that move every awake shape every step (a resting pile's refit, where through
  // two calls it was a third of the refit).
  bool fits(ProxyId id, const AABB& aabb, Vec2 displacement) const {
    const ProxyData& p = proxies_[checked(id)];
    AABB swept = aabb;
    (displacement.x < 0.0f ? swept.lower.x : swept.upper.x) += displacement.x;
    (displacement.y < 0.0f ? swept.lower.y : swept.upper.y) += displacement.y;
    if (!(p.fat.contains(swept) && aabb.lower.x <= aabb.upper.x && aabb.lower.y <= aabb.upper.y))
      return false;
    const AABB fat = fatten(aabb, displacement);
    const Vec2 grown = (p.fat.upper - p.fat.lower) - (fat.upper - fat.lower);
    return std::max(grown.x, grown.y) <= 4.0f * kAabbMargin;
  }
  // Without the check, for a proxy the caller's own records keep alive (a contact's shapes'):
  // the narrowphase looks up two a contact, every step.
  const AABB& liveFatAABB(ProxyId id) const { return proxies_[static_cast<std::size_t>(id)].fat; }
  std::uint64_t userData(ProxyId id) const { return links_[checked(id)].userData; }
  ProxyFilter filter(ProxyId id) const { return proxies_[checked(id)].filter; }
  bool isStatic(ProxyId id) const { return proxies_[checked(id)].isStatic; }
  int proxyCount() const { return count_; }
  // A new filter: the proxy takes part in the next pair update as if it had moved, so pairs the
  // old filter refused are found (the caller ends those the new one refuses).
  void setFilter(ProxyId id, ProxyFilter filter);

 protected:
  explicit ProxyStore(const char* name) : name_(name) {}
  std::size_t checked(ProxyId id) const {
    if (id < 0 || static_cast<std::size_t>(id) >= proxies_.size() ||
        !proxies_[static_cast<std::size_t>(id)].alive)
      noSuchProxy(id);
    return static_cast<std::size_t>(id);
  }
  [[noreturn]] void noSuchProxy(ProxyId id) const;
  ProxyId allocate(const ProxyDef& def);
  void release(ProxyId id);
  // Sets a new fat AABB when `aabb` left the old one (or the old one is far too large);
  // returns whether it did.
  bool refit(ProxyId id, const AABB& aabb, Vec2 displacement);
  // updatePairs' shared part: `candidates(id, visit)` calls visit(other) for the proxies whose
  // fat AABB overlaps id's, from whichever structure the caller has.
  template <class Candidates>
  void pairsOfMoved(std::vector<ProxyPair>& pairs, Candidates&& candidates);
  // Brute-force query loops over the dense array.
  template <class Visit>
  bool bruteAABB(const AABB& box, ProxyFilter filter, Visit& visit) const;
  template <class Callback>
  void bruteCast(const RayCastInput& in, float radius, ProxyFilter filter, Callback& cb) const;
  void bruteFindPairs(std::vector<ProxyPair>& pairs) const;

  const char* name_;
  std::vector<ProxyData> proxies_;
  std::vector<ProxyLinks> links_;
  std::vector<ProxyId> free_;
  std::vector<ProxyId> moveBuffer_;
  int count_ = 0;
};

class Quadtree : public ProxyStore {
 public:
  // Depth chosen from the world's size: the finest cells are at least kFinestCell across.
  static constexpr int kAutoDepth = -1;
  static constexpr float kFinestCell = 1.0f;
  static constexpr int kMaxDepth = 10;  // 2^20 cells on the finest level at most
  // Below this many proxies pair updates and queries loop over the proxies instead of the
  // cells. Measured (tests/bench/broadphase_bench, "crossover" rows, medians of 5): the tree's
  // pair update and AABB queries win from 40 to 48 proxies, its 50 m ray casts from 56 to 64.
  static constexpr int kBruteForceBelow = 48;

  // worldBounds: the region most proxies live in (the level's bounds); it is made square.
  // maxDepth: deepest level (0 is the root), clamped to [0, kMaxDepth].
  explicit Quadtree(const AABB& worldBounds, int maxDepth = kAutoDepth);

  ProxyId createProxy(const ProxyDef& def);
  void destroyProxy(ProxyId id);
  // New tight AABB for a proxy, and optionally how far it will move in the next step (for a
  // steady mover, how far it moved in this one). Returns true when the AABB swept by that
  // displacement left the fat AABB and the proxy was re-inserted (it then takes part in the
  // next updatePairs).
  bool moveProxy(ProxyId id, const AABB& aabb, Vec2 displacement = {});
  // ProxyStore::setFilter, and the proxy's level learns the new filter.
  void setFilter(ProxyId id, ProxyFilter filter);

  // Every pair of overlapping fat AABBs with at least one moving proxy that passes the
  // filters, each once, sorted. `pairs` is cleared first.
  void findPairs(std::vector<ProxyPair>& pairs) const;
  // The pairs of findPairs that involve a proxy created or re-inserted since the last call:
  // with the pairs kept from before that still overlap, exactly findPairs. Clears the buffer.
  void updatePairs(std::vector<ProxyPair>& pairs);

  // Calls visit(id) for every proxy whose fat AABB overlaps `box` and passes the filter
  // (category against the proxies' masks and the reverse); visit returns false to stop.
  template <class Visit>
  void queryAABB(const AABB& box, ProxyFilter filter, Visit&& visit) const;
  std::vector<ProxyId> queryAABB(const AABB& box, ProxyFilter filter = {}) const;
  std::vector<ProxyId> queryPoint(Vec2 p, ProxyFilter filter = {}) const;

  // Ray (radius 0) or swept-circle cast along origin + t * translation, t in [0, maxFraction].
  // Calls cb(id, current) for every proxy whose fat AABB, grown by the radius, the cast enters
  // before current.maxFraction, nearest cells first; cb returns the new max fraction (the hit's
  // fraction clips the cast there, current.maxFraction or more goes on, 0 or less stops).
  template <class Callback>
  void cast(const RayCastInput& in, float radius, ProxyFilter filter, Callback&& cb) const;

  // Checks every invariant (links, placement, counts, move buffer); throws std::logic_error
  // naming the first broken one.
  void validate() const;

  // The proxies, their cells and the move buffer as bytes, and back into a tree made with the
  // same bounds and depth (World::snapshot): the restored tree reports the same pairs in the
  // same order. load() checks every id and invariant and throws std::invalid_argument for
  // bytes that are not such a tree, leaving this one empty.
  void save(ByteWriter& out) const;
  void load(ByteReader& in);

  int maxDepth() const { return maxDepth_; }

  // The cells that hold at least one proxy (their own bounds, not the loose ones), with their
  // level and whether they belong to the static tree: for a debug overlay. Scans every cell of
  // every populated level, so it is for drawing, not for per-step use.
  struct OccupiedCell {
    AABB bounds;
    int level;
    bool isStatic;
  };
  std::vector<OccupiedCell> occupiedCells() const;
  // Overrides kBruteForceBelow (0: always the tree). For measuring the crossover.
  void setBruteForceBelow(int count) { bruteBelow_ = count; }

 private:
  struct Level {
    float cellSize = 0.0f;
    float invCellSize = 0.0f;
    int side = 0;                // cells per row
    std::vector<ProxyId> heads;  // first proxy of each cell
    int population = 0;          // proxies on this level
    // The largest half-extent of a proxy placed here since the level was last empty: no proxy
    // sticks out of its cell by more. At most half a cell (the loose bound), often much less
    // (movers a little too large for the level below), and queries grow cells by this instead
    // of half a cell.
    float reach = 0.0f;
    // The reach plus a hair: placement rounds the proxy's centre, and a proxy an ulp outside
    // its cell's grown bounds must still be found.
    float queryMargin() const { return reach + 1e-4f * cellSize; }
    // Every category and every mask of a proxy placed here since the level was last empty:
    // a query whose filter no proxy here can pass skips the level (as Box2D v3's tree nodes keep
    // their subtree's category bits). Not saved: a restored tree recomputes them.
    std::uint32_t categories = 0, masks = 0;
    bool mayPass(ProxyFilter filter) const {
      return (categories & filter.mask) != 0 && (filter.category & masks) != 0;
    }
  };
  struct Tree {
    std::vector<Level> levels;
    ProxyId outside = kNullProxy;  // list of proxies kept outside the cells
    int outsideCount = 0;
    // Bit l set while level l holds a proxy: queries visit those levels only (a world's tree
    // has 11 levels, most of them empty, and a short cast spent an eighth of its time
    // skipping them).
    std::uint32_t populated = 0;
    static_assert(kMaxDepth < 32);
  };
  struct CastFrame;
  class CellWalk;

  void place(ProxyId id);
  void unlink(ProxyId id);
  void clearAll();
  void validateLists(bool fromHeads) const;
  void link(ProxyId id, Tree& tree, int level, int cell);
  // One more proxy on a level: its population, the tree's populated bit, the filter unions
  // (link, and load, which reads the reach instead of growing it).
  static Level& countOn(Tree& tree, int level, ProxyFilter filter);
  ProxyId& headOf(Tree& tree, int level, int cell);
  Tree& treeOf(const ProxyData& p) { return p.isStatic ? static_ : moving_; }
  const Tree& treeOf(const ProxyData& p) const { return p.isStatic ? static_ : moving_; }
  template <class Visit>
  bool queryTree(const Tree& tree, const AABB& box, ProxyFilter filter, Visit& visit) const;
  bool small() const { return count_ < bruteBelow_; }

  Vec2 origin_{};
  float size_ = 0.0f;
  int maxDepth_ = 0;
  int bruteBelow_ = kBruteForceBelow;
  Tree static_, moving_;
};

// The reference: the same interface, every proxy against every proxy.
class BruteForce : public ProxyStore {
 public:
  BruteForce() : ProxyStore("BruteForce") {}
  ProxyId createProxy(const ProxyDef& def);
  void destroyProxy(ProxyId id);
  bool moveProxy(ProxyId id, const AABB& aabb, Vec2 displacement = {});
  void findPairs(std::vector<ProxyPair>& pairs) const { bruteFindPairs(pairs); }
  void updatePairs(std::vector<ProxyPair>& pairs);
  template <class Visit>
  void queryAABB(const AABB& box, ProxyFilter filter, Visit&& visit) const {
    bruteAABB(box, filter, visit);
  }
  std::vector<ProxyId> queryAABB(const AABB& box, ProxyFilter filter = {}) const;
  std::vector<ProxyId> queryPoint(Vec2 p, ProxyFilter filter = {}) const;
  template <class Callback>
  void cast(const RayCastInput& in, float radius, ProxyFilter filter, Callback&& cb) const {
    bruteCast(in, radius, filter, cb);
  }
};

// How the casts below order hits of equal fraction: by the proxy's id, or by a key of the
// caller's (the world ranks by shape id, which a proxy's id does not follow once proxies are
// removed and made again).
struct RankById {
  std::uint64_t operator()(ProxyId id) const { return static_cast<std::uint64_t>(id); }
};

// The nearest hit of a ray (radius 0) or swept circle through either broadphase.
// exact(id, input) is the exact test of that proxy's shape against the whole cast, returning a
// CastOutput. Ties in fraction go to the lower rank(id), so the answer does not
// depend on the traversal order. out.hit is false when nothing was hit.
template <class Broadphase, class Exact, class Rank = RankById>
ProxyHit castClosest(const Broadphase& bp, const RayCastInput& in, float radius, ProxyFilter filter,
                     Exact&& exact, Rank rank = {});
// Every hit along the cast, sorted by fraction, then by rank(id).
template <class Broadphase, class Exact, class Rank = RankById>
std::vector<ProxyHit> castAll(const Broadphase& bp, const RayCastInput& in, float radius,
                              ProxyFilter filter, Exact&& exact, Rank rank = {});

// ---------------------------------------------------------------------------------------------

inline SegmentProbe::SegmentProbe(const RayCastInput& in, float radius)
    : origin_(in.origin), radius_(radius) {
  constexpr float inf = std::numeric_limits<float>::infinity();
  inverse_ = {in.translation.x != 0.0f ? 1.0f / in.translation.x : inf,
              in.translation.y != 0.0f ? 1.0f / in.translation.y : inf};
}

inline bool SegmentProbe::clip(const AABB& box, float maxFraction, float& t0, float& t1) const {
  // Slabs: on each axis the interval of t where the segment is between the box's planes, the
  // near plane chosen by the direction's sign (no compare-and-swap per box). Along an axis the
  // segment does not move, the inverse is infinite: a plane on either side gives -inf or +inf,
  // a plane through the origin 0 * inf = NaN, which std::max / std::min ignore in their second
  // argument, so the segment is in exactly when it lies between the planes, edges included.
  const float lx = box.lower.x - radius_, hx = box.upper.x + radius_;
  const float ly = box.lower.y - radius_, hy = box.upper.y + radius_;
  const bool fx = inverse_.x < 0.0f, fy = inverse_.y < 0.0f;
  t0 = std::max(std::max(0.0f, ((fx ? hx : lx) - origin_.x) * inverse_.x),
                ((fy ? hy : ly) - origin_.y) * inverse_.y);
  t1 = std::min(std::min(maxFraction, ((fx ? lx : hx) - origin_.x) * inverse_.x),
                ((fy ? ly : hy) - origin_.y) * inverse_.y);
  return t0 <= t1;
}

template <class Candidates>
void ProxyStore::pairsOfMoved(std::vector<ProxyPair>& pairs, Candidates&& candidates) {
  pairs.clear();
  for (ProxyId self : moveBuffer_) {
    const ProxyData& m = proxies_[static_cast<std::size_t>(self)];
    if (!m.alive || !m.moved) continue;
    candidates(self, [&](ProxyId other) {
      const ProxyData& o = proxies_[static_cast<std::size_t>(other)];
      // A pair of two buffered proxies is reported from the lower id only.
      if (other == self || (o.moved && other < self) || (m.isStatic && o.isStatic)) return true;
      if (shouldCollide(m.filter, o.filter))
        pairs.push_back(self < other ? ProxyPair{self, other} : ProxyPair{other, self});
      return true;
    });
  }
  for (ProxyId id : moveBuffer_)
    proxies_[static_cast<std::size_t>(id)].moved = false;
  moveBuffer_.clear();
  // A proxy destroyed and re-created under the same id appears twice in the buffer.
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

template <class Visit>
bool ProxyStore::bruteAABB(const AABB& box, ProxyFilter filter, Visit& visit) const {
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    const ProxyData& p = proxies_[i];
    if (p.alive && overlaps(p.fat, box) && shouldCollide(filter, p.filter) &&
        !visit(static_cast<ProxyId>(i)))
      return false;
  }
  return true;
}

template <class Callback>
void ProxyStore::bruteCast(const RayCastInput& in, float radius, ProxyFilter filter,
                           Callback& cb) const {
  const SegmentProbe probe(in, radius);
  RayCastInput current = in;
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    const ProxyData& p = proxies_[i];
    if (!p.alive || !shouldCollide(filter, p.filter) ||
        probe.entry(p.fat, current.maxFraction) > current.maxFraction)
      continue;
    const float f = cb(static_cast<ProxyId>(i), current);
    if (!(f > 0.0f)) return;
    current.maxFraction = std::min(current.maxFraction, f);
  }
}

template <class Visit>
bool Quadtree::queryTree(const Tree& tree, const AABB& box, ProxyFilter filter,
                         Visit& visit) const {
  for (ProxyId id = tree.outside; id != kNullProxy; id = proxies_[id].next)
    if (overlaps(proxies_[id].fat, box) && !visit(id)) return false;
  for (std::uint32_t bits = tree.populated; bits != 0; bits &= bits - 1) {
    const Level& level = tree.levels[static_cast<std::size_t>(std::countr_zero(bits))];
    // A level no proxy of which can pass the filter has nothing for the visit.
    if (!level.mayPass(filter)) continue;
    // Cells whose bounds grown by the level's reach overlap the box. Truncation is the floor
    // from 0 up (std::floor, without SSE4.1, is a chain of conversions); below the grid is its
    // first cell, at or beyond it the last.
    const float inv = level.invCellSize;
    const float half = level.queryMargin();
    auto index = [&](float v) {
      const float f = v * inv;
      return !(f >= 0.0f)                          ? 0
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
  if (small()) {
    bruteAABB(box, filter, visit);
    return;
  }
  auto filtered = [&](ProxyId id) {
    return !shouldCollide(filter, proxies_[id].filter) || visit(id);
  };
  if (queryTree(moving_, box, filter, filtered)) queryTree(static_, box, filter, filtered);
}

// What the walks of one cast share: the cast in the tree's frame (origin at the world square's
// lower corner) along its major axis (the one it moves furthest along) and its minor axis, each
// mirrored when the cast runs towards lower cells (coordinate x becomes size - x, cell i of a
// level becomes side - 1 - i), so that it runs towards higher ones on both.
struct Quadtree::CastFrame {
  CastFrame(const Quadtree& qt, const RayCastInput& in, float castRadius)
      : size(qt.size_), maxFraction(in.maxFraction), radius(castRadius) {
    const Vec2 p = in.origin - qt.origin_;
    yMajor = std::fabs(in.translation.y) > std::fabs(in.translation.x);
    const float po[2] = {yMajor ? p.y : p.x, yMajor ? p.x : p.y};
    const float pd[2] = {yMajor ? in.translation.y : in.translation.x,
                         yMajor ? in.translation.x : in.translation.y};
    for (int k = 0; k < 2; ++k) {
      flip[k] = pd[k] < 0.0f;
      o[k] = flip[k] ? size - po[k] : po[k];
      d[k] = std::fabs(pd[k]);
      inv[k] = d[k] > 0.0f ? 1.0f / d[k] : 0.0f;
    }
  }
  float size, maxFraction, radius;
  bool yMajor;
  bool flip[2];              // [0] the major axis, [1] the minor
  float o[2], d[2], inv[2];  // mirrored origin, rate (>= 0) and 1 / rate (0: no motion)
};

// The cells of one level that a cast can reach, a column at a time. A proxy in cell X (in cell
// units along one axis) lies within [X - reach, X + 1 + reach] (reach <= 1/2, see Level); grown
// by the cast's radius that is [X - h, X + 1 + h] with h = (reach + radius) / cellSize. The
// cast's point a(t) can touch it only while X is in the window [a - 1 - h, a + h]. Columns run
// across the major axis: column X is in the window for t in [in(X), out(X)], and meanwhile the
// minor coordinate sweeps a range of rows, visited together. Nothing in the column can be hit
// before in(X): that is the column's lower bound, and walks are advanced in its order.
// Visiting by column rather than cell by cell in order of entry halves the steps of a cast and
// takes the data-dependent choices (which axis enters next) out of them.
class Quadtree::CellWalk {
 public:
  static constexpr float kNever = std::numeric_limits<float>::infinity();

  // Returns false when the cast misses the level's cells within [0, maxFraction].
  bool start(const CastFrame& f, const Level& lv) {
    side_ = lv.side;
    const float cells = static_cast<float>(side_), inv = lv.invCellSize;
    // A thousandth of a cell of slack: rounding in the cell coordinates must never drop a cell.
    h_ = (lv.queryMargin() + f.radius) * inv + 1e-3f;
    // The part of the cast that can touch any cell: both coordinates in [-h, size + h].
    const float halo = h_ * lv.cellSize;
    float t0 = 0.0f, end = f.maxFraction;
    for (int k = 0; k < 2; ++k) {
      if (f.d[k] > 0.0f) {
        t0 = std::max(t0, (-halo - f.o[k]) * f.inv[k]);
        end = std::min(end, (f.size + halo - f.o[k]) * f.inv[k]);
      } else if (f.o[k] < -halo || f.o[k] > f.size + halo) {
        return false;
      }
    }
    if (!(t0 <= end)) return false;
    t0_ = t0;
    end_ = end;
    om_ = f.o[0] * inv;
    on_ = f.o[1] * inv;
    dn_ = f.d[1] * inv;
    inv_ = f.inv[0] * lv.cellSize;
    // Heads index of (column, row) = base + column * colStride + row * rowStride, mirrored.
    const std::ptrdiff_t col = f.yMajor ? side_ : 1, row = f.yMajor ? 1 : side_, last = side_ - 1;
    base_ = lv.heads.data() + (f.flip[0] ? col * last : 0) + (f.flip[1] ? row * last : 0);
    colStride_ = f.flip[0] ? -col : col;
    rowStride_ = f.flip[1] ? -row : row;
    const float dm = f.d[0] * inv;
    col_ = std::max(-floorNear(std::min(1.0f + h_ - om_ - t0 * dm, 1.0f)), 0);
    last_ = std::min(floorNear(std::min(om_ + end * dm + h_, cells)), side_ - 1);
    if (col_ > last_) return false;
    next_ = lowerBound();
    return true;
  }

  // Visits the columns in order until one's lower bound passes maxFraction, which the visits
  // may lower (a lone walk: step() in a loop, without choosing between walks).
  template <class VisitList>
  void run(VisitList& visitList, const float& maxFraction) {
    while (next_ <= maxFraction) {
      if (!visitColumn(visitList, maxFraction)) return;
      if (++col_ > last_) return;
      next_ = lowerBound();
    }
  }

  // The lower bound of the next column this walk will visit (kNever when done).
  float next() const { return next_; }

  // Visits the next column's cells that the cast can reach before maxFraction (the columns
  // already in the window where the walk starts share its lower bound: all of them at once).
  // visitList(head) returns false to stop the whole cast.
  template <class VisitList>
  bool step(VisitList& visitList, float maxFraction) {
    do {
      if (!visitColumn(visitList, maxFraction)) return false;
      next_ = ++col_ > last_ ? kNever : lowerBound();
    } while (next_ <= t0_);
    return true;
  }

 private:
  // floor(x), or one more within 2.5e-4 of the next integer, for x in [-2048, 2048]: here a
  // cell more at either end of a range, never one less. Without SSE4.1 std::floor is a chain of
  // conversions four times as long, and a third of a short cast was spent in it.
  static int floorNear(float x) { return static_cast<int>(x + 4096.0f) - 4096; }

  float lowerBound() const {
    return inv_ > 0.0f ? std::max(t0_, (static_cast<float>(col_) - h_ - om_) * inv_) : t0_;
  }

  // The rows of column col_ whose window the cast passes through between the column's lower
  // bound and the sooner of its leaving the column's window and maxFraction. Inputs to
  // floorNear are clamped a cell beyond the grid, keeping them in its range.
  template <class VisitList>
  bool visitColumn(VisitList& visitList, float maxFraction) const {
    const float out = inv_ > 0.0f ? (static_cast<float>(col_) + 1.0f + h_ - om_) * inv_ : kNever;
    // out last: a denormal rate's infinite inverse can make it 0 * inf = NaN, which std::min
    // ignores in its second argument only.
    const float tB = std::min(std::min(end_, maxFraction), out);
    const int r0 = std::max(-floorNear(std::min(1.0f + h_ - on_ - next_ * dn_, 1.0f)), 0);
    const int r1 =
        std::min(floorNear(std::min(on_ + tB * dn_ + h_, static_cast<float>(side_))), side_ - 1);
    const ProxyId* cell = base_ + col_ * colStride_ + r0 * rowStride_;
    for (int r = r0; r <= r1; ++r, cell += rowStride_)
      if (!visitList(*cell)) return false;
    return true;
  }

  // No initializers: a cast keeps a walk for every level on its stack, and start() sets all of
  // it (initialized, the array of 22 walks was a twelfth of a ray cast).
  const ProxyId* base_;
  std::ptrdiff_t colStride_, rowStride_;
  int side_, col_, last_;
  float h_, t0_, end_, next_;
  float om_, on_, dn_, inv_;  // in cells: major and minor origin, minor rate; 1 / major rate
};

template <class Callback>
void Quadtree::cast(const RayCastInput& in, float radius, ProxyFilter filter, Callback&& cb) const {
  if (!isFinite(in.origin) || !isFinite(in.translation) || !std::isfinite(in.maxFraction) ||
      !std::isfinite(radius) || radius < 0.0f)
    throw InvalidProxy("Quadtree::cast: NaN, infinite or negative input");
  if (small()) {
    bruteCast(in, radius, filter, cb);
    return;
  }
  const SegmentProbe probe(in, radius);
  RayCastInput current = in;
  bool stopped = false;
  auto visitList = [&](ProxyId head) {
    for (ProxyId id = head; id != kNullProxy; id = proxies_[static_cast<std::size_t>(id)].next) {
      const ProxyData& p = proxies_[static_cast<std::size_t>(id)];
      if (!shouldCollide(filter, p.filter) ||
          probe.entry(p.fat, current.maxFraction) > current.maxFraction)
        continue;
      const float f = cb(id, current);
      if (!(f > 0.0f)) return !(stopped = true);
      current.maxFraction = std::min(current.maxFraction, f);
    }
    return true;
  };
  // The outside lists first: anything in them may be hit at fraction 0.
  if (!visitList(moving_.outside) || !visitList(static_.outside)) return;
  // One walk per populated level of either tree, always advancing the one whose next cells
  // come first: the cast meets cells in order of their lower bound whatever their level.
  const CastFrame frame(*this, in, radius);
  std::array<CellWalk, 2 * (kMaxDepth + 1)> walks;
  int n = 0;
  for (const Tree* tree : {&moving_, &static_})
    for (std::uint32_t bits = tree->populated; bits != 0; bits &= bits - 1) {
      const Level& level = tree->levels[static_cast<std::size_t>(std::countr_zero(bits))];
      if (level.mayPass(filter) && walks[static_cast<std::size_t>(n)].start(frame, level)) ++n;
    }
  // A walk that has visited its last column leaves the array (the others keep their order, which
  // breaks ties); the last one left runs its columns without choosing between walks: a cast
  // among like-sized shapes walks one level, and the coarse level of a few long walls is done
  // after its first column or two.
  while (n > 1) {
    int best = -1;
    float bestT = CellWalk::kNever;
    for (int i = 0; i < n; ++i)
      if (walks[static_cast<std::size_t>(i)].next() < bestT) {
        bestT = walks[static_cast<std::size_t>(i)].next();
        best = i;
      }
    if (best < 0 || bestT > current.maxFraction) return;
    if (!walks[static_cast<std::size_t>(best)].step(visitList, current.maxFraction)) return;
    if (walks[static_cast<std::size_t>(best)].next() == CellWalk::kNever) {
      std::copy(walks.begin() + best + 1, walks.begin() + n, walks.begin() + best);
      --n;
    }
  }
  if (n == 1) walks[0].run(visitList, current.maxFraction);
}

template <class Broadphase, class Exact, class Rank>
ProxyHit castClosest(const Broadphase& bp, const RayCastInput& in, float radius, ProxyFilter filter,
                     Exact&& exact, Rank rank) {
  ProxyHit best;
  bp.cast(in, radius, filter, [&](ProxyId id, const RayCastInput& current) {
    // The exact test sees the whole cast, not the clipped one: its result then cannot depend on
    // the order proxies come in, and a tie with the best so far is not lost to its rounding.
    const CastOutput out = exact(id, in);
    if (!out.hit || out.fraction > current.maxFraction) return current.maxFraction;
    if (!best.out.hit || out.fraction < best.out.fraction ||
        (out.fraction == best.out.fraction && rank(id) < rank(best.id)))
      best = {id, out};
    // Clip at the hit; a hit at fraction 0 cannot be beaten but may tie with a lower id.
    return std::max(out.fraction, std::numeric_limits<float>::min());
  });
  return best;
}

template <class Broadphase, class Exact, class Rank>
std::vector<ProxyHit> castAll(const Broadphase& bp, const RayCastInput& in, float radius,
                              ProxyFilter filter, Exact&& exact, Rank rank) {
  std::vector<ProxyHit> hits;
  bp.cast(in, radius, filter, [&](ProxyId id, const RayCastInput& current) {
    const CastOutput out = exact(id, in);
    if (out.hit) hits.push_back({id, out});
    return current.maxFraction;
  });
  std::sort(hits.begin(), hits.end(), [&rank](const ProxyHit& a, const ProxyHit& b) {
    return a.out.fraction != b.out.fraction ? a.out.fraction < b.out.fraction
                                            : rank(a.id) < rank(b.id);
  });
  return hits;
}

}  // namespace rc
