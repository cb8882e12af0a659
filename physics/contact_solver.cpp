#include "physics/contact_solver.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

#include "physics/constants.h"
#include "physics/simd.h"

namespace rc {
namespace {

using simd::F;
using simd::kLanes;
using simd::M;
using simd::select;
using simd::splat;
using simd::vmax;
using simd::vmin;

// Colours a constraint may take; a body with more contacts than this overflows.
constexpr int kColours = 24;

struct PointLanes {
  F rAx, rAy, rBx, rBy, rnA, rnB, rtA, rtB;
  F baseSeparation, normalMass, tangentMass;
  F normalImpulse, tangentImpulse, maxNormalImpulse, relativeVelocity;
};

// Four constraints, structure of arrays. Empty lanes have zero masses and point at the null body.
struct Batch {
  std::int32_t a[kLanes], b[kLanes];
  F invMassA, invIA, invMassB, invIB;
  F nx, ny, friction;
  F k11, k12, k22, i11, i12, i22;
  M block;  // the lane's two points may be solved together
  PointLanes p[2];
  int points;  // the most points of any lane: with 1 (circles), the second point's lanes are
               // skipped
};

// The bodies of one side of a batch, lane by lane (pad: SolverBody::unused, written back as read).
struct BodyLanes {
  F vx, vy, w, pad, dpx, dpy, dqc, dqs;
};

// Rows of a 4x4 matrix into its columns. With the bodies' 16-byte halves as rows, one gather is
// eight vector loads and sixteen shuffles, where building each lane from scalars took 28 loads
// and as many inserts (a third of a batch's solve).
inline void transpose(F& a, F& b, F& c, F& d) {
  const F ab01 = __builtin_shufflevector(a, b, 0, 4, 1, 5);
  const F ab23 = __builtin_shufflevector(a, b, 2, 6, 3, 7);
  const F cd01 = __builtin_shufflevector(c, d, 0, 4, 1, 5);
  const F cd23 = __builtin_shufflevector(c, d, 2, 6, 3, 7);
  a = __builtin_shufflevector(ab01, cd01, 0, 1, 4, 5);
  b = __builtin_shufflevector(ab01, cd01, 2, 3, 6, 7);
  c = __builtin_shufflevector(ab23, cd23, 0, 1, 4, 5);
  d = __builtin_shufflevector(ab23, cd23, 2, 3, 6, 7);
}

// A SolverBody's first half (v, w, unused) or second half (dp, dq) as one vector.
inline F loadHalf(const SolverBody& b, int half) {
  F row;
  std::memcpy(&row, reinterpret_cast<const char*>(&b) + 16 * half, sizeof row);
  return row;
}

template <bool withMotion>
inline BodyLanes gather(const SolverBody* bodies, const std::int32_t (&index)[kLanes]) {
  BodyLanes out;
  out.vx = loadHalf(bodies[index[0]], 0);
  out.vy = loadHalf(bodies[index[1]], 0);
  out.w = loadHalf(bodies[index[2]], 0);
  out.pad = loadHalf(bodies[index[3]], 0);
  transpose(out.vx, out.vy, out.w, out.pad);
  if constexpr (withMotion) {
    out.dpx = loadHalf(bodies[index[0]], 1);
    out.dpy = loadHalf(bodies[index[1]], 1);
    out.dqc = loadHalf(bodies[index[2]], 1);
    out.dqs = loadHalf(bodies[index[3]], 1);
    transpose(out.dpx, out.dpy, out.dqc, out.dqs);
  }
  return out;
}

// Lanes are written in order; lanes sharing a body (the null body, a kinematic body) hold the
// same unchanged velocity, so the order does not matter. Only the first half is written.
inline void scatter(SolverBody* bodies, const std::int32_t (&index)[kLanes], F vx, F vy, F w,
                    F pad) {
  transpose(vx, vy, w, pad);
  const F rows[kLanes] = {vx, vy, w, pad};
  for (int l = 0; l < kLanes; ++l)
    std::memcpy(static_cast<void*>(&bodies[index[l]]), &rows[l], sizeof(F));
}

// Velocities of both sides of a batch, updated by impulses.
struct Velocities {
  F vAx, vAy, wA, vBx, vBy, wB;

  // Impulse `applied` along the direction (dx, dy), with the lever arms rA x d and rB x d:
  // -P on A, +P on B.
  void apply(const Batch& c, F applied, F dx, F dy, F leverA, F leverB) {
    const F px = applied * dx, py = applied * dy;
    vAx -= c.invMassA * px;
    vAy -= c.invMassA * py;
    wA -= c.invIA * applied * leverA;
    vBx += c.invMassB * px;
    vBy += c.invMassB * py;
    wB += c.invIB * applied * leverB;
  }
  // Relative velocity along (dx, dy) at a point with lever arms leverA, leverB.
  F along(F dx, F dy, F leverA, F leverB) const {
    return (vBx - vAx) * dx + (vBy - vAy) * dy + wB * leverB - wA * leverA;
  }
};

void warmStartBatch(Batch& c, SolverBody* bodies) {
  const BodyLanes A = gather<false>(bodies, c.a), B = gather<false>(bodies, c.b);
  Velocities v{A.vx, A.vy, A.w, B.vx, B.vy, B.w};
  const F tx = c.ny, ty = -c.nx;
  // The approach speed restitution reverses: the fastest free-motion normal velocity of the
  // step until the solver first pushes the point, which includes what gravity added before
  // the impact. Later substeps' velocities carry what the solver did to neighbouring contacts
  // and are not an approach: restitution on those fed a cluster of overlapping circles
  // energy, step after step.
  for (int k = 0; k < c.points; ++k) {
    PointLanes& p = c.p[k];
    const F vn = vmin(p.relativeVelocity, v.along(c.nx, c.ny, p.rnA, p.rnB));
    p.relativeVelocity = select(p.maxNormalImpulse > 0.0f, p.relativeVelocity, vn);
  }
  for (int k = 0; k < c.points; ++k) {
    const PointLanes& p = c.p[k];
    const F px = p.normalImpulse * c.nx + p.tangentImpulse * tx;
    const F py = p.normalImpulse * c.ny + p.tangentImpulse * ty;
    v.vAx -= c.invMassA * px;
    v.vAy -= c.invMassA * py;
    v.wA -= c.invIA * (p.normalImpulse * p.rnA + p.tangentImpulse * p.rtA);
    v.vBx += c.invMassB * px;
    v.vBy += c.invMassB * py;
    v.wB += c.invIB * (p.normalImpulse * p.rnB + p.tangentImpulse * p.rtB);
  }
  scatter(bodies, c.a, v.vAx, v.vAy, v.wA, A.pad);
  scatter(bodies, c.b, v.vBx, v.vBy, v.wB, B.pad);
}

void solveBatch(Batch& c, SolverBody* bodies, const ContactSoftness& soft, bool useBias) {
  const BodyLanes A = gather<true>(bodies, c.a), B = gather<true>(bodies, c.b);
  Velocities v{A.vx, A.vy, A.w, B.vx, B.vy, B.w};
  const M biasLanes = useBias ? M{-1, -1, -1, -1} : M{};

  // Each point's regime: speculative (apart: approach no faster than closes the gap this
  // substep), rigid (within the slop: carries its load without pressing in further), or soft
  // (deeper, with the push-out bias; in the relax pass rigid too).
  F bias[2], massScale[2], impulseScale[2];
  M isSoft[2];
  for (int k = 0; k < c.points; ++k) {
    const PointLanes& p = c.p[k];
    // Separation now, from how far the bodies moved and turned since the manifold was made.
    const F rAx = A.dqc * p.rAx - A.dqs * p.rAy, rAy = A.dqs * p.rAx + A.dqc * p.rAy;
    const F rBx = B.dqc * p.rBx - B.dqs * p.rBy, rBy = B.dqs * p.rBx + B.dqc * p.rBy;
    const F dx = (B.dpx - A.dpx) + (rBx - p.rBx) - (rAx - p.rAx);
    const F dy = (B.dpy - A.dpy) + (rBy - p.rBy) - (rAy - p.rAy);
    const F s = dx * c.nx + dy * c.ny + p.baseSeparation;
    const M apart = s > 0.0f;
    isSoft[k] = ~apart & (s <= -kLinearSlop) & biasLanes;
    const F push = vmax(soft.biasRate * s, splat(-soft.maxPushout));
    // Inside the slop, rigid, but pushed out towards half of it at the soft bias rate (the relax
    // pass takes the push's velocity back out): what a stack took in while it settled comes back
    // out, where a rigid contact alone keeps it (base-40 pyramid's top 0.074 -> 0.046 m below
    // its exact height after 1000 steps). The price: a tall stack sleeps later (the base-40
    // pyramid with sleeping on averages 358 us a step over 1000 steps, was 144).
    const F settle = vmin(soft.biasRate * (s + 0.5f * kLinearSlop), F{});
    bias[k] = select(apart, s * soft.invH, select(isSoft[k], push, select(biasLanes, settle, F{})));
    massScale[k] = select(isSoft[k], splat(soft.massScale), splat(1.0f));
    impulseScale[k] = select(isSoft[k], splat(soft.impulseScale), F{});
  }

  auto setNormal = [&](PointLanes& p, F total) {
    const F applied = total - p.normalImpulse;
    p.normalImpulse = total;
    p.maxNormalImpulse = vmax(p.maxNormalImpulse, applied);
    v.apply(c, applied, c.nx, c.ny, p.rnA, p.rnB);
  };
  // One point alone: l + (-m s_m (vn + b) - s_i l), clamped to push only.
  auto alone = [&](const PointLanes& p, F vn, int k) {
    const F impulse =
        -p.normalMass * massScale[k] * (vn + bias[k]) - impulseScale[k] * p.normalImpulse;
    return vmax(p.normalImpulse + impulse, F{});
  };
  PointLanes &p0 = c.p[0], &p1 = c.p[1];
  if (c.points == 1) {
    setNormal(p0, alone(p0, v.along(c.nx, c.ny, p0.rnA, p0.rnB), 0));
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
    const M blockSoft = isSoft[0];
    const F sm = massScale[0];
    const F carry = select(blockSoft, splat(soft.carry), splat(1.0f));
    const F q0 = vn0 + bias[0] - carry * (c.k11 * l0 + c.k12 * l1);
    const F q1 = vn1 + bias[1] - carry * (c.k12 * l0 + c.k22 * l1);
    const F both0 = -sm * (c.i11 * q0 + c.i12 * q1), both1 = -sm * (c.i12 * q0 + c.i22 * q1);
    const F a12 = select(blockSoft, c.k12 * soft.invMassScale, c.k12);
    const M bothPush = (both0 >= 0.0f) & (both1 >= 0.0f);
    const F first0 = -sm * p0.normalMass * q0;
    const M firstPushes = (first0 >= 0.0f) & (a12 * first0 + q1 >= 0.0f);
    const F second1 = -sm * p1.normalMass * q1;
    const M secondPushes = (second1 >= 0.0f) & (a12 * second1 + q0 >= 0.0f);
    const M neither = (q0 >= 0.0f) & (q1 >= 0.0f);
    const M useBlock =
        c.block & (isSoft[0] == isSoft[1]) & (bothPush | firstPushes | secondPushes | neither);
    const F block0 = select(bothPush, both0, select(firstPushes, first0, F{}));
    const F block1 =
        select(bothPush, both1, select(firstPushes, F{}, select(secondPushes, second1, F{})));
    setNormal(p0, select(useBlock, block0, alone(p0, vn0, 0)));
    setNormal(p1, select(useBlock, block1, alone(p1, v.along(c.nx, c.ny, p1.rnA, p1.rnB), 1)));
  }

  // Coulomb friction, bounded by each point's normal impulse.
  const F tx = c.ny, ty = -c.nx;
  for (int k = 0; k < c.points; ++k) {
    PointLanes& p = c.p[k];
    const F vt = v.along(tx, ty, p.rtA, p.rtB);
    const F limit = c.friction * p.normalImpulse;
    const F total = vmin(vmax(p.tangentImpulse - p.tangentMass * vt, -limit), limit);
    const F applied = total - p.tangentImpulse;
    p.tangentImpulse = total;
    v.apply(c, applied, tx, ty, p.rtA, p.rtB);
  }
  scatter(bodies, c.a, v.vAx, v.vAy, v.wA, A.pad);
  scatter(bodies, c.b, v.vBx, v.vBy, v.wB, B.pad);
}

}  // namespace

ContactSoftness ContactSoftness::make(float h, float hertz, float dampingRatio, float maxPushout) {
  const float omega = 2.0f * kPi * std::min(hertz, 0.25f / h), zeta = dampingRatio;
  const float a1 = 2.0f * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0f / (1.0f + a2);
  ContactSoftness s;
  s.invH = 1.0f / h;
  s.biasRate = omega / a1;
  s.massScale = a2 * a3;
  s.impulseScale = a3;
  s.maxPushout = maxPushout;
  s.invMassScale = 1.0f / s.massScale;
  s.carry = (1.0f - s.impulseScale) * s.invMassScale;
  return s;
}

struct ContactSolver::Data {
  std::vector<Batch> batches;
  std::vector<std::int32_t> laneConstraint;  // per batch lane: its constraint, -1 when empty
  std::vector<std::uint32_t> bodyColours;    // per body: the colours its constraints took
  std::vector<std::int32_t> colour;          // per constraint: its colour, kColours: overflow
  int colours = 0, overflow = 0;
};

ContactSolver::ContactSolver() : data_(std::make_unique<Data>()) {}
ContactSolver::~ContactSolver() = default;

int ContactSolver::colourCount() const {
  return data_->colours;
}
int ContactSolver::overflowCount() const {
  return data_->overflow;
}

void ContactSolver::prepare(std::span<const ContactConstraint> constraints, int bodyCount) {
  Data& d = *data_;
  // Greedy colouring in constraint order: each takes the lowest colour neither of its moving
  // bodies has yet.
  const std::size_t n = constraints.size();
  d.bodyColours.assign(static_cast<std::size_t>(bodyCount), 0u);
  d.colour.resize(n);
  int perColour[kColours + 1] = {};
  auto moves = [](std::int32_t slot, float invMass, float invI) {
    return slot >= 0 && (invMass > 0.0f || invI > 0.0f);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const ContactConstraint& cc = constraints[i];
    const bool movesA = moves(cc.slotA, cc.invMassA, cc.invIA);
    const bool movesB = moves(cc.slotB, cc.invMassB, cc.invIB);
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

  // Batches: each colour's constraints four at a time, then the overflow one at a time.
  int firstBatch[kColours + 2] = {};
  for (int k = 0; k < kColours; ++k)
    firstBatch[k + 1] = firstBatch[k] + (perColour[k] + kLanes - 1) / kLanes;
  firstBatch[kColours + 1] = firstBatch[kColours] + perColour[kColours];
  const auto batchCount = static_cast<std::size_t>(firstBatch[kColours + 1]);
  d.batches.resize(batchCount);
  d.laneConstraint.assign(batchCount * kLanes, -1);
  for (Batch& b : d.batches) {
    b = Batch{};
    b.points = 1;
    std::fill(std::begin(b.a), std::end(b.a), bodyCount);
    std::fill(std::begin(b.b), std::end(b.b), bodyCount);
  }
  int filled[kColours + 1] = {};
  for (std::size_t i = 0; i < n; ++i) {
    const int colour = d.colour[i];
    const int at = filled[colour]++;
    const int lanesPer = colour < kColours ? kLanes : 1;
    const auto batch = static_cast<std::size_t>(firstBatch[colour] + at / lanesPer);
    d.laneConstraint[batch * kLanes + static_cast<std::size_t>(at % lanesPer)] =
        static_cast<std::int32_t>(i);
  }
  // Fill the lanes (empty lanes stay zero, so every impulse they compute is zero).
  for (std::size_t bi = 0; bi < batchCount; ++bi) {
    Batch& b = d.batches[bi];
    for (int l = 0; l < kLanes; ++l) {
      const std::int32_t ci = d.laneConstraint[bi * kLanes + static_cast<std::size_t>(l)];
      if (ci < 0) continue;
      const ContactConstraint& cc = constraints[static_cast<std::size_t>(ci)];
      b.a[l] = cc.slotA >= 0 ? cc.slotA : bodyCount;
      b.b[l] = cc.slotB >= 0 ? cc.slotB : bodyCount;
      b.invMassA[l] = cc.invMassA;
      b.invIA[l] = cc.invIA;
      b.invMassB[l] = cc.invMassB;
      b.invIB[l] = cc.invIB;
      b.nx[l] = cc.normal.x;
      b.ny[l] = cc.normal.y;
      b.friction[l] = cc.friction;
      b.k11[l] = cc.k11;
      b.k12[l] = cc.k12;
      b.k22[l] = cc.k22;
      b.i11[l] = cc.i11;
      b.i12[l] = cc.i12;
      b.i22[l] = cc.i22;
      b.block[l] = cc.pointCount == 2 && cc.blockSolve ? -1 : 0;
      b.points = std::max(b.points, cc.pointCount);
      for (int k = 0; k < cc.pointCount; ++k) {
        const ConstraintPoint& s = cc.points[k];
        PointLanes& p = b.p[k];
        p.rAx[l] = s.rA.x;
        p.rAy[l] = s.rA.y;
        p.rBx[l] = s.rB.x;
        p.rBy[l] = s.rB.y;
        p.rnA[l] = s.rnA;
        p.rnB[l] = s.rnB;
        p.rtA[l] = s.rtA;
        p.rtB[l] = s.rtB;
        p.baseSeparation[l] = s.baseSeparation;
        p.normalMass[l] = s.normalMass;
        p.tangentMass[l] = s.tangentMass;
        p.normalImpulse[l] = s.normalImpulse;
        p.tangentImpulse[l] = s.tangentImpulse;
        p.maxNormalImpulse[l] = s.maxNormalImpulse;
        p.relativeVelocity[l] = s.relativeVelocity;
      }
    }
  }
}

void ContactSolver::warmStart(std::span<SolverBody> bodies) {
  for (Batch& b : data_->batches)
    warmStartBatch(b, bodies.data());
}

void ContactSolver::solve(std::span<SolverBody> bodies, const ContactSoftness& soft, bool useBias,
                          bool backward) {
  if (backward) {
    for (std::size_t i = data_->batches.size(); i-- > 0;)
      solveBatch(data_->batches[i], bodies.data(), soft, useBias);
  } else {
    for (Batch& b : data_->batches)
      solveBatch(b, bodies.data(), soft, useBias);
  }
}

void ContactSolver::store(std::span<ContactConstraint> constraints) const {
  const Data& d = *data_;
  for (std::size_t bi = 0; bi < d.batches.size(); ++bi) {
    const Batch& b = d.batches[bi];
    for (int l = 0; l < kLanes; ++l) {
      const std::int32_t ci = d.laneConstraint[bi * kLanes + static_cast<std::size_t>(l)];
      if (ci < 0) continue;
      ContactConstraint& cc = constraints[static_cast<std::size_t>(ci)];
      for (int k = 0; k < cc.pointCount; ++k) {
        ConstraintPoint& s = cc.points[k];
        s.normalImpulse = b.p[k].normalImpulse[l];
        s.tangentImpulse = b.p[k].tangentImpulse[l];
        s.maxNormalImpulse = b.p[k].maxNormalImpulse[l];
        s.relativeVelocity = b.p[k].relativeVelocity[l];
      }
    }
  }
}

}  // namespace rc
