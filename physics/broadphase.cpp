#include "physics/broadphase.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>

namespace rc {
namespace {

void checkAABB(const AABB& box, const char* where) {
  if (!box.isValid())
    throw InvalidProxy(std::string(where) + ": AABB is not finite or has lower > upper");
}

}  // namespace

Vec2 cappedStretch(Vec2 displacement) {
  const float len = length(displacement);
  if (!(len > 0.0f)) return displacement;  // zero stays zero; NaN is caught by the caller
  return std::min(kDisplacementMultiplier, 1.0f + kMaxPrediction / len) * displacement;
}

// ---------------------------------------------------------------------------------- ProxyStore

void ProxyStore::noSuchProxy(ProxyId id) const {
  throw InvalidProxy(std::string(name_) + ": no proxy " + std::to_string(id));
}

ProxyId ProxyStore::allocate(const ProxyDef& def) {
  checkAABB(def.aabb, name_);
  ProxyId id;
  if (!free_.empty()) {
    // Last freed, first reused: ids depend only on the sequence of calls.
    id = free_.back();
    free_.pop_back();
  } else {
    id = static_cast<ProxyId>(proxies_.size());
    proxies_.emplace_back();
    links_.emplace_back();
  }
  ProxyData& p = proxies_[static_cast<std::size_t>(id)];
  p = ProxyData{};
  links_[static_cast<std::size_t>(id)] = ProxyLinks{};
  links_[static_cast<std::size_t>(id)].userData = def.userData;
  p.fat = inflate(def.aabb, kAabbMargin);
  p.filter = def.filter;
  p.isStatic = def.isStatic;
  p.alive = true;
  // A new proxy, static ones included, must find its pairs in the next updatePairs.
  p.moved = true;
  moveBuffer_.push_back(id);
  ++count_;
  return id;
}

void ProxyStore::setFilter(ProxyId id, ProxyFilter filter) {
  ProxyData& p = proxies_[checked(id)];
  p.filter = filter;
  if (!p.moved) {
    p.moved = true;
    moveBuffer_.push_back(id);
  }
}

void ProxyStore::release(ProxyId id) {
  ProxyData& p = proxies_[checked(id)];
  p.alive = false;
  p.moved = false;  // its stale buffer entry is skipped
  free_.push_back(id);
  --count_;
}

bool ProxyStore::refit(ProxyId id, const AABB& aabb, Vec2 displacement) {
  if (fits(id, aabb, displacement)) return false;  // the common case
  ProxyData& p = proxies_[checked(id)];
  checkAABB(aabb, name_);
  if (!isFinite(displacement))
    throw InvalidProxy(std::string(name_) + ": displacement is not finite");
  p.fat = fatten(aabb, displacement);
  if (!p.moved) {
    p.moved = true;
    moveBuffer_.push_back(id);
  }
  return true;
}

void ProxyStore::bruteFindPairs(std::vector<ProxyPair>& pairs) const {
  pairs.clear();
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    const ProxyData& a = proxies_[i];
    if (!a.alive) continue;
    for (std::size_t j = i + 1; j < proxies_.size(); ++j) {
      const ProxyData& b = proxies_[j];
      if (!b.alive || (a.isStatic && b.isStatic)) continue;
      if (shouldCollide(a.filter, b.filter) && overlaps(a.fat, b.fat))
        pairs.push_back({static_cast<ProxyId>(i), static_cast<ProxyId>(j)});
    }
  }
}

// ------------------------------------------------------------------------------------ Quadtree

Quadtree::Quadtree(const AABB& worldBounds, int maxDepth) : ProxyStore("Quadtree") {
  checkAABB(worldBounds, "Quadtree world bounds");
  Vec2 e = worldBounds.extents();
  size_ = 2.0f * std::max(e.x, e.y);
  if (!(size_ > 0.0f)) throw InvalidProxy("Quadtree world bounds: zero size");
  if (maxDepth == kAutoDepth) {
    // The finest cells at least kFinestCell across: a character-sized mover sits on the finest
    // level, and a huge world does not allocate millions of cells nothing fits.
    maxDepth = 0;
    while (maxDepth < kMaxDepth && size_ / static_cast<float>(2 << maxDepth) >= kFinestCell)
      ++maxDepth;
  }
  maxDepth_ = std::clamp(maxDepth, 0, kMaxDepth);
  Vec2 c = worldBounds.center();
  origin_ = {c.x - 0.5f * size_, c.y - 0.5f * size_};
  for (Tree* tree : {&static_, &moving_}) {
    tree->levels.resize(static_cast<std::size_t>(maxDepth_ + 1));
    for (int l = 0; l <= maxDepth_; ++l) {
      Level& level = tree->levels[static_cast<std::size_t>(l)];
      level.side = 1 << l;
      level.cellSize = size_ / static_cast<float>(level.side);
      level.invCellSize = static_cast<float>(level.side) / size_;
      // Cells are allocated when the level first holds a proxy (link, load): a default world's
      // finest levels are a million cells (11 MB to zero) that a small scene never touches, and
      // a batch of short replays would pay for them every time.
    }
  }
}

ProxyId& Quadtree::headOf(Tree& tree, int level, int cell) {
  if (level < 0) return tree.outside;
  return tree.levels[static_cast<std::size_t>(level)].heads[static_cast<std::size_t>(cell)];
}

void Quadtree::link(ProxyId id, Tree& tree, int level, int cell) {
  ProxyData& p = proxies_[static_cast<std::size_t>(id)];
  ProxyLinks& k = links_[static_cast<std::size_t>(id)];
  if (level >= 0) {
    Level& lv = tree.levels[static_cast<std::size_t>(level)];
    if (lv.heads.empty()) lv.heads.assign(static_cast<std::size_t>(lv.side) * lv.side, kNullProxy);
  }
  ProxyId& head = headOf(tree, level, cell);
  k.level = level;
  k.cell = cell;
  k.prev = kNullProxy;
  p.next = head;
  if (head != kNullProxy) links_[static_cast<std::size_t>(head)].prev = id;
  head = id;
  if (level < 0) {
    ++tree.outsideCount;
    return;
  }
  Level& lv = countOn(tree, level, p.filter);
  const Vec2 e = p.fat.extents();
  lv.reach = std::max(lv.reach, std::max(e.x, e.y));
}

Quadtree::Level& Quadtree::countOn(Tree& tree, int level, ProxyFilter filter) {
  Level& lv = tree.levels[static_cast<std::size_t>(level)];
  ++lv.population;
  tree.populated |= 1u << level;
  lv.categories |= filter.category;
  lv.masks |= filter.mask;
  return lv;
}

void Quadtree::unlink(ProxyId id) {
  ProxyData& p = proxies_[static_cast<std::size_t>(id)];
  ProxyLinks& k = links_[static_cast<std::size_t>(id)];
  Tree& tree = treeOf(p);
  if (k.prev != kNullProxy)
    proxies_[static_cast<std::size_t>(k.prev)].next = p.next;
  else
    headOf(tree, k.level, k.cell) = p.next;
  if (p.next != kNullProxy) links_[static_cast<std::size_t>(p.next)].prev = k.prev;
  k.prev = p.next = kNullProxy;
  if (k.level < 0) {
    --tree.outsideCount;
    return;
  }
  Level& lv = tree.levels[static_cast<std::size_t>(k.level)];
  if (--lv.population == 0) {
    tree.populated &= ~(1u << k.level);
    lv.reach = 0.0f;
    lv.categories = lv.masks = 0;
  }
}

void Quadtree::place(ProxyId id) {
  const ProxyData& p = proxies_[static_cast<std::size_t>(id)];
  Tree& tree = treeOf(p);
  const Vec2 c = p.fat.center() - origin_;
  const Vec2 e = p.fat.extents();
  const float span = 2.0f * std::max(e.x, e.y);
  // Outside the world square, or too large for the root's loose bounds: the outside list.
  if (!(c.x >= 0.0f && c.x < size_ && c.y >= 0.0f && c.y < size_) || span > size_) {
    link(id, tree, -1, 0);
    return;
  }
  // Deepest level whose cells are at least as large as the proxy: span <= size / 2^level.
  int level = maxDepth_;
  if (span > 0.0f) {
    // A proxy far smaller than the deepest cell (a denormal span makes the ratio infinite)
    // goes to the deepest level. Otherwise floor(log2(ratio)), exactly: the exponent of the
    // float, a normal one in [1, 2^maxDepth) here (span <= size); std::log2 and std::floor were
    // two library calls per re-insertion.
    const float ratio = size_ / span;
    const int fit =
        ratio >= static_cast<float>(1 << maxDepth_)
            ? maxDepth_
            : static_cast<int>((std::bit_cast<std::uint32_t>(ratio) >> 23) & 0xFFu) - 127;
    level = std::clamp(fit, 0, maxDepth_);
    // Rounding in size / span: step back while the cell is smaller than the proxy.
    while (level > 0 && span > size_ / static_cast<float>(1 << level))
      --level;
  }
  const Level& lv = tree.levels[static_cast<std::size_t>(level)];
  const int x = std::min(static_cast<int>(c.x / lv.cellSize), lv.side - 1);
  const int y = std::min(static_cast<int>(c.y / lv.cellSize), lv.side - 1);
  link(id, tree, level, y * lv.side + x);
}

ProxyId Quadtree::createProxy(const ProxyDef& def) {
  ProxyId id = allocate(def);
  place(id);
  return id;
}

void Quadtree::destroyProxy(ProxyId id) {
  checked(id);
  unlink(id);
  release(id);
}

bool Quadtree::moveProxy(ProxyId id, const AABB& aabb, Vec2 displacement) {
  if (!refit(id, aabb, displacement)) return false;
  unlink(id);  // from the cell it records, whatever its new fat AABB
  place(id);
  return true;
}

void Quadtree::setFilter(ProxyId id, ProxyFilter filter) {
  ProxyStore::setFilter(id, filter);
  const ProxyLinks& k = links_[static_cast<std::size_t>(id)];
  if (k.level < 0) return;
  Level& lv =
      treeOf(proxies_[static_cast<std::size_t>(id)]).levels[static_cast<std::size_t>(k.level)];
  lv.categories |= filter.category;
  lv.masks |= filter.mask;
}

void Quadtree::findPairs(std::vector<ProxyPair>& pairs) const {
  if (small()) {
    bruteFindPairs(pairs);
    return;
  }
  pairs.clear();
  // Every moving proxy queries both trees; a moving-moving pair is kept from its lower id only.
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    const ProxyData& m = proxies_[i];
    if (!m.alive || m.isStatic) continue;
    const ProxyId self = static_cast<ProxyId>(i);
    auto visit = [&](ProxyId other) {
      const ProxyData& o = proxies_[static_cast<std::size_t>(other)];
      if (!o.isStatic && other <= self) return true;
      if (!shouldCollide(m.filter, o.filter)) return true;
      pairs.push_back(self < other ? ProxyPair{self, other} : ProxyPair{other, self});
      return true;
    };
    queryTree(moving_, m.fat, m.filter, visit);
    queryTree(static_, m.fat, m.filter, visit);
  }
  std::sort(pairs.begin(), pairs.end());
}

void Quadtree::updatePairs(std::vector<ProxyPair>& pairs) {
  const bool brute = small();
  pairsOfMoved(pairs, [&](ProxyId self, auto&& visit) {
    const ProxyData& m = proxies_[static_cast<std::size_t>(self)];
    if (brute) {
      bruteAABB(m.fat, ProxyFilter{0xFFFFFFFFu, 0xFFFFFFFFu}, visit);
      return;
    }
    queryTree(moving_, m.fat, m.filter, visit);
    if (!m.isStatic) queryTree(static_, m.fat, m.filter, visit);
  });
}

std::vector<ProxyId> Quadtree::queryAABB(const AABB& box, ProxyFilter filter) const {
  std::vector<ProxyId> out;
  queryAABB(box, filter, [&](ProxyId id) {
    out.push_back(id);
    return true;
  });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<ProxyId> Quadtree::queryPoint(Vec2 p, ProxyFilter filter) const {
  return queryAABB(AABB{p, p}, filter);
}

std::vector<Quadtree::OccupiedCell> Quadtree::occupiedCells() const {
  std::vector<OccupiedCell> out;
  for (const Tree* tree : {&static_, &moving_}) {
    for (int l = 0; l <= maxDepth_; ++l) {
      const Level& lv = tree->levels[static_cast<std::size_t>(l)];
      if (lv.population == 0) continue;
      for (int c = 0; c < lv.side * lv.side; ++c) {
        if (lv.heads[static_cast<std::size_t>(c)] == kNullProxy) continue;
        const Vec2 lo{origin_.x + static_cast<float>(c % lv.side) * lv.cellSize,
                      origin_.y + static_cast<float>(c / lv.side) * lv.cellSize};
        out.push_back({{lo, {lo.x + lv.cellSize, lo.y + lv.cellSize}}, l, tree == &static_});
      }
    }
  }
  return out;
}

void Quadtree::validate() const {
  validateLists(false);
}

// fromHeads: the cell lists are found from the proxies that head them (what load() set, in
// proportion to the proxies), not by scanning every cell of every level (a million and more).
void Quadtree::validateLists(bool fromHeads) const {
  auto fail = [](const std::string& what) {
    throw std::logic_error("Quadtree::validate: " + what);
  };
  int alive = 0;
  for (std::size_t i = 0; i < proxies_.size(); ++i)
    alive += proxies_[i].alive;
  if (alive != count_)
    fail("count " + std::to_string(count_) + " but " + std::to_string(alive) + " alive");
  int seen = 0;
  for (const Tree* tree : {&static_, &moving_}) {
    const bool isStatic = tree == &static_;
    auto walk = [&](ProxyId head, int level, int cell, const Level* lv) {
      int n = 0;
      ProxyId prev = kNullProxy;
      for (ProxyId id = head; id != kNullProxy; id = proxies_[static_cast<std::size_t>(id)].next) {
        if (++n > static_cast<int>(proxies_.size())) fail("cycle in a cell list");
        const ProxyData& p = proxies_[static_cast<std::size_t>(id)];
        const std::string name = "proxy " + std::to_string(id);
        if (!p.alive) fail(name + " is dead but linked");
        if (p.isStatic != isStatic) fail(name + " is in the wrong tree");
        const ProxyLinks& k = links_[static_cast<std::size_t>(id)];
        if (k.prev != prev) fail(name + " has a broken back link");
        if (k.level != level || k.cell != cell) fail(name + " records the wrong cell");
        if (lv != nullptr) {
          // Inside its cell grown by the level's reach (what the queries rely on), which is at
          // most half a cell (the loose bounds).
          int side = lv->side;
          const float grow = lv->queryMargin();
          Vec2 lo{origin_.x + static_cast<float>(cell % side) * lv->cellSize - grow,
                  origin_.y + static_cast<float>(cell / side) * lv->cellSize - grow};
          AABB grown{lo, {lo.x + lv->cellSize + 2.0f * grow, lo.y + lv->cellSize + 2.0f * grow}};
          if (!grown.contains(p.fat)) fail(name + " sticks out of its cell by more than the reach");
          if (lv->reach > 0.5f * lv->cellSize) fail(name + " is too large for its level");
          if ((p.filter.category & ~lv->categories) != 0 || (p.filter.mask & ~lv->masks) != 0)
            fail(name + "'s filter is not in its level's");
        }
        prev = id;
      }
      return n;
    };
    int outside = walk(tree->outside, -1, 0, nullptr);
    if (outside != tree->outsideCount) fail("outside count");
    seen += outside;
    std::vector<int> population(static_cast<std::size_t>(maxDepth_ + 1), 0);
    if (fromHeads) {
      for (std::size_t i = 0; i < proxies_.size(); ++i) {
        const ProxyLinks& k = links_[i];
        if (!proxies_[i].alive || proxies_[i].isStatic != isStatic || k.level < 0 ||
            k.prev != kNullProxy)
          continue;
        const Level& lv = tree->levels[static_cast<std::size_t>(k.level)];
        if (lv.heads[static_cast<std::size_t>(k.cell)] != static_cast<ProxyId>(i))
          fail("proxy " + std::to_string(i) + " heads no cell");
        population[static_cast<std::size_t>(k.level)] +=
            walk(static_cast<ProxyId>(i), k.level, k.cell, &lv);
      }
    } else {
      for (int l = 0; l <= maxDepth_; ++l) {
        const Level& lv = tree->levels[static_cast<std::size_t>(l)];
        if (lv.heads.empty()) continue;  // never held a proxy
        for (int c = 0; c < lv.side * lv.side; ++c)
          population[static_cast<std::size_t>(l)] +=
              walk(lv.heads[static_cast<std::size_t>(c)], l, c, &lv);
      }
    }
    for (int l = 0; l <= maxDepth_; ++l) {
      const int pop = population[static_cast<std::size_t>(l)];
      if (pop != tree->levels[static_cast<std::size_t>(l)].population)
        fail("population of level " + std::to_string(l));
      if (((tree->populated >> l) & 1u) != (pop > 0 ? 1u : 0u))
        fail("populated bit of level " + std::to_string(l));
      seen += pop;
    }
  }
  if (seen != count_) fail("linked " + std::to_string(seen) + " of " + std::to_string(count_));
  // Every proxy flagged as moved is in the move buffer.
  std::vector<char> buffered(proxies_.size(), 0);
  for (ProxyId id : moveBuffer_) {
    if (id < 0 || static_cast<std::size_t>(id) >= proxies_.size())
      fail("move buffer holds a bad id");
    buffered[static_cast<std::size_t>(id)] = 1;
  }
  for (std::size_t i = 0; i < proxies_.size(); ++i)
    if (proxies_[i].moved && (!proxies_[i].alive || !buffered[i]))
      fail("proxy " + std::to_string(i) + " is flagged as moved but not buffered");
}

// ------------------------------------------------------------------------------- snapshots

void Quadtree::save(ByteWriter& out) const {
  out.count(proxies_.size());
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    const ProxyData& p = proxies_[i];
    const ProxyLinks& k = links_[i];
    for (float f : {p.fat.lower.x, p.fat.lower.y, p.fat.upper.x, p.fat.upper.y})
      out.f32(f);
    out.i32(p.next);
    out.u32(p.filter.category);
    out.u32(p.filter.mask);
    out.u8(static_cast<std::uint8_t>(p.isStatic | (p.alive << 1) | (p.moved << 2)));
    out.i32(k.prev);
    out.i32(k.level);
    out.i32(k.cell);
    out.u64(k.userData);
  }
  out.count(free_.size());
  for (ProxyId id : free_)
    out.i32(id);
  out.count(moveBuffer_.size());
  for (ProxyId id : moveBuffer_)
    out.i32(id);
  out.i32(bruteBelow_);
  // Each level's reach (it remembers what was placed there); heads, populations and the
  // outside lists follow from the links.
  for (const Tree* tree : {&static_, &moving_})
    for (const Level& lv : tree->levels)
      out.f32(lv.reach);
}

// Every proxy gone, every cell empty: only the cells that hold something are visited (the
// finest levels have a million).
void Quadtree::clearAll() {
  for (std::size_t i = 0; i < proxies_.size(); ++i) {
    const ProxyLinks& k = links_[i];
    if (!proxies_[i].alive || k.level < 0 || k.level > maxDepth_) continue;
    Level& lv = treeOf(proxies_[i]).levels[static_cast<std::size_t>(k.level)];
    if (k.cell >= 0 && k.cell < lv.side * lv.side && !lv.heads.empty())
      lv.heads[static_cast<std::size_t>(k.cell)] = kNullProxy;
  }
  proxies_.clear();
  links_.clear();
  free_.clear();
  moveBuffer_.clear();
  count_ = 0;
  for (Tree* tree : {&static_, &moving_}) {
    tree->outside = kNullProxy;
    tree->outsideCount = 0;
    tree->populated = 0;
    for (Level& lv : tree->levels) {
      lv.population = 0;
      lv.reach = 0.0f;
      lv.categories = lv.masks = 0;
    }
  }
}

void Quadtree::load(ByteReader& in) {
  clearAll();
  try {
    const std::size_t n = in.count(41);
    proxies_.resize(n);
    links_.resize(n);
    auto id = [&](ProxyId v, bool nullable) {
      if ((nullable && v == kNullProxy) || (v >= 0 && static_cast<std::size_t>(v) < n)) return v;
      in.fail("broadphase: proxy id " + std::to_string(v) + " out of range");
    };
    for (std::size_t i = 0; i < n; ++i) {
      ProxyData& p = proxies_[i];
      ProxyLinks& k = links_[i];
      p.fat.lower.x = in.f32();
      p.fat.lower.y = in.f32();
      p.fat.upper.x = in.f32();
      p.fat.upper.y = in.f32();
      p.next = id(in.i32(), true);
      p.filter.category = in.u32();
      p.filter.mask = in.u32();
      const std::uint8_t flags = in.u8();
      if (flags > 7) in.fail("broadphase: bad proxy flags");
      p.isStatic = (flags & 1) != 0;
      p.alive = (flags & 2) != 0;
      p.moved = (flags & 4) != 0;
      k.prev = id(in.i32(), true);
      k.level = in.i32();
      k.cell = in.i32();
      k.userData = in.u64();
      if (!p.alive) continue;
      if (!p.fat.isValid()) in.fail("broadphase: a fat AABB is not finite");
      ++count_;
      Tree& tree = treeOf(p);
      if (k.level == -1) {
        ++tree.outsideCount;
        if (k.prev == kNullProxy) tree.outside = static_cast<ProxyId>(i);
        continue;
      }
      if (k.level < 0 || k.level > maxDepth_) in.fail("broadphase: level out of range");
      Level& lv = tree.levels[static_cast<std::size_t>(k.level)];
      if (k.cell < 0 || k.cell >= lv.side * lv.side) in.fail("broadphase: cell out of range");
      countOn(tree, k.level, p.filter);
      if (k.prev == kNullProxy) {
        if (lv.heads.empty())
          lv.heads.assign(static_cast<std::size_t>(lv.side) * lv.side, kNullProxy);
        ProxyId& head = lv.heads[static_cast<std::size_t>(k.cell)];
        if (head != kNullProxy) in.fail("broadphase: two heads of one cell");
        head = static_cast<ProxyId>(i);
      }
    }
    const std::size_t freeCount = in.count(4);
    for (std::size_t j = 0; j < freeCount; ++j) {
      const ProxyId f = id(in.i32(), false);
      if (proxies_[static_cast<std::size_t>(f)].alive) in.fail("broadphase: a free id is alive");
      free_.push_back(f);
    }
    if (static_cast<std::size_t>(count_) + free_.size() != n)
      in.fail("broadphase: free ids do not match the dead proxies");
    std::vector<char> seen(n, 0);
    for (ProxyId f : free_)
      if (std::exchange(seen[static_cast<std::size_t>(f)], 1))
        in.fail("broadphase: a free id twice");
    const std::size_t moved = in.count(4);
    for (std::size_t j = 0; j < moved; ++j)
      moveBuffer_.push_back(id(in.i32(), false));
    bruteBelow_ = in.i32();
    for (Tree* tree : {&static_, &moving_})
      for (Level& lv : tree->levels) {
        lv.reach = in.f32();
        if (!(lv.reach >= 0.0f && lv.reach <= 0.5f * lv.cellSize))
          in.fail("broadphase: a level's reach is out of range");
      }
    validateLists(true);
  } catch (const std::logic_error& e) {
    // A reader's complaint (invalid_argument) or validate()'s: the tree is left empty.
    clearAll();
    if (dynamic_cast<const std::invalid_argument*>(&e) != nullptr) throw;
    throw std::invalid_argument(std::string("snapshot: broadphase: ") + e.what());
  }
}

// ---------------------------------------------------------------------------------- BruteForce

ProxyId BruteForce::createProxy(const ProxyDef& def) {
  return allocate(def);
}

void BruteForce::destroyProxy(ProxyId id) {
  release(id);
}

bool BruteForce::moveProxy(ProxyId id, const AABB& aabb, Vec2 displacement) {
  return refit(id, aabb, displacement);
}

void BruteForce::updatePairs(std::vector<ProxyPair>& pairs) {
  pairsOfMoved(pairs, [&](ProxyId self, auto&& visit) {
    bruteAABB(proxies_[static_cast<std::size_t>(self)].fat, ProxyFilter{0xFFFFFFFFu, 0xFFFFFFFFu},
              visit);
  });
}

std::vector<ProxyId> BruteForce::queryAABB(const AABB& box, ProxyFilter filter) const {
  std::vector<ProxyId> out;
  queryAABB(box, filter, [&](ProxyId id) {
    out.push_back(id);
    return true;
  });
  return out;
}

std::vector<ProxyId> BruteForce::queryPoint(Vec2 p, ProxyFilter filter) const {
  return queryAABB(AABB{p, p}, filter);
}

}  // namespace rc
