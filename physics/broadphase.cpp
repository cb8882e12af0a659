#include "physics/broadphase.h"

#include <algorithm>
#include <cmath>

namespace rc {
namespace {

void checkAABB(const AABB& box, const char* where) {
  if (!box.isValid())
    throw InvalidProxy(std::string(where) + ": AABB is not finite or has lower > upper");
}

ProxyId allocate(std::vector<ProxyData>& proxies, std::vector<ProxyId>& freeList,
                 const ProxyDef& def) {
  ProxyId id;
  if (!freeList.empty()) {
    // Last freed, first reused: ids depend only on the sequence of calls.
    id = freeList.back();
    freeList.pop_back();
  } else {
    id = static_cast<ProxyId>(proxies.size());
    proxies.emplace_back();
  }
  ProxyData& p = proxies[static_cast<std::size_t>(id)];
  p = ProxyData{};
  p.fat = inflate(def.aabb, kAabbMargin);
  p.filter = def.filter;
  p.userData = def.userData;
  p.isStatic = def.isStatic;
  p.alive = true;
  return id;
}

std::size_t checkedIndex(const std::vector<ProxyData>& proxies, ProxyId id, const char* owner) {
  if (id < 0 || static_cast<std::size_t>(id) >= proxies.size() ||
      !proxies[static_cast<std::size_t>(id)].alive)
    throw InvalidProxy(std::string(owner) + ": no proxy " + std::to_string(id));
  return static_cast<std::size_t>(id);
}

}  // namespace

// ------------------------------------------------------------------------------------ Quadtree

Quadtree::Quadtree(const AABB& worldBounds, int maxDepth) {
  checkAABB(worldBounds, "Quadtree world bounds");
  maxDepth_ = std::clamp(maxDepth, 0, 12);
  Vec2 e = worldBounds.extents();
  size_ = 2.0f * std::max(e.x, e.y);
  if (!(size_ > 0.0f)) throw InvalidProxy("Quadtree world bounds: zero size");
  Vec2 c = worldBounds.center();
  origin_ = {c.x - 0.5f * size_, c.y - 0.5f * size_};
  for (Tree* tree : {&static_, &moving_}) {
    tree->levels.resize(static_cast<std::size_t>(maxDepth_ + 1));
    for (int l = 0; l <= maxDepth_; ++l) {
      Level& level = tree->levels[static_cast<std::size_t>(l)];
      level.side = 1 << l;
      level.cellSize = size_ / static_cast<float>(level.side);
      level.heads.assign(static_cast<std::size_t>(level.side) * level.side, kNullProxy);
    }
  }
}

std::size_t Quadtree::checked(ProxyId id) const {
  return checkedIndex(proxies_, id, "Quadtree");
}

ProxyId& Quadtree::headOf(Tree& tree, int level, int cell) {
  if (level < 0) return tree.outside;
  return tree.levels[static_cast<std::size_t>(level)].heads[static_cast<std::size_t>(cell)];
}

void Quadtree::link(ProxyId id, Tree& tree, int level, int cell) {
  ProxyData& p = proxies_[static_cast<std::size_t>(id)];
  ProxyId& head = headOf(tree, level, cell);
  p.level = level;
  p.cell = cell;
  p.prev = kNullProxy;
  p.next = head;
  if (head != kNullProxy) proxies_[static_cast<std::size_t>(head)].prev = id;
  head = id;
  if (level < 0)
    ++tree.outsideCount;
  else
    ++tree.levels[static_cast<std::size_t>(level)].population;
}

void Quadtree::unlink(ProxyId id) {
  ProxyData& p = proxies_[static_cast<std::size_t>(id)];
  Tree& tree = treeOf(p);
  if (p.prev != kNullProxy)
    proxies_[static_cast<std::size_t>(p.prev)].next = p.next;
  else
    headOf(tree, p.level, p.cell) = p.next;
  if (p.next != kNullProxy) proxies_[static_cast<std::size_t>(p.next)].prev = p.prev;
  p.prev = p.next = kNullProxy;
  if (p.level < 0)
    --tree.outsideCount;
  else
    --tree.levels[static_cast<std::size_t>(p.level)].population;
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
    int fit = static_cast<int>(std::floor(std::log2(size_ / span)));
    level = std::clamp(fit, 0, maxDepth_);
    // log2 rounding: step back while the cell is smaller than the proxy.
    while (level > 0 && span > size_ / static_cast<float>(1 << level))
      --level;
  }
  const Level& lv = tree.levels[static_cast<std::size_t>(level)];
  const int x = std::min(static_cast<int>(c.x / lv.cellSize), lv.side - 1);
  const int y = std::min(static_cast<int>(c.y / lv.cellSize), lv.side - 1);
  link(id, tree, level, y * lv.side + x);
}

ProxyId Quadtree::createProxy(const ProxyDef& def) {
  checkAABB(def.aabb, "Quadtree::createProxy");
  ProxyId id = allocate(proxies_, free_, def);
  place(id);
  ++count_;
  return id;
}

void Quadtree::destroyProxy(ProxyId id) {
  std::size_t i = checked(id);
  unlink(id);
  proxies_[i].alive = false;
  free_.push_back(id);
  --count_;
}

bool Quadtree::moveProxy(ProxyId id, const AABB& aabb) {
  std::size_t i = checked(id);
  checkAABB(aabb, "Quadtree::moveProxy");
  ProxyData& p = proxies_[i];
  if (p.fat.contains(aabb)) return false;
  unlink(id);
  p.fat = inflate(aabb, kAabbMargin);
  place(id);
  return true;
}

void Quadtree::findPairs(std::vector<ProxyPair>& pairs) const {
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
    queryTree(moving_, m.fat, visit);
    queryTree(static_, m.fat, visit);
  }
  std::sort(pairs.begin(), pairs.end());
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

void Quadtree::validate() const {
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
        if (p.prev != prev) fail(name + " has a broken back link");
        if (p.level != level || p.cell != cell) fail(name + " records the wrong cell");
        if (lv != nullptr) {
          // Inside the cell's loose bounds, and as deep as its size allows.
          int side = lv->side;
          Vec2 lo{origin_.x + static_cast<float>(cell % side) * lv->cellSize - 0.5f * lv->cellSize,
                  origin_.y + static_cast<float>(cell / side) * lv->cellSize - 0.5f * lv->cellSize};
          AABB loose{lo, {lo.x + 2.0f * lv->cellSize, lo.y + 2.0f * lv->cellSize}};
          if (!loose.contains(p.fat)) fail(name + " sticks out of its cell's loose bounds");
        }
        prev = id;
      }
      return n;
    };
    int outside = walk(tree->outside, -1, 0, nullptr);
    if (outside != tree->outsideCount) fail("outside count");
    seen += outside;
    for (int l = 0; l <= maxDepth_; ++l) {
      const Level& lv = tree->levels[static_cast<std::size_t>(l)];
      int pop = 0;
      for (int c = 0; c < lv.side * lv.side; ++c)
        pop += walk(lv.heads[static_cast<std::size_t>(c)], l, c, &lv);
      if (pop != lv.population) fail("population of level " + std::to_string(l));
      seen += pop;
    }
  }
  if (seen != count_) fail("linked " + std::to_string(seen) + " of " + std::to_string(count_));
}

// ---------------------------------------------------------------------------------- BruteForce

std::size_t BruteForce::checked(ProxyId id) const {
  return checkedIndex(proxies_, id, "BruteForce");
}

ProxyId BruteForce::createProxy(const ProxyDef& def) {
  checkAABB(def.aabb, "BruteForce::createProxy");
  ++count_;
  return allocate(proxies_, free_, def);
}

void BruteForce::destroyProxy(ProxyId id) {
  proxies_[checked(id)].alive = false;
  free_.push_back(id);
  --count_;
}

bool BruteForce::moveProxy(ProxyId id, const AABB& aabb) {
  ProxyData& p = proxies_[checked(id)];
  checkAABB(aabb, "BruteForce::moveProxy");
  if (p.fat.contains(aabb)) return false;
  p.fat = inflate(aabb, kAabbMargin);
  return true;
}

void BruteForce::findPairs(std::vector<ProxyPair>& pairs) const {
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

std::vector<ProxyId> BruteForce::queryAABB(const AABB& box, ProxyFilter filter) const {
  std::vector<ProxyId> out;
  for (std::size_t i = 0; i < proxies_.size(); ++i)
    if (proxies_[i].alive && shouldCollide(filter, proxies_[i].filter) &&
        overlaps(proxies_[i].fat, box))
      out.push_back(static_cast<ProxyId>(i));
  return out;
}

std::vector<ProxyId> BruteForce::queryPoint(Vec2 p, ProxyFilter filter) const {
  return queryAABB(AABB{p, p}, filter);
}

}  // namespace rc
