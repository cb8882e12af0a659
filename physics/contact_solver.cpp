// Every function here that takes or returns vectors is inlined into the per-width pass functions
// (solve4, solve8, ...), so no eight-lane vector crosses a call compiled without AVX: the
// compilers' warning that such a call would change the ABI (-Wpsabi) does not apply.
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wunknown-warning-option"
#endif
#pragma GCC diagnostic ignored "-Wpsabi"

#include "physics/contact_solver.h"

#include <algorithm>
#include <cfloat>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "physics/constants.h"
#include "physics/simd.h"

namespace rc {
namespace {

using simd::select;
using simd::vmax;
using simd::vmin;

#define RC_INLINE [[gnu::always_inline]] inline

// Colours a constraint may take; a body with more contacts than this overflows.
constexpr int kColours = 24;

template <int N>
struct PointLanes {
  using F = typename simd::Lanes<N>::F;
  F rAx, rAy, rBx, rBy, rnA, rnB, rtA, rtB;
  F baseSeparation, normalMass, tangentMass;
  F normalImpulse, tangentImpulse, maxNormalImpulse, relativeVelocity;
  // The separation the last relax pass measured: the next substep's solve pass reads it, for no
  // position changes in between (ContactSolver::solve's sameMotion).
  F separation;
};

// N constraints, structure of arrays. Empty lanes have zero masses and point at the null body.
template <int N>
struct Batch {
  using F = typename simd::Lanes<N>::F;
  using M = typename simd::Lanes<N>::M;
  // Each lane's bodies as byte offsets into the solver's bodies (index * sizeof(SolverBody)):
  // a row's address is then one load and an add, where an index took a sign extension and a
  // shift more, 48 loads a batch (a tenth of a two-point batch's solve instructions).
  std::uint32_t a[N], b[N];
  F invMassA, invIA, invMassB, invIB;
  F nx, ny, friction, maxPushout;
  F k11, k12, k22, i11, i12, i22;
  M two;    // the lane has two points (writeLane)
  M block;  // the lane's two points may be solved together (computeMasses)
  PointLanes<N> p[2];
  int points;  // the most points of any lane: with 1 (circles), the second point's lanes are
               // skipped
};
static_assert(alignof(Batch<8>) == 32, "AVX loads of a batch need it 32-byte aligned");

// The bodies of one side of a batch, lane by lane (pad: SolverBody::unused, which nothing reads;
// the scatter writes it 0, so that the solve keeps no register for it).
template <int N>
struct BodyLanes {
  using F = typename simd::Lanes<N>::F;
  F vx, vy, w, pad, dpx, dpy, dqc, dqs;
};

// Rows of a 4x4 matrix into its columns; with eight lanes, two 4x4 matrices side by side (the
// low and high halves), each transposed in its own half. With the bodies' 16-byte halves as
// rows, one gather of four bodies is eight vector loads and sixteen shuffles, where building
// each lane from scalars took 28 loads and as many inserts (a third of a batch's solve).
RC_INLINE void transpose(simd::F& a, simd::F& b, simd::F& c, simd::F& d) {
  const simd::F ab01 = __builtin_shufflevector(a, b, 0, 4, 1, 5);
  const simd::F ab23 = __builtin_shufflevector(a, b, 2, 6, 3, 7);
  const simd::F cd01 = __builtin_shufflevector(c, d, 0, 4, 1, 5);
  const simd::F cd23 = __builtin_shufflevector(c, d, 2, 6, 3, 7);
  a = __builtin_shufflevector(ab01, cd01, 0, 1, 4, 5);
  b = __builtin_shufflevector(ab01, cd01, 2, 3, 6, 7);
  c = __builtin_shufflevector(ab23, cd23, 0, 1, 4, 5);
  d = __builtin_shufflevector(ab23, cd23, 2, 3, 6, 7);
}
RC_INLINE void transpose(simd::F8& a, simd::F8& b, simd::F8& c, simd::F8& d) {
  const simd::F8 ab01 = __builtin_shufflevector(a, b, 0, 8, 1, 9, 4, 12, 5, 13);
  const simd::F8 ab23 = __builtin_shufflevector(a, b, 2, 10, 3, 11, 6, 14, 7, 15);
  const simd::F8 cd01 = __builtin_shufflevector(c, d, 0, 8, 1, 9, 4, 12, 5, 13);
  const simd::F8 cd23 = __builtin_shufflevector(c, d, 2, 10, 3, 11, 6, 14, 7, 15);
  a = __builtin_shufflevector(ab01, cd01, 0, 1, 8, 9, 4, 5, 12, 13);
  b = __builtin_shufflevector(ab01, cd01, 2, 3, 10, 11, 6, 7, 14, 15);
  c = __builtin_shufflevector(ab23, cd23, 0, 1, 8, 9, 4, 5, 12, 13);
  d = __builtin_shufflevector(ab23, cd23, 2, 3, 10, 11, 6, 7, 14, 15);
}

// The body at a lane's byte offset (Batch::a, Batch::b).
RC_INLINE const SolverBody& bodyAt(const SolverBody* bodies, std::uint32_t offset) {
  return *reinterpret_cast<const SolverBody*>(reinterpret_cast<const char*>(bodies) + offset);
}
RC_INLINE SolverBody& bodyAt(SolverBody* bodies, std::uint32_t offset) {
  return *reinterpret_cast<SolverBody*>(reinterpret_cast<char*>(bodies) + offset);
}
constexpr std::uint32_t kBodyBytes = sizeof(SolverBody);

// A SolverBody's first half (v, w, unused) or second half (dp, dq) as one vector.
RC_INLINE simd::F loadHalf(const SolverBody& b, int half) {
  simd::F row;
  std::memcpy(&row, reinterpret_cast<const char*>(&b) + 16 * half, sizeof row);
  return row;
}
RC_INLINE void storeHalf(SolverBody& b, simd::F row) {
  std::memcpy(static_cast<void*>(&b), &row, sizeof row);
}

// Row k of the matrix transpose() turns into lanes: body k's half, and with eight lanes body
// k + 4's half beside it.
template <int N>
RC_INLINE typename simd::Lanes<N>::F loadRow(const SolverBody* bodies,
                                             const std::uint32_t (&index)[N], int k, int half) {
  const simd::F low = loadHalf(bodyAt(bodies, index[k]), half);
  if constexpr (N == 4) {
    return low;
  } else {
    const simd::F high = loadHalf(bodyAt(bodies, index[k + 4]), half);
    return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
  }
}

template <int N, bool withMotion>
RC_INLINE BodyLanes<N> gather(const SolverBody* bodies, const std::uint32_t (&index)[N]) {
  BodyLanes<N> out;
  out.vx = loadRow(bodies, index, 0, 0);
  out.vy = loadRow(bodies, index, 1, 0);
  out.w = loadRow(bodies, index, 2, 0);
  out.pad = loadRow(bodies, index, 3, 0);
  transpose(out.vx, out.vy, out.w, out.pad);
  if constexpr (withMotion) {
    out.dpx = loadRow(bodies, index, 0, 1);
    out.dpy = loadRow(bodies, index, 1, 1);
    out.dqc = loadRow(bodies, index, 2, 1);
    out.dqs = loadRow(bodies, index, 3, 1);
    transpose(out.dpx, out.dpy, out.dqc, out.dqs);
  }
  return out;
}

// Body k's velocity from rows of three floats a body (vx, vy, w), loaded as four (the fourth,
// the next body's vx or the padding after the last row, is not used), and with eight lanes body
// k + 4's beside it: row k of the matrix transpose() turns into lanes. (offset: the lane's
// SolverBody offset.)
RC_INLINE simd::F loadVelocityRow(const float* rows, std::uint32_t offset) {
  simd::F row;
  std::memcpy(&row, rows + 3 * static_cast<std::size_t>(offset / kBodyBytes), sizeof row);
  return row;
}
template <int N>
RC_INLINE typename simd::Lanes<N>::F loadVelocityRow(const float* rows,
                                                     const std::uint32_t (&index)[N], int k) {
  const simd::F low = loadVelocityRow(rows, index[k]);
  if constexpr (N == 4) {
    return low;
  } else {
    const simd::F high = loadVelocityRow(rows, index[k + 4]);
    return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
  }
}
template <int N>
RC_INLINE BodyLanes<N> gatherVelocities(const float* rows, const std::uint32_t (&index)[N]) {
  BodyLanes<N> out;
  out.vx = loadVelocityRow(rows, index, 0);
  out.vy = loadVelocityRow(rows, index, 1);
  out.w = loadVelocityRow(rows, index, 2);
  out.pad = loadVelocityRow(rows, index, 3);
  transpose(out.vx, out.vy, out.w, out.pad);
  return out;
}

// Lanes are written in order; lanes sharing a body (the null body, a kinematic body) hold the
// same unchanged velocity, so the order does not matter. Only the first half is written.
template <int N, class F>
RC_INLINE void scatter(SolverBody* bodies, const std::uint32_t (&index)[N], F vx, F vy, F w) {
  F pad{};
  transpose(vx, vy, w, pad);
  const F rows[4] = {vx, vy, w, pad};
  for (int k = 0; k < 4; ++k) {
    if constexpr (N == 4) {
      storeHalf(bodyAt(bodies, index[k]), rows[k]);
    } else {
      storeHalf(bodyAt(bodies, index[k]), __builtin_shufflevector(rows[k], rows[k], 0, 1, 2, 3));
    }
  }
  if constexpr (N == 8) {
    for (int k = 0; k < 4; ++k)
      storeHalf(bodyAt(bodies, index[k + 4]),
                __builtin_shufflevector(rows[k], rows[k], 4, 5, 6, 7));
  }
}

// Velocities of both sides of a batch, updated by impulses.
template <int N>
struct Velocities {
  using F = typename simd::Lanes<N>::F;
  F vAx, vAy, wA, vBx, vBy, wB;

  // Impulse `applied` along the direction (dx, dy), with the lever arms rA x d and rB x d:
  // -P on A, +P on B.
  RC_INLINE void apply(const Batch<N>& c, F applied, F dx, F dy, F leverA, F leverB) {
    const F px = applied * dx, py = applied * dy;
    vAx -= c.invMassA * px;
    vAy -= c.invMassA * py;
    wA -= c.invIA * applied * leverA;
    vBx += c.invMassB * px;
    vBy += c.invMassB * py;
    wB += c.invIB * applied * leverB;
  }
  // Relative velocity along (dx, dy) at a point with lever arms leverA, leverB.
  RC_INLINE F along(F dx, F dy, F leverA, F leverB) const {
    return (vBx - vAx) * dx + (vBy - vAy) * dy + wB * leverB - wA * leverA;
  }
};

template <int N>
RC_INLINE void warmStartBatch(Batch<N>& c, SolverBody* bodies, const float* free) {
  using F = typename simd::Lanes<N>::F;
  const BodyLanes<N> A = gather<N, false>(bodies, c.a), B = gather<N, false>(bodies, c.b);
  Velocities<N> v{A.vx, A.vy, A.w, B.vx, B.vy, B.w};
  const F tx = c.ny, ty = -c.nx;
  // The approach speed restitution reverses: the normal velocity of the free motion of the
  // substep in which the solver first pushes the point, the speed at the impact (what gravity
  // added before it included, and what it took away: the fastest of the step's substeps gave a
  // body decelerating into a ceiling more speed back than it hit with, up to g dt). Read from
  // the substep's free velocities, before any warm start: the bodies
  // here already carry the warm starts of earlier batches, a kick the solve takes back out
  // (a bullet resting on a floor and hit by another read the floor's carried impulse as 370
  // m/s of approach, where the free motion had 220, and the pair bounced apart with more
  // energy than they met with). Later substeps' velocities carry what the solver did to
  // neighbouring contacts and are not an approach: restitution on those fed a cluster of
  // overlapping circles energy, step after step.
  if (free != nullptr) {
    const BodyLanes<N> fA = gatherVelocities<N>(free, c.a), fB = gatherVelocities<N>(free, c.b);
    const Velocities<N> fv{fA.vx, fA.vy, fA.w, fB.vx, fB.vy, fB.w};
    for (int k = 0; k < c.points; ++k) {
      PointLanes<N>& p = c.p[k];
      const F vn = fv.along(c.nx, c.ny, p.rnA, p.rnB);
      p.relativeVelocity = select(p.maxNormalImpulse > 0.0f, p.relativeVelocity, vn);
    }
  }
  for (int k = 0; k < c.points; ++k) {
    const PointLanes<N>& p = c.p[k];
    const F px = p.normalImpulse * c.nx + p.tangentImpulse * tx;
    const F py = p.normalImpulse * c.ny + p.tangentImpulse * ty;
    v.vAx -= c.invMassA * px;
    v.vAy -= c.invMassA * py;
    v.wA -= c.invIA * (p.normalImpulse * p.rnA + p.tangentImpulse * p.rtA);
    v.vBx += c.invMassB * px;
    v.vBy += c.invMassB * py;
    v.wB += c.invIB * (p.normalImpulse * p.rnB + p.tangentImpulse * p.rtB);
  }
  scatter<N>(bodies, c.a, v.vAx, v.vAy, v.wA);
  scatter<N>(bodies, c.b, v.vBx, v.vBy, v.wB);
}

// What one point's normal row needs from the softness: its bias and its mass and impulse
// scales, by regime.
template <int N>
struct PointRegime {
  using F = typename simd::Lanes<N>::F;
  using M = typename simd::Lanes<N>::M;
  F bias, massScale, impulseScale;
  M isSoft, held;
};

template <int N>
RC_INLINE void setNormal(const Batch<N>& c, Velocities<N>& v, PointLanes<N>& p,
                         typename simd::Lanes<N>::F total) {
  const auto applied = total - p.normalImpulse;
  p.normalImpulse = total;
  p.maxNormalImpulse = vmax(p.maxNormalImpulse, applied);
  v.apply(c, applied, c.nx, c.ny, p.rnA, p.rnB);
}

// One point alone: l + (-m s_m (vn + b) - s_i l), clamped to push only; a held point may only
// give impulse back.
template <int N>
RC_INLINE typename simd::Lanes<N>::F alone(const PointLanes<N>& p, typename simd::Lanes<N>::F vn,
                                           const PointRegime<N>& r) {
  using F = typename simd::Lanes<N>::F;
  const F impulse = -p.normalMass * r.massScale * (vn + r.bias) - r.impulseScale * p.normalImpulse;
  const F total = vmax(p.normalImpulse + impulse, F{});
  return select(r.held, vmin(total, p.normalImpulse), total);
}

// Where a pass's separations come from: worked out from the bodies' motion, worked out and kept
// (the relax pass), or the kept ones (a solve pass with the motion the relax pass before saw).
enum class Separation { measure, measureAndKeep, kept };

template <int N, bool useBias, Separation from>
RC_INLINE void solveBatch(Batch<N>& c, SolverBody* bodies, const ContactSoftness& soft) {
  using F = typename simd::Lanes<N>::F;
  using M = typename simd::Lanes<N>::M;
  using simd::splat;
  constexpr bool measure = from != Separation::kept;
  const BodyLanes<N> A = gather<N, measure>(bodies, c.a), B = gather<N, measure>(bodies, c.b);
  Velocities<N> v{A.vx, A.vy, A.w, B.vx, B.vy, B.w};
  const M biasLanes = useBias ? ~M{} : M{};

  // Each point's regime: speculative (apart: approach no faster than closes the gap this
  // substep), rigid (within the slop: carries its load without pressing in further), or soft
  // (deeper, with the push-out bias; in the relax pass rigid too).
  PointRegime<N> regime[2];
  for (int k = 0; k < c.points; ++k) {
    PointLanes<N>& p = c.p[k];
    PointRegime<N>& r = regime[k];
    // Separation now, from how far the bodies moved and turned since the manifold was made.
    F s;
    if constexpr (measure) {
      const F rAx = A.dqc * p.rAx - A.dqs * p.rAy, rAy = A.dqs * p.rAx + A.dqc * p.rAy;
      const F rBx = B.dqc * p.rBx - B.dqs * p.rBy, rBy = B.dqs * p.rBx + B.dqc * p.rBy;
      const F dx = (B.dpx - A.dpx) + (rBx - p.rBx) - (rAx - p.rAx);
      const F dy = (B.dpy - A.dpy) + (rBy - p.rBy) - (rAy - p.rAy);
      s = dx * c.nx + dy * c.ny + p.baseSeparation;
      if constexpr (from == Separation::measureAndKeep) p.separation = s;
    } else {
      s = p.separation;
    }
    const M apart = s > 0.0f;
    r.isSoft = ~apart & (s <= -kLinearSlop) & biasLanes;
    // The push-out cap bounds how fast overlapping points part, not what a contact carries: on
    // top of it, the bias that holds the point's impulse against the softness's leak
    // (s_i l / (s_m m)). Capped alone, a soft contact carries at most m s_m cap / (s_i h), and a
    // heavier load (1000 kg on a 1 kg box: 30 times that) drives it in without end.
    // Only the pass with bias pushes (the relax pass skips the division). A lane without this
    // point has neither mass nor impulse: 0 / FLT_MIN, no NaN.
    const F hold =
        useBias ? soft.leak * p.normalImpulse / vmax(p.normalMass, splat<F>(FLT_MIN)) : F{};
    const F push = vmax(soft.biasRate * s, -c.maxPushout - hold);
    // Inside the slop, rigid, but pushed out towards half of it at the soft bias rate (the relax
    // pass takes the push's velocity back out): what a stack took in while it settled comes back
    // out, where a rigid contact alone keeps it (a tall pyramid's top stays low by what its
    // contacts sank). The price: a tall stack moves longer and sleeps later.
    const F settle = vmin(soft.biasRate * (s + 0.5f * kLinearSlop), F{});
    r.bias = select(apart, s * soft.invH, select(r.isSoft, push, select(biasLanes, settle, F{})));
    r.massScale = select(r.isSoft, splat<F>(soft.massScale), splat<F>(1.0f));
    r.impulseScale = select(r.isSoft, splat<F>(soft.impulseScale), F{});
    // The relax pass does not push a point still apart by more than the slop. Its gap is now
    // the one the next substep's motion will close, so a push here stops an approach before
    // the next substep's free motion adds to it: restitution would then reverse the approach of
    // a substep too early (bounces low by that substep's gravity), and a push in the last
    // substep would bounce the ball from up to v h above the floor. The next
    // substep's solve pass stops it instead, at the speed it arrives with. It may still take
    // back what the solve pass gave it: in a row of touching bodies the order of the solve
    // can leave a point separating with an impulse still on it, and kept, that impulse is
    // energy the contact made. Within the slop (resting contacts hover there) the relax pass
    // solves as before.
    r.held = ~biasLanes & (s > kLinearSlop);
  }

  PointLanes<N>&p0 = c.p[0], &p1 = c.p[1];
  if (c.points == 1) {
    setNormal(c, v, p0, alone(p0, v.along(c.nx, c.ny, p0.rnA, p0.rnB), regime[0]));
  } else {
    // Both points at once where the manifold allows it (a 2x2 linear complementarity problem):
    // solved one after the other, the first point's impulse turns the body and the second pushes
    // harder, and a tall stack of boxes, perfectly symmetric, starts to rock. With K the points'
    // coupled effective mass, the soft update x = (1 - s_i) l - s_m K^-1 (vn + b) is the solution
    // of A x + q = r with A = K / s_m, x >= 0, r >= 0, x r = 0; the four cases of which points
    // push are tried in turn. Lanes whose points are in different regimes, whose K is badly
    // conditioned, or where rounding leaves no case standing take the points one after the other.
    const F l0 = p0.normalImpulse, l1 = p1.normalImpulse;
    const F vn0 = v.along(c.nx, c.ny, p0.rnA, p0.rnB);
    const F vn1 = v.along(c.nx, c.ny, p1.rnA, p1.rnB);
    const M blockSoft = regime[0].isSoft;
    const F sm = regime[0].massScale;
    const F carry = select(blockSoft, splat<F>(soft.carry), splat<F>(1.0f));
    const F q0 = vn0 + regime[0].bias - carry * (c.k11 * l0 + c.k12 * l1);
    const F q1 = vn1 + regime[1].bias - carry * (c.k12 * l0 + c.k22 * l1);
    const F both0 = -sm * (c.i11 * q0 + c.i12 * q1), both1 = -sm * (c.i12 * q0 + c.i22 * q1);
    const F a12 = select(blockSoft, c.k12 * soft.invMassScale, c.k12);
    const M bothPush = (both0 >= 0.0f) & (both1 >= 0.0f);
    const F first0 = -sm * p0.normalMass * q0;
    const M firstPushes = (first0 >= 0.0f) & (a12 * first0 + q1 >= 0.0f);
    const F second1 = -sm * p1.normalMass * q1;
    const M secondPushes = (second1 >= 0.0f) & (a12 * second1 + q0 >= 0.0f);
    const M neither = (q0 >= 0.0f) & (q1 >= 0.0f);
    const M useBlock = c.block & (regime[0].isSoft == regime[1].isSoft) &
                       ~(regime[0].held | regime[1].held) &
                       (bothPush | firstPushes | secondPushes | neither);
    const F block0 = select(bothPush, both0, select(firstPushes, first0, F{}));
    const F block1 =
        select(bothPush, both1, select(firstPushes, F{}, select(secondPushes, second1, F{})));
    if (simd::allLanes(useBlock)) {
      // Every lane solved both points at once (a resting pile's usual case): the one-at-a-time
      // fallback, computed only to be discarded, is skipped.
      setNormal(c, v, p0, block0);
      setNormal(c, v, p1, block1);
    } else {
      setNormal(c, v, p0, select(useBlock, block0, alone(p0, vn0, regime[0])));
      setNormal(
          c, v, p1,
          select(useBlock, block1, alone(p1, v.along(c.nx, c.ny, p1.rnA, p1.rnB), regime[1])));
    }
  }

  // Coulomb friction, bounded by each point's normal impulse.
  const F tx = c.ny, ty = -c.nx;
  for (int k = 0; k < c.points; ++k) {
    PointLanes<N>& p = c.p[k];
    const F vt = v.along(tx, ty, p.rtA, p.rtB);
    const F limit = c.friction * p.normalImpulse;
    const F total = vmin(vmax(p.tangentImpulse - p.tangentMass * vt, -limit), limit);
    const F applied = total - p.tangentImpulse;
    p.tangentImpulse = total;
    v.apply(c, applied, tx, ty, p.rtA, p.rtB);
  }
  scatter<N>(bodies, c.a, v.vAx, v.vAy, v.wA);
  scatter<N>(bodies, c.b, v.vBx, v.vBy, v.wB);
}

// The passes over every batch, inlined into one function per lane count: four lanes in the
// baseline instruction set, eight in a function compiled for AVX2 (chosen at run time).
template <int N>
RC_INLINE void warmStartAll(std::span<Batch<N>> batches, SolverBody* bodies, const float* free) {
  for (Batch<N>& b : batches)
    warmStartBatch(b, bodies, free);
}
template <int N, bool useBias, Separation from>
RC_INLINE void solvePass(std::span<Batch<N>> batches, SolverBody* bodies,
                         const ContactSoftness& soft, bool backward) {
  if (backward) {
    for (std::size_t i = batches.size(); i-- > 0;)
      solveBatch<N, useBias, from>(batches[i], bodies, soft);
  } else {
    for (Batch<N>& b : batches)
      solveBatch<N, useBias, from>(b, bodies, soft);
  }
}
// The pass with bias and the relax pass compiled apart: in the relax pass the regimes are
// constants (nothing soft, no push), and their arithmetic folds away (3% of a pyramid's step).
// The relax pass keeps its separations for the next solve pass.
template <int N>
RC_INLINE void solveAll(std::span<Batch<N>> batches, SolverBody* bodies,
                        const ContactSoftness& soft, bool useBias, bool backward, bool sameMotion) {
  if (!useBias)
    solvePass<N, false, Separation::measureAndKeep>(batches, bodies, soft, backward);
  else if (sameMotion)
    solvePass<N, true, Separation::kept>(batches, bodies, soft, backward);
  else
    solvePass<N, true, Separation::measure>(batches, bodies, soft, backward);
}

void warmStart4(std::span<Batch<4>> batches, SolverBody* bodies, const float* free) {
  warmStartAll(batches, bodies, free);
}
void solve4(std::span<Batch<4>> batches, SolverBody* bodies, const ContactSoftness& soft,
            bool useBias, bool backward, bool sameMotion) {
  solveAll(batches, bodies, soft, useBias, backward, sameMotion);
}

#if RC_HAVE_AVX2_PATHS
[[gnu::target("avx2")]] void warmStart8(std::span<Batch<8>> batches, SolverBody* bodies,
                                        const float* free) {
  warmStartAll(batches, bodies, free);
}
[[gnu::target("avx2")]] void solve8(std::span<Batch<8>> batches, SolverBody* bodies,
                                    const ContactSoftness& soft, bool useBias, bool backward,
                                    bool sameMotion) {
  solveAll(batches, bodies, soft, useBias, backward, sameMotion);
}
#endif

// Lays out a width's batches: each colour's constraints N at a time, then the overflow one at a
// time; every lane's bodies and the batch's point count. A batch with an empty lane is zeroed
// (an empty lane's impulses are then all zero); the others are written whole by writeLane.
template <int N>
void layoutBatches(std::span<const ConstraintBodies> constraints,
                   std::span<const std::int32_t> colour, const int (&perColour)[kColours + 1],
                   int bodyCount, std::vector<Batch<N>>& batches,
                   std::vector<std::int32_t>& constraintLane, std::vector<std::uint8_t>& partial) {
  const std::uint32_t nullBody = static_cast<std::uint32_t>(bodyCount) * kBodyBytes;
  int firstBatch[kColours + 2] = {};
  for (int k = 0; k < kColours; ++k)
    firstBatch[k + 1] = firstBatch[k] + (perColour[k] + N - 1) / N;
  firstBatch[kColours + 1] = firstBatch[kColours] + perColour[kColours];
  const auto batchCount = static_cast<std::size_t>(firstBatch[kColours + 1]);
  batches.resize(batchCount);
  constraintLane.resize(constraints.size());
  int filled[kColours + 1] = {};
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const int c = colour[i];
    const int at = filled[c]++;
    const int lanesPer = c < kColours ? N : 1;
    constraintLane[i] = (firstBatch[c] + at / lanesPer) * N + at % lanesPer;
  }
  // The batches with an empty lane: a colour's last when its count is not a multiple of N,
  // and every overflow batch (one lane taken).
  partial.assign(batchCount, 0);
  for (int k = 0; k < kColours; ++k)
    if (perColour[k] % N != 0) partial[static_cast<std::size_t>(firstBatch[k + 1] - 1)] = 1;
  std::fill(partial.begin() + firstBatch[kColours], partial.end(), 1);
  for (std::size_t bi = 0; bi < batchCount; ++bi)
    if (partial[bi]) batches[bi] = Batch<N>{};
  for (Batch<N>& b : batches) {
    b.points = 1;
    std::fill(std::begin(b.a), std::end(b.a), nullBody);
    std::fill(std::begin(b.b), std::end(b.b), nullBody);
  }
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const ConstraintBodies& cb = constraints[i];
    Batch<N>& b = batches[static_cast<std::size_t>(constraintLane[i] / N)];
    const int l = constraintLane[i] % N;
    b.a[l] = cb.slotA >= 0 ? static_cast<std::uint32_t>(cb.slotA) * kBodyBytes : nullBody;
    b.b[l] = cb.slotB >= 0 ? static_cast<std::uint32_t>(cb.slotB) * kBodyBytes : nullBody;
    b.points = std::max(b.points, cb.pointCount);
  }
}

// The batches with an empty lane back to how layoutBatches left them: zeros but for each lane's
// bodies and the point count. The solve may leave zeros of either sign in an empty lane; a
// layout used again starts from the same bits as a new one.
template <int N>
void clearPartial(std::vector<Batch<N>>& batches, std::span<const std::uint8_t> partial) {
  for (std::size_t bi = 0; bi < batches.size(); ++bi) {
    if (!partial[bi]) continue;
    Batch<N>& b = batches[bi];
    Batch<N> fresh{};
    std::copy(std::begin(b.a), std::end(b.a), std::begin(fresh.a));
    std::copy(std::begin(b.b), std::end(b.b), std::begin(fresh.b));
    fresh.points = b.points;
    b = fresh;
  }
}

// One constraint into its lane: what the caller sets, and a missing second point as zeros
// where the batch has two.
template <int N>
void writeLane(Batch<N>& b, int l, const ContactConstraint& cc) {
  b.invMassA[l] = cc.invMassA;
  b.invIA[l] = cc.invIA;
  b.invMassB[l] = cc.invMassB;
  b.invIB[l] = cc.invIB;
  b.nx[l] = cc.normal.x;
  b.ny[l] = cc.normal.y;
  b.friction[l] = cc.friction;
  b.maxPushout[l] = cc.maxPushout;
  b.two[l] = cc.pointCount == 2 ? -1 : 0;
  for (int k = 0; k < b.points; ++k) {
    PointLanes<N>& p = b.p[k];
    const bool set = k < cc.pointCount;
    const ConstraintPoint& s = cc.points[k];
    p.rAx[l] = set ? s.rA.x : 0.0f;
    p.rAy[l] = set ? s.rA.y : 0.0f;
    p.rBx[l] = set ? s.rB.x : 0.0f;
    p.rBy[l] = set ? s.rB.y : 0.0f;
    p.baseSeparation[l] = set ? s.baseSeparation : 0.0f;
    p.normalImpulse[l] = set ? s.normalImpulse : 0.0f;
    p.tangentImpulse[l] = set ? s.tangentImpulse : 0.0f;
    p.maxNormalImpulse[l] = set ? s.maxNormalImpulse : 0.0f;
    p.relativeVelocity[l] = set ? s.relativeVelocity : 0.0f;
  }
}

// The derived fields of a batch (see ContactSolver::computeMasses). Element by element the same
// operations in the same order as the scalar expressions they replace, so the same bits; a
// missing point's are zero.
template <int N>
RC_INLINE void massesBatch(Batch<N>& c) {
  using F = typename simd::Lanes<N>::F;
  using M = typename simd::Lanes<N>::M;
  const M two = c.two;
  const F m = c.invMassA + c.invMassB;
  const F tx = c.ny, ty = -c.nx;
  F kNormal[2];
  for (int k = 0; k < c.points; ++k) {
    PointLanes<N>& p = c.p[k];
    const M present = k == 0 ? ~M{} : two;
    // rA x n, rA x t, ...; K = mA + mB + iA (rA x n)^2 + iB (rB x n)^2, its inverse where K > 0.
    p.rnA = select(present, p.rAx * c.ny - p.rAy * c.nx, F{});
    p.rnB = select(present, p.rBx * c.ny - p.rBy * c.nx, F{});
    kNormal[k] = m + c.invIA * p.rnA * p.rnA + c.invIB * p.rnB * p.rnB;
    p.normalMass = select(present & (kNormal[k] > 0.0f), 1.0f / kNormal[k], F{});
    p.rtA = select(present, p.rAx * ty - p.rAy * tx, F{});
    p.rtB = select(present, p.rBx * ty - p.rBy * tx, F{});
    const F kTangent = m + c.invIA * p.rtA * p.rtA + c.invIB * p.rtB * p.rtB;
    p.tangentMass = select(present & (kTangent > 0.0f), 1.0f / kTangent, F{});
  }
  if (c.points == 1) {
    c.k11 = c.k12 = c.k22 = c.i11 = c.i12 = c.i22 = F{};
    c.block = M{};
    return;
  }
  // The two points' coupled effective mass, and whether it is well conditioned enough to solve
  // both at once (two points nearly on top of each other make it singular).
  const PointLanes<N>&p0 = c.p[0], &p1 = c.p[1];
  const F k11 = kNormal[0], k22 = kNormal[1];
  const F k12 = m + c.invIA * p0.rnA * p1.rnA + c.invIB * p0.rnB * p1.rnB;
  const F det = k11 * k22 - k12 * k12;
  const M block = two & (k11 * k11 < 1000.0f * det);
  c.k11 = select(two, k11, F{});
  c.k12 = select(two, k12, F{});
  c.k22 = select(two, k22, F{});
  c.i11 = select(block, k22 / det, F{});
  c.i12 = select(block, -k12 / det, F{});
  c.i22 = select(block, k11 / det, F{});
  c.block = block;
}

template <int N>
ConstraintPoint readLane(const Batch<N>& b, int l, int k) {
  const PointLanes<N>& p = b.p[k];
  ConstraintPoint out;
  out.rA = {p.rAx[l], p.rAy[l]};
  out.rB = {p.rBx[l], p.rBy[l]};
  out.rnA = p.rnA[l];
  out.rnB = p.rnB[l];
  out.rtA = p.rtA[l];
  out.rtB = p.rtB[l];
  out.baseSeparation = p.baseSeparation[l];
  out.normalMass = p.normalMass[l];
  out.tangentMass = p.tangentMass[l];
  out.normalImpulse = p.normalImpulse[l];
  out.tangentImpulse = p.tangentImpulse[l];
  out.maxNormalImpulse = p.maxNormalImpulse[l];
  out.relativeVelocity = p.relativeVelocity[l];
  return out;
}

// The stale batches' masses, each batch's flag cleared as it is done.
template <int N>
RC_INLINE void staleMasses(std::span<Batch<N>> batches, std::uint8_t* stale) {
  for (std::size_t i = 0; i < batches.size(); ++i)
    if (stale[i]) {
      massesBatch(batches[i]);
      stale[i] = 0;
    }
}
void masses4(std::span<Batch<4>> batches, std::uint8_t* stale) {
  staleMasses(batches, stale);
}
#if RC_HAVE_AVX2_PATHS
[[gnu::target("avx2")]] void masses8(std::span<Batch<8>> batches, std::uint8_t* stale) {
  staleMasses(batches, stale);
}
#endif

}  // namespace

ContactSoftness ContactSoftness::make(float h, float hertz, float dampingRatio) {
  const float omega = 2.0f * kPi * std::min(hertz, 0.25f / h), zeta = dampingRatio;
  const float a1 = 2.0f * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0f / (1.0f + a2);
  ContactSoftness s;
  s.invH = 1.0f / h;
  s.biasRate = omega / a1;
  s.massScale = a2 * a3;
  s.impulseScale = a3;
  s.invMassScale = 1.0f / s.massScale;
  s.carry = (1.0f - s.impulseScale) * s.invMassScale;
  s.leak = s.impulseScale * s.invMassScale;
  return s;
}

struct ContactSolver::Data {
  int lanes = 4;  // the width prepare() laid out
  std::vector<Batch<4>> batches4;
  std::vector<Batch<8>> batches8;
  std::vector<std::int32_t> constraintLane;  // per constraint: batch * lanes + lane
  std::vector<std::uint32_t> bodyColours;    // per body: the colours its constraints took
  std::vector<std::int32_t> colour;          // per constraint: its colour, kColours: overflow
  std::vector<std::uint8_t> partial;         // per batch: whether it has an empty lane
  // Per batch: a lane set() since its masses were computed (a refreshed lane's are as they were).
  std::vector<std::uint8_t> staleMasses;
  int colours = 0, overflow = 0;
  // What the layout was made for: the same constraints again (a resting pile's, step after
  // step) take the same colours and lanes, so the layout is kept.
  std::vector<ConstraintBodies> laidOut;
  int laidOutBodies = -1;
  std::size_t lastCount = 0;  // constraints in the last layout made
};

namespace {

// Constraint i's batch index (a shift: a division by the width, known only at run time, was a
// divide instruction in refresh(), once a constraint a step).
template <class SolverData>
std::size_t batchOf(const SolverData& d, std::size_t i) {
  const auto lane = static_cast<std::size_t>(d.constraintLane[i]);
  return d.lanes == 8 ? lane >> 3 : lane >> 2;
}

// Constraint i's batch and lane, at the width prepare() laid out: f(batch, lane).
template <class SolverData, class Visit>
decltype(auto) atLane(SolverData& d, std::size_t i, Visit&& f) {
  const auto lane = static_cast<std::size_t>(d.constraintLane[i]);
  if (d.lanes == 8) return f(d.batches8[lane / 8], static_cast<int>(lane % 8));
  return f(d.batches4[lane / 4], static_cast<int>(lane % 4));
}

}  // namespace

ContactSolver::ContactSolver() : data_(std::make_unique<Data>()) {}
ContactSolver::~ContactSolver() = default;

int ContactSolver::colourCount() const {
  return data_->colours;
}
int ContactSolver::overflowCount() const {
  return data_->overflow;
}
std::span<const std::uint32_t> ContactSolver::bodyColours() const {
  return data_->bodyColours;
}
int ContactSolver::laneCount() const {
  return data_->lanes;
}

int ContactSolver::widestLanes() {
  return simd::avx2Enabled() ? 8 : 4;
}

bool ContactSolver::prepare(std::span<const ConstraintBodies> constraints, int bodyCount,
                            int maxLanes) {
  Data& d = *data_;
  // The batches address bodies by 32-bit byte offsets, the null body's included.
  if (static_cast<std::uint64_t>(bodyCount) + 1 > UINT32_MAX / kBodyBytes)
    throw std::length_error("contact solver: more than 2^27 awake bodies");
  const int lanes = maxLanes >= 8 ? widestLanes() : 4;
  // Compared as bytes (every byte of one is a field or zeroed padding): field by field it was
  // two thirds of this function in a resting pile, every step.
  if (lanes == d.lanes && bodyCount == d.laidOutBodies && constraints.size() == d.laidOut.size() &&
      (constraints.empty() || std::memcmp(constraints.data(), d.laidOut.data(),
                                          constraints.size() * sizeof(ConstraintBodies)) == 0)) {
    if (lanes == 8) {
      clearPartial(d.batches8, d.partial);
    } else {
      clearPartial(d.batches4, d.partial);
    }
    return true;
  }
  // Kept for the next step only when the count is the last layout's: a resting pile's stays
  // put, where a moving crowd's changes nearly every step and would pay for a copy never used.
  if (constraints.size() == d.lastCount) {
    d.laidOut.assign(constraints.begin(), constraints.end());
    d.laidOutBodies = bodyCount;
  } else {
    d.laidOut.clear();
    d.laidOutBodies = -1;
  }
  d.lastCount = constraints.size();
  // Greedy colouring in constraint order: each takes the lowest colour neither of its moving
  // bodies has yet.
  const std::size_t n = constraints.size();
  d.bodyColours.assign(static_cast<std::size_t>(bodyCount), 0u);
  d.colour.resize(n);
  int perColour[kColours + 1] = {};
  for (std::size_t i = 0; i < n; ++i) {
    const ConstraintBodies& cc = constraints[i];
    const bool movesA = cc.slotA >= 0 && cc.movesA, movesB = cc.slotB >= 0 && cc.movesB;
    std::uint32_t used = 0;
    if (movesA) used |= d.bodyColours[static_cast<std::size_t>(cc.slotA)];
    if (movesB) used |= d.bodyColours[static_cast<std::size_t>(cc.slotB)];
    const std::uint32_t free = ~used & ((1u << kColours) - 1u);
    int colour = kColours;
    if (free != 0) {
      colour = std::countr_zero(free);
      if (movesA) d.bodyColours[static_cast<std::size_t>(cc.slotA)] |= 1u << colour;
      if (movesB) d.bodyColours[static_cast<std::size_t>(cc.slotB)] |= 1u << colour;
    }
    d.colour[i] = colour;
    ++perColour[colour];
  }
  d.colours = 0;
  for (int k = 0; k < kColours; ++k)
    d.colours += perColour[k] > 0;
  d.overflow = perColour[kColours];

  d.lanes = lanes;
  if (d.lanes == 8) {
    layoutBatches<8>(constraints, d.colour, perColour, bodyCount, d.batches8, d.constraintLane,
                     d.partial);
  } else {
    layoutBatches<4>(constraints, d.colour, perColour, bodyCount, d.batches4, d.constraintLane,
                     d.partial);
  }
  d.staleMasses.assign(d.partial.size(), 1);
  return false;
}

void ContactSolver::set(std::size_t i, const ContactConstraint& constraint) {
  Data& d = *data_;
  d.staleMasses[batchOf(d, i)] = 1;
  atLane(d, i, [&](auto& batch, int lane) { writeLane(batch, lane, constraint); });
}

bool ContactSolver::refresh(std::size_t i, int pointCount, float separation0, float separation1,
                            float maxPushout) {
  Data& d = *data_;
  if (d.partial[batchOf(d, i)]) return false;
  atLane(d, i, [&](auto& b, int l) {
    b.maxPushout[l] = maxPushout;
    b.p[0].baseSeparation[l] = separation0;
    b.p[0].maxNormalImpulse[l] = b.p[0].relativeVelocity[l] = 0.0f;
    if (b.points == 2) {
      auto& p = b.p[1];
      if (pointCount == 2) {
        p.baseSeparation[l] = separation1;
      } else {
        // A missing point's impulses as writeLane leaves them (the solve may leave a zero of
        // the other sign).
        p.normalImpulse[l] = p.tangentImpulse[l] = 0.0f;
      }
      p.maxNormalImpulse[l] = p.relativeVelocity[l] = 0.0f;
    }
  });
  return true;
}

ConstraintPoint ContactSolver::point(std::size_t i, int point) const {
  return atLane(*data_, i,
                [&](const auto& batch, int lane) { return readLane(batch, lane, point); });
}

SolvedPoint ContactSolver::solved(std::size_t i, int point) const {
  return atLane(*data_, i, [&](const auto& batch, int lane) -> SolvedPoint {
    const auto& p = batch.p[point];
    return {p.normalImpulse[lane], p.tangentImpulse[lane], p.maxNormalImpulse[lane],
            p.relativeVelocity[lane]};
  });
}

void ContactSolver::impulses(std::span<float> out) const {
  const Data& d = *data_;
  for (std::size_t i = 0; i < d.constraintLane.size(); ++i) {
    float* o = &out[4 * i];
    atLane(d, i, [&](const auto& b, int l) {
      o[0] = b.p[0].normalImpulse[l];
      o[1] = b.points == 2 ? b.p[1].normalImpulse[l] : 0.0f;
      o[2] = b.p[0].tangentImpulse[l];
      o[3] = b.points == 2 ? b.p[1].tangentImpulse[l] : 0.0f;
    });
  }
}

void ContactSolver::setImpulses(std::span<const float> in) {
  Data& d = *data_;
  for (std::size_t i = 0; i < d.constraintLane.size(); ++i) {
    const float* o = &in[4 * i];
    atLane(d, i, [&](auto& b, int l) {
      b.p[0].normalImpulse[l] = o[0];
      b.p[0].tangentImpulse[l] = o[2];
      if (b.points == 2) {
        b.p[1].normalImpulse[l] = o[1];
        b.p[1].tangentImpulse[l] = o[3];
      }
    });
  }
}

void ContactSolver::computeMasses() {
  Data& d = *data_;
#if RC_HAVE_AVX2_PATHS
  if (d.lanes == 8) {
    masses8(d.batches8, d.staleMasses.data());
    return;
  }
#endif
  masses4(d.batches4, d.staleMasses.data());
}

void ContactSolver::warmStart(std::span<SolverBody> bodies, std::span<const float> free) {
  Data& d = *data_;
  const float* approach = free.empty() ? nullptr : free.data();
#if RC_HAVE_AVX2_PATHS
  if (d.lanes == 8) {
    warmStart8(d.batches8, bodies.data(), approach);
    return;
  }
#endif
  warmStart4(d.batches4, bodies.data(), approach);
}

void ContactSolver::solve(std::span<SolverBody> bodies, const ContactSoftness& soft, bool useBias,
                          bool backward, bool sameMotion) {
  Data& d = *data_;
#if RC_HAVE_AVX2_PATHS
  if (d.lanes == 8) {
    solve8(d.batches8, bodies.data(), soft, useBias, backward, sameMotion);
    return;
  }
#endif
  solve4(d.batches4, bodies.data(), soft, useBias, backward, sameMotion);
}

}  // namespace rc
