#include "physics/stack_solve.h"
// The four-double solves are compiled for AVX2 in their own function and everything they use is
// inlined into it, so the compilers' warning that passing such a vector would change the ABI
// (-Wpsabi) does not apply (as in contact_solver.cpp).
#pragma GCC diagnostic ignored "-Wpsabi"
#include "physics/constants.h"
#include "physics/simd.h"
#include "physics/union_find.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace rc {

namespace {

// A row's Jacobian on one body: its velocity along the row is dot(j, (vx, vy, w)).
struct Jac {
  double x, y, w;
};

// The triangular solves on the float factor, W doubles a vector (2: SSE2, 4: AVX2). The same
// bits at either width: the backward pass is element by element, and the forward dot products
// keep eight running sums of two lanes each (element k in sum k mod 8 / 2's lane k mod 2),
// which four-lane vectors hold two to a register and add up in the same order.
struct Envelope {
  const float* factor;
  const std::size_t* start;
  const std::int32_t* first;
  std::int32_t bodies;
};

using D2 = double __attribute__((vector_size(16)));
using D4 = double __attribute__((vector_size(32)));
using F2 = float __attribute__((vector_size(8)));
using F4 = float __attribute__((vector_size(16)));

// Always inlined (no lambdas returning vectors): an AVX2 caller must get them in its own
// instructions, not as calls compiled without AVX that return a vector by another convention
// (see simd.h).
template <class V>
[[gnu::always_inline]] inline V loadDoubles(const double* p) {
  V v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
template <class V, class VF>
[[gnu::always_inline]] inline V loadFloats(const float* p) {
  VF v;
  __builtin_memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, V);
}
[[gnu::always_inline]] inline D2 pairs(D2 v) {
  return v;
}
[[gnu::always_inline]] inline D2 pairs(D4 v) {
  return D2{v[0], v[1]} + D2{v[2], v[3]};
}

template <class V>
[[gnu::always_inline]] inline V loadRow(const double* p) {
  return loadDoubles<V>(p);
}
template <class V>
[[gnu::always_inline]] inline V loadRow(const float* p) {
  if constexpr (sizeof(V) == 16)
    return loadFloats<V, F2>(p);
  else
    return loadFloats<V, F4>(p);
}

// R rows a[r] (float or double) dotted with the same b over n terms in eight two-lane running
// sums, then a tail: b loaded once for the R rows. One running sum is a chain of
// dependent additions: that chain, not the arithmetic, bounded the factorisation.
template <int W, int R, class T>
[[gnu::always_inline]] inline void dotRows(const T* const (&a)[R], const double* b, std::int32_t n,
                                           double (&out)[R]) {
  using V = std::conditional_t<W == 2, D2, D4>;
  constexpr int kSums = 8 / W;
  V sum[R][kSums] = {};
  std::int32_t k = 0;
  for (; k + 8 <= n; k += 8)
    for (int v = 0; v < kSums; ++v) {
      const V bv = loadDoubles<V>(b + k + W * v);
      for (int r = 0; r < R; ++r)
        sum[r][v] += loadRow<V>(a[r] + k + W * v) * bv;
    }
  for (int r = 0; r < R; ++r) {
    double tail = 0;
    for (std::int32_t j = k; j < n; ++j)
      tail += static_cast<double>(a[r][j]) * b[j];
    D2 s;
    if constexpr (W == 2)
      s = (sum[r][0] + sum[r][1]) + (sum[r][2] + sum[r][3]);
    else
      s = pairs(sum[r][0]) + pairs(sum[r][1]);
    out[r] = (s[0] + s[1]) + tail;
  }
}

template <int W>
[[gnu::always_inline]] inline double dot(const double* a, const double* b, std::int32_t n) {
  const double* const rows[1] = {a};
  double out[1];
  dotRows<W, 1, double>(rows, b, n, out);
  return out[0];
}

template <int W>
[[gnu::always_inline]] inline void solveEnvelope(const Envelope& L, double* x) {
  using V = std::conditional_t<W == 2, D2, D4>;
  // L y = b, a body (three rows, one envelope start) at a time: x loaded once for the three.
  for (std::int32_t p = 0; p < L.bodies; ++p) {
    const auto i = static_cast<std::size_t>(3 * p);
    const std::int32_t f = L.first[i];
    const std::int32_t n = 3 * p - f;
    const float* const l[3] = {L.factor + L.start[i], L.factor + L.start[i + 1],
                               L.factor + L.start[i + 2]};
    double d[3];
    dotRows<W, 3, float>(l, x + f, n, d);
    x[i] = (x[i] - d[0]) / l[0][n];
    x[i + 1] = (x[i + 1] - d[1] - l[1][n] * x[i]) / l[1][n + 1];
    x[i + 2] = (x[i + 2] - d[2] - l[2][n] * x[i] - l[2][n + 1] * x[i + 1]) / l[2][n + 2];
  }
  // L^T e = y, a body at a time: x updated once for the three rows, in the order row by row
  // would.
  for (std::int32_t p = L.bodies - 1; p >= 0; --p) {
    const auto i = static_cast<std::size_t>(3 * p);
    const std::int32_t f = L.first[i];
    const std::int32_t n = 3 * p - f;
    const float* l0 = L.factor + L.start[i];
    const float* l1 = L.factor + L.start[i + 1];
    const float* l2 = L.factor + L.start[i + 2];
    const double x2 = x[i + 2] / l2[n + 2];
    const double x1 = (x[i + 1] - l2[n + 1] * x2) / l1[n + 1];
    const double x0 = ((x[i] - l2[n] * x2) - l1[n] * x1) / l0[n];
    x[i] = x0;
    x[i + 1] = x1;
    x[i + 2] = x2;
    double* xf = x + f;
    std::int32_t k = 0;
    const V v0 = V{} + x0, v1 = V{} + x1, v2 = V{} + x2;
    for (; k + W <= n; k += W) {
      const V r = ((loadDoubles<V>(xf + k) - loadRow<V>(l2 + k) * v2) - loadRow<V>(l1 + k) * v1) -
                  loadRow<V>(l0 + k) * v0;
      std::memcpy(xf + k, &r, sizeof r);
    }
    for (; k < n; ++k)
      xf[k] = ((xf[k] - l2[k] * x2) - l1[k] * x1) - l0[k] * x0;
  }
}

// Cholesky in place, row by row within the envelope (fill stays inside it; row i holds columns
// first[i] to i), a body's three rows at a time: each earlier row j is loaded once for the
// three. K is positive definite (M's diagonal alone is); the floor only keeps rounding from
// taking a square root of a negative.
template <int W>
[[gnu::always_inline]] inline void factorEnvelope(double* factor, const std::size_t* start,
                                                  const std::int32_t* first, std::int32_t bodies) {
  for (std::int32_t p = 0; p < bodies; ++p) {
    const auto i = static_cast<std::size_t>(3 * p);
    const std::int32_t f = first[i];
    const std::int32_t n = 3 * p - f;
    double* l[3] = {factor + start[i], factor + start[i + 1], factor + start[i + 2]};
    for (std::int32_t j = f; j < 3 * p; ++j) {
      const std::int32_t fj = first[static_cast<std::size_t>(j)];
      const double* lj = factor + start[static_cast<std::size_t>(j)];
      const std::int32_t k0 = std::max(f, fj);
      const double* const a[3] = {l[0] + (k0 - f), l[1] + (k0 - f), l[2] + (k0 - f)};
      double d[3];
      dotRows<W, 3, double>(a, lj + (k0 - fj), j - k0, d);
      for (int r = 0; r < 3; ++r)
        l[r][j - f] = (l[r][j - f] - d[r]) / lj[j - fj];
    }
    // The body's own 3 x 3 block.
    l[0][n] = std::sqrt(std::max(l[0][n] - dot<W>(l[0], l[0], n), 1e-300));
    l[1][n] = (l[1][n] - dot<W>(l[1], l[0], n)) / l[0][n];
    l[1][n + 1] = std::sqrt(std::max(l[1][n + 1] - dot<W>(l[1], l[1], n + 1), 1e-300));
    l[2][n] = (l[2][n] - dot<W>(l[2], l[0], n)) / l[0][n];
    l[2][n + 1] = (l[2][n + 1] - dot<W>(l[2], l[1], n + 1)) / l[1][n + 1];
    l[2][n + 2] = std::sqrt(std::max(l[2][n + 2] - dot<W>(l[2], l[2], n + 2), 1e-300));
  }
}

#if RC_HAVE_AVX2_PATHS
[[gnu::target("avx2")]] void factorEnvelope4(double* factor, const std::size_t* start,
                                             const std::int32_t* first, std::int32_t bodies) {
  factorEnvelope<4>(factor, start, first, bodies);
}
[[gnu::target("avx2")]] void solveEnvelope4(const Envelope& L, double* x) {
  solveEnvelope<4>(L, x);
}
#endif

// Each at the width asked for (wide: four doubles a vector, where there are AVX2 paths).
void factorEnvelope(bool wide, double* factor, const std::size_t* start, const std::int32_t* first,
                    std::int32_t bodies) {
#if RC_HAVE_AVX2_PATHS
  if (wide) return factorEnvelope4(factor, start, first, bodies);
#endif
  (void)wide;
  factorEnvelope<2>(factor, start, first, bodies);
}
void solveEnvelope(bool wide, const Envelope& L, double* x) {
#if RC_HAVE_AVX2_PATHS
  if (wide) return solveEnvelope4(L, x);
#endif
  (void)wide;
  solveEnvelope<2>(L, x);
}

// A row's forces fn (normal) and ft (tangent) on the system's unknowns: J^T (fn, ft), -J on A's
// side. out: per unknown body, three a body.
template <class Row>
void addRowForces(const Row& r, double fn, double ft, double* out) {
  const Vec2 t{r.n.y, -r.n.x};
  if (r.posA >= 0) {
    double* x = &out[3 * static_cast<std::size_t>(r.posA)];
    x[0] -= fn * r.n.x + ft * t.x;
    x[1] -= fn * r.n.y + ft * t.y;
    x[2] -= fn * r.rnA + ft * r.rtA;
  }
  if (r.posB >= 0) {
    double* x = &out[3 * static_cast<std::size_t>(r.posB)];
    x[0] += fn * r.n.x + ft * t.x;
    x[1] += fn * r.n.y + ft * t.y;
    x[2] += fn * r.rnB + ft * r.rtB;
  }
}

// A carried friction impulse at this fraction of its cone or more: the point was sliding.
constexpr float kSlidingFraction = 0.99f;
// Once a correction is wanted, it is until the pile is under this fraction of the bounds
// (correctionWanted).
constexpr float kStopFraction = 0.1f;
// A pile with a body over this many times the bounds is not settling but moving, and is left to
// the passes (correctionWanted). The line search keeps the pile's energy from growing, not one
// body's: 600 circles falling into a box at up to 7 m/s, corrected, shot one out at about 20 m/s
// (tests/stress, "pressure"); at 50 times the bounds the piston pressing that pile still crept
// 15 mm in the last 300 steps, at 25 times 0.05 mm (without the solve 0.005 mm).
constexpr float kMovingFactor = 25.0f;

}  // namespace

bool StackSolver::widestByDefault() {
#if RC_HAVE_AVX2_PATHS
  return simd::avx2Enabled();
#else
  return false;
#endif
}

void StackSolver::build(std::span<const Constraint> constraints, std::span<const float> invMass,
                        std::span<const float> invInertia, int minDepth, float compliance,
                        bool sameLinks) {
  constraints_ = constraints;
  invMassBySlot_ = invMass;
  invInertiaBySlot_ = invInertia;
  compliance_ = compliance;
  rowsMade_ = false;
  // The piles are a function of which bodies touch which: the same links as the last build's
  // (a pile at rest, step after step) give the same piles, found again for nothing.
  deepestKnown_ = false;
  if (sameLinks && minDepth == lastMinDepth_) return;
  links_.clear();
  for (const Constraint& c : constraints)
    if (c.touching != 0)
      links_.push_back({c.movesA ? c.slotA : -1, c.movesB ? c.slotB : -1, c.touching});
  if (minDepth != lastMinDepth_ || links_ != lastLinks_) {
    std::swap(links_, lastLinks_);
    lastMinDepth_ = minDepth;
    findPiles(minDepth);
  }
}

// The piles' deepest overlap this step (<= 0), for correctionWanted's last test: worked out
// only in a step where a correction would otherwise be wanted.
float StackSolver::deepestOverlap() {
  if (deepestKnown_) return deepest_;
  deepestKnown_ = true;
  deepest_ = 0;
  for (const Constraint& c : constraints_) {
    if (c.touching == 0) continue;
    if (position(local(c.slotA, c.movesA)) < 0 && position(local(c.slotB, c.movesB)) < 0) continue;
    for (int k = 0; k < c.pointCount; ++k)
      if ((c.touching >> k) & 1) deepest_ = std::min(deepest_, c.separation[k]);
  }
  return deepest_;
}

void StackSolver::findPiles(int minDepth) {
  const std::span<const Constraint> constraints = constraints_;
  const std::span<const float> invMass = invMassBySlot_;
  order_.clear();
  unknowns_ = 0;
  auto touching = [](const Constraint& c) { return c.touching != 0; };

  // The bodies of touching constraints by local number (slot_ / local_), so that what follows
  // costs the contacts, not the awake bodies: a crowd of thousands with a few dozen contacts
  // pays for the contacts alone.
  for (const std::int32_t slot : slot_)
    local_[static_cast<std::size_t>(slot)] = -1;
  slot_.clear();
  if (local_.size() < invMass.size()) local_.resize(invMass.size(), -1);
  auto localOf = [&](std::int32_t slot) {
    std::int32_t& l = local_[static_cast<std::size_t>(slot)];
    if (l < 0) {
      l = static_cast<std::int32_t>(slot_.size());
      slot_.push_back(slot);
    }
    return l;
  };
  for (const Constraint& c : constraints) {
    if (!touching(c)) continue;
    if (c.movesA) localOf(c.slotA);
    if (c.movesB) localOf(c.slotB);
  }
  const auto m = static_cast<std::int32_t>(slot_.size());
  // Adjacency of the moving bodies over touching constraints (compressed rows), and the
  // sources: bodies resting on something contacts do not move.
  level_.assign(static_cast<std::size_t>(m), -1);
  adjStart_.assign(static_cast<std::size_t>(m) + 1, 0);
  queue_.clear();
  for (const Constraint& c : constraints) {
    if (!touching(c)) continue;
    const std::int32_t a = local(c.slotA, c.movesA), b = local(c.slotB, c.movesB);
    if (a >= 0 && b >= 0) {
      ++adjStart_[static_cast<std::size_t>(a) + 1];
      ++adjStart_[static_cast<std::size_t>(b) + 1];
    } else if (a >= 0 || b >= 0) {
      const std::int32_t s = a >= 0 ? a : b;
      if (level_[static_cast<std::size_t>(s)] < 0) {
        level_[static_cast<std::size_t>(s)] = 0;
        queue_.push_back(s);
      }
    }
  }
  if (queue_.empty()) return;
  for (std::int32_t s = 0; s < m; ++s)
    adjStart_[static_cast<std::size_t>(s) + 1] += adjStart_[static_cast<std::size_t>(s)];
  adj_.resize(static_cast<std::size_t>(adjStart_[static_cast<std::size_t>(m)]));
  pos_.assign(adjStart_.begin(), adjStart_.end() - 1);  // fill cursors
  for (const Constraint& c : constraints) {
    if (!touching(c)) continue;
    const std::int32_t a = local(c.slotA, c.movesA), b = local(c.slotB, c.movesB);
    if (a < 0 || b < 0) continue;
    adj_[static_cast<std::size_t>(pos_[static_cast<std::size_t>(a)]++)] = b;
    adj_[static_cast<std::size_t>(pos_[static_cast<std::size_t>(b)]++)] = a;
  }
  // Breadth first from the sources: each body's level, and the order of the unknowns (level
  // by level, which keeps the envelope one row of the pile wide).
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const std::int32_t s = queue_[head];
    const std::int32_t next = level_[static_cast<std::size_t>(s)] + 1;
    for (std::int32_t e = adjStart_[static_cast<std::size_t>(s)];
         e < adjStart_[static_cast<std::size_t>(s) + 1]; ++e) {
      const std::int32_t t = adj_[static_cast<std::size_t>(e)];
      if (level_[static_cast<std::size_t>(t)] >= 0) continue;
      level_[static_cast<std::size_t>(t)] = next;
      queue_.push_back(t);
    }
  }
  // Each group of touching bodies (union-find) and its deepest level.
  parent_.resize(static_cast<std::size_t>(m));
  for (std::int32_t s = 0; s < m; ++s)
    parent_[static_cast<std::size_t>(s)] = s;
  auto root = [&](std::int32_t x) { return unionFindRoot(parent_, x); };
  for (std::int32_t s = 0; s < m; ++s)
    for (std::int32_t e = adjStart_[static_cast<std::size_t>(s)];
         e < adjStart_[static_cast<std::size_t>(s) + 1]; ++e) {
      const std::int32_t ra = root(s), rb = root(adj_[static_cast<std::size_t>(e)]);
      if (ra != rb) parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
    }
  depth_.assign(static_cast<std::size_t>(m), -1);
  for (const std::int32_t s : queue_) {
    std::int32_t& d = depth_[static_cast<std::size_t>(root(s))];
    d = std::max(d, level_[static_cast<std::size_t>(s)]);
  }
  pos_.assign(static_cast<std::size_t>(m), -1);
  for (const std::int32_t s : queue_) {
    if (depth_[static_cast<std::size_t>(root(s))] < minDepth) continue;
    pos_[static_cast<std::size_t>(s)] = static_cast<std::int32_t>(order_.size());
    order_.push_back(slot_[static_cast<std::size_t>(s)]);
  }
  if (order_.empty()) return;
  invMass_.resize(order_.size());
  invInertia_.resize(order_.size());
  unknowns_ = 3 * static_cast<std::int32_t>(order_.size());
}

// The rows: every touching point of a constraint on a pile's body, from this step's
// constraints; and the pile's inverse masses by position in the system.
void StackSolver::makeRows() {
  rowsMade_ = true;
  rows_.clear();
  for (std::size_t p = 0; p < order_.size(); ++p) {
    invMass_[p] = invMassBySlot_[static_cast<std::size_t>(order_[p])];
    invInertia_[p] = invInertiaBySlot_[static_cast<std::size_t>(order_[p])];
  }
  const std::span<const Constraint> constraints = constraints_;
  const auto C = static_cast<std::int32_t>(constraints.size());
  const float compliance = compliance_;
  for (std::int32_t i = 0; i < C; ++i) {
    const Constraint& c = constraints[static_cast<std::size_t>(i)];
    const std::int32_t a = local(c.slotA, c.movesA), b = local(c.slotB, c.movesB);
    const std::int32_t pa = position(a), pb = position(b);
    if (pa < 0 && pb < 0) continue;
    // Only the support: a contact between two bodies of one level (neighbours in a row) is
    // left to the passes. Solved exactly with the rest, such a contact is asked to pull (the
    // row spreads as the pile settles), the projection drops the pull, and the rest of the
    // correction, which counted on it, is then wrong: that grew without bound on a base-40
    // pyramid.
    if (pa >= 0 && pb >= 0 &&
        level_[static_cast<std::size_t>(a)] == level_[static_cast<std::size_t>(b)])
      continue;
    const Vec2 t{c.normal.y, -c.normal.x};
    for (int k = 0; k < c.pointCount; ++k) {
      if (((c.touching >> k) & 1) == 0) continue;
      Row r;
      r.constraint = i;
      r.point = k;
      r.slotA = c.slotA;
      r.slotB = c.slotB;
      r.posA = pa;
      r.posB = pb;
      r.n = c.normal;
      r.rnA = cross(c.rA[k], c.normal);
      r.rnB = cross(c.rB[k], c.normal);
      r.rtA = cross(c.rA[k], t);
      r.rtB = cross(c.rB[k], t);
      double kn = 0, kt = 0;
      if (pa >= 0) {
        const double im = invMass_[static_cast<std::size_t>(pa)];
        const double ii = invInertia_[static_cast<std::size_t>(pa)];
        kn += im + ii * r.rnA * r.rnA;
        kt += im + ii * r.rtA * r.rtA;
      }
      if (pb >= 0) {
        const double im = invMass_[static_cast<std::size_t>(pb)];
        const double ii = invInertia_[static_cast<std::size_t>(pb)];
        kn += im + ii * r.rnB * r.rnB;
        kt += im + ii * r.rtB * r.rtB;
      }
      if (kn <= 0 || kt <= 0) continue;
      r.weightN = 1.0 / (compliance * kn);
      // Friction's row where the point sticks: without the tangents in the system a pile's
      // sideways mode grows (its normal impulses answered by friction only in the passes). A
      // point that slid last step (its friction at the cone) or has none is left out: solved
      // as if it stuck, its friction would then be cut back to the cone and the normal
      // impulses that balanced it would be wrong (a sliding box spun). A point with no load
      // yet counts as sticking; leaving those out made a base-40 pyramid fall.
      const float tn = c.normalImpulse[k], tt = std::abs(c.tangentImpulse[k]);
      const bool slid = tn > 0.0f && tt >= kSlidingFraction * c.friction * tn;
      r.weightT = c.friction > 0.0f && !slid ? 1.0 / (compliance * kt) : 0.0;
      r.friction = c.friction;
      rows_.push_back(r);
    }
  }
}

void StackSolver::factor() {
  // The envelope: an unknown's row reaches back to the first unknown of the earliest body it
  // touches.
  const auto bodies = static_cast<std::int32_t>(order_.size());
  std::vector<std::int32_t>& firstBody = depth_;  // reused: per position
  firstBody.resize(static_cast<std::size_t>(bodies));
  for (std::int32_t p = 0; p < bodies; ++p)
    firstBody[static_cast<std::size_t>(p)] = p;
  for (const Row& r : rows_) {
    if (r.posA < 0 || r.posB < 0) continue;
    const std::int32_t lo = std::min(r.posA, r.posB), hi = std::max(r.posA, r.posB);
    std::int32_t& f = firstBody[static_cast<std::size_t>(hi)];
    f = std::min(f, lo);
  }
  first_.resize(static_cast<std::size_t>(unknowns_));
  start_.resize(static_cast<std::size_t>(unknowns_) + 1);
  std::size_t size = 0;
  for (std::int32_t u = 0; u < unknowns_; ++u) {
    first_[static_cast<std::size_t>(u)] = 3 * firstBody[static_cast<std::size_t>(u / 3)];
    start_[static_cast<std::size_t>(u)] = size;
    size += static_cast<std::size_t>(u - first_[static_cast<std::size_t>(u)] + 1);
  }
  start_[static_cast<std::size_t>(unknowns_)] = size;
  factor_.assign(size, 0.0);
  auto at = [&](std::int32_t i, std::int32_t j) -> double& {  // j <= i, inside the envelope
    return factor_[start_[static_cast<std::size_t>(i)] +
                   static_cast<std::size_t>(j - first_[static_cast<std::size_t>(i)])];
  };

  // K = M + J^T W J. A direction a body cannot move in (infinite mass or inertia: a
  // fixed-rotation body's turn) keeps a unit diagonal and no coupling, so its change is 0.
  auto inverse = [&](std::int32_t p, int d) {
    const auto q = static_cast<std::size_t>(p);
    return d < 2 ? static_cast<double>(invMass_[q]) : static_cast<double>(invInertia_[q]);
  };
  for (std::int32_t p = 0; p < bodies; ++p)
    for (int d = 0; d < 3; ++d) {
      const double im = inverse(p, d);
      at(3 * p + d, 3 * p + d) = im > 0 ? 1.0 / im : 1.0;
    }
  auto addOuter = [&](std::int32_t p, const Jac& jp, std::int32_t q, const Jac& jq, double w) {
    // Block (p, q) with p >= q; on the diagonal only its lower half.
    const double ap[3] = {jp.x, jp.y, jp.w}, aq[3] = {jq.x, jq.y, jq.w};
    for (int d = 0; d < 3; ++d) {
      if (inverse(p, d) <= 0) continue;
      for (int e = 0; e < 3; ++e) {
        if (inverse(q, e) <= 0 || (p == q && e > d)) continue;
        at(3 * p + d, 3 * q + e) += w * ap[d] * aq[e];
      }
    }
  };
  for (const Row& r : rows_) {
    const Vec2 t{r.n.y, -r.n.x};
    const Jac nA{-r.n.x, -r.n.y, -r.rnA}, nB{r.n.x, r.n.y, r.rnB};
    const Jac tA{-t.x, -t.y, -r.rtA}, tB{t.x, t.y, r.rtB};
    for (int pass = 0; pass < 2; ++pass) {
      const Jac& jA = pass == 0 ? nA : tA;
      const Jac& jB = pass == 0 ? nB : tB;
      const double w = pass == 0 ? r.weightN : r.weightT;
      if (r.posA >= 0) addOuter(r.posA, jA, r.posA, jA, w);
      if (r.posB >= 0) addOuter(r.posB, jB, r.posB, jB, w);
      if (r.posA >= 0 && r.posB >= 0) {
        if (r.posA > r.posB)
          addOuter(r.posA, jA, r.posB, jB, w);
        else
          addOuter(r.posB, jB, r.posA, jA, w);
      }
    }
  }

  factorEnvelope(wide_, factor_.data(), start_.data(), first_.data(), bodies);
  // The solves read the factor in float: half the bytes (the base-40 pyramid's 197k entries fit
  // in a core's 1 MiB L2 as float, not as double), and the triangular solves stream it twice a
  // correction. What the rounding leaves is taken out by the next correction with the rest of
  // what the compliance let through; the piles measured sleep and drift as with double.
  factorF_.resize(factor_.size());
  for (std::size_t k = 0; k < factor_.size(); ++k)
    factorF_[k] = static_cast<float>(factor_[k]);
}

bool StackSolver::correctionWanted(std::span<const SolverBody> bodies, float speed, float turn) {
  if (unknowns_ == 0) return false;
  // Started above the bounds, wanted until every body is under a tenth of them: corrections
  // that stop as soon as the pile is under the bounds leave it breathing just below them (a
  // base-40 pyramid at 0.02 m/s for hundreds of steps), where taking it down to a tenth stops
  // it (under 0.003 m/s after 9 corrections in 4000 substeps).
  const float f = wanted_ ? kStopFraction : 1.0f;
  const float v2 = f * f * speed * speed, w2 = f * f * turn * turn;
  const float u2 = kMovingFactor * kMovingFactor * speed * speed,
              uw2 = kMovingFactor * kMovingFactor * turn * turn;
  // Squared, two bodies at a time into running maxima of their own: one was a chain of dependent
  // max instructions as long as the pile. The same result: a maximum is exact, and a NaN, never
  // greater, is never taken by either.
  float fastest = 0, fastestTurn = 0, fastest2 = 0, fastestTurn2 = 0;
  const std::size_t n = order_.size();
  std::size_t k = 0;
  for (; k + 2 <= n; k += 2) {
    const SolverBody& b = bodies[static_cast<std::size_t>(order_[k])];
    const SolverBody& b2 = bodies[static_cast<std::size_t>(order_[k + 1])];
    fastest = std::max(fastest, dot(b.v, b.v));
    fastestTurn = std::max(fastestTurn, b.w * b.w);
    fastest2 = std::max(fastest2, dot(b2.v, b2.v));
    fastestTurn2 = std::max(fastestTurn2, b2.w * b2.w);
  }
  if (k < n) {
    const SolverBody& b = bodies[static_cast<std::size_t>(order_[k])];
    fastest = std::max(fastest, dot(b.v, b.v));
    fastestTurn = std::max(fastestTurn, b.w * b.w);
  }
  fastest = std::max(fastest, fastest2);
  fastestTurn = std::max(fastestTurn, fastestTurn2);
  if (fastest > u2 || fastestTurn > uw2) {
    wanted_ = false;
    return false;
  }
  const bool over = fastest > v2 || fastestTurn > w2;
  // A correction works on velocities and cannot push overlaps apart: a pile overlapping deeper
  // than the slop (pressed beyond what its soft contacts hold there, or being pushed apart) is
  // left to the passes. Corrected, 600 circles under a piston were held 9 cm higher than their
  // contacts' law rests them, and crept down to it at 3 mm/s for seconds.
  wanted_ = over && deepestOverlap() >= -kLinearSlop;
  return wanted_;
}

void StackSolver::correct(std::span<SolverBody> bodies, std::span<float> impulses) {
  if (unknowns_ == 0) return;
  if (!rowsMade_) {
    makeRows();
    factor();
  }
  rhs_.assign(static_cast<std::size_t>(unknowns_), 0.0);
  vn_.resize(rows_.size());
  vt_.resize(rows_.size());
  // Each row's velocity, and the right-hand side -J^T W J v.
  for (std::size_t ri = 0; ri < rows_.size(); ++ri) {
    const Row& r = rows_[ri];
    const Vec2 t{r.n.y, -r.n.x};
    double vn = 0, vt = 0;
    if (r.slotA >= 0) {
      const SolverBody& a = bodies[static_cast<std::size_t>(r.slotA)];
      vn -= static_cast<double>(dot(a.v, r.n)) + static_cast<double>(a.w) * r.rnA;
      vt -= static_cast<double>(dot(a.v, t)) + static_cast<double>(a.w) * r.rtA;
    }
    if (r.slotB >= 0) {
      const SolverBody& b = bodies[static_cast<std::size_t>(r.slotB)];
      vn += static_cast<double>(dot(b.v, r.n)) + static_cast<double>(b.w) * r.rnB;
      vt += static_cast<double>(dot(b.v, t)) + static_cast<double>(b.w) * r.rtB;
    }
    vn_[ri] = vn;
    vt_[ri] = vt;
    addRowForces(r, -r.weightN * vn, -r.weightT * vt, rhs_.data());
  }
  // Directions a body cannot move in have no right-hand side (their unit diagonal gives 0).
  for (std::size_t p = 0; p < invMass_.size(); ++p) {
    if (invMass_[p] <= 0) rhs_[3 * p] = 0, rhs_[3 * p + 1] = 0;
    if (invInertia_[p] <= 0) rhs_[3 * p + 2] = 0;
  }
  // L y = b, then L^T e = y.
  double* x = rhs_.data();
  solveEnvelope(wide_, Envelope{factorF_.data(), start_.data(), first_.data(), unknowns_ / 3}, x);
  // Each point's impulse change from the corrected velocities, projected onto its cone.
  delta_.assign(static_cast<std::size_t>(unknowns_), 0.0);
  for (std::size_t ri = 0; ri < rows_.size(); ++ri) {
    const Row& r = rows_[ri];
    const Vec2 t{r.n.y, -r.n.x};
    double un = vn_[ri], ut = vt_[ri];
    if (r.posA >= 0) {
      const double* e = &x[3 * static_cast<std::size_t>(r.posA)];
      un -= e[0] * r.n.x + e[1] * r.n.y + e[2] * r.rnA;
      ut -= e[0] * t.x + e[1] * t.y + e[2] * r.rtA;
    }
    if (r.posB >= 0) {
      const double* e = &x[3 * static_cast<std::size_t>(r.posB)];
      un += e[0] * r.n.x + e[1] * r.n.y + e[2] * r.rnB;
      ut += e[0] * t.x + e[1] * t.y + e[2] * r.rtB;
    }
    const float ln = impulses[normalAt(r)], lt = impulses[tangentAt(r)];
    const float n1 = std::max(ln + static_cast<float>(-r.weightN * un), 0.0f);
    const float limit = r.friction * n1;
    const float t1 = std::clamp(lt + static_cast<float>(-r.weightT * ut), -limit, limit);
    const double dn = static_cast<double>(n1) - ln, dt = static_cast<double>(t1) - lt;
    vn_[ri] = dn;  // the row's step, from here on
    vt_[ri] = dt;
    addRowForces(r, dn, dt, delta_.data());
  }
  // Where nothing was cut back to its cone the step is the projection, the least kinetic
  // energy the support allows. Where something was, it is not: the rest of the step still
  // counts on what was cut, and applied whole it can add energy (every point in its cone, yet
  // the pile faster), which the passes between corrections then fed (corrections every other
  // substep blew a base-40 pyramid apart). So the step is taken only as far along as lowers the
  // kinetic energy most, never past 1: a convex combination of two impulses in the cone stays
  // in it, and no correction adds energy.
  const std::int32_t P = unknowns_ / 3;
  double slope = 0, curvature = 0;  // kinetic energy along the step: slope a + curvature a^2 / 2
  for (std::int32_t p = 0; p < P; ++p) {
    const auto q = static_cast<std::size_t>(p);
    const double* d = &delta_[3 * q];
    const SolverBody& b = bodies[static_cast<std::size_t>(order_[q])];
    const double im = invMass_[q], ii = invInertia_[q];
    // A change's impulse d turns into a velocity change im d: energy terms v . d and im d . d.
    slope += b.v.x * d[0] + b.v.y * d[1] + b.w * d[2];
    curvature += im * (d[0] * d[0] + d[1] * d[1]) + ii * d[2] * d[2];
  }
  const double along = curvature > 0 ? std::clamp(-slope / curvature, 0.0, 1.0) : 1.0;
  for (std::int32_t p = 0; p < P; ++p) {
    const auto q = static_cast<std::size_t>(p);
    const double* d = &delta_[3 * q];
    SolverBody& b = bodies[static_cast<std::size_t>(order_[q])];
    b.v.x += static_cast<float>(along * invMass_[q] * d[0]);
    b.v.y += static_cast<float>(along * invMass_[q] * d[1]);
    b.w += static_cast<float>(along * invInertia_[q] * d[2]);
  }
  for (std::size_t ri = 0; ri < rows_.size(); ++ri) {
    const Row& r = rows_[ri];
    float& ln = impulses[normalAt(r)];
    float& lt = impulses[tangentAt(r)];
    // In double: a whole step gives back the projected impulse exactly.
    ln = static_cast<float>(ln + along * vn_[ri]);
    lt = static_cast<float>(lt + along * vt_[ri]);
  }
  lastStep_ = along;
}

}  // namespace rc
