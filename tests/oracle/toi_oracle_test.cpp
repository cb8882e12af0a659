// Time of impact (rc::timeOfImpact) against Box2D 2.4.1's b2TimeOfImpact.
//
// Same geometry on both sides. The b2DistanceProxy members are filled directly from our
// rc::ShapeProxy (rc::makeProxy; rc::testing::Box2DProxy): m_vertices, m_count and m_radius. So
// Box2D's polygon skin (b2_polygonRadius, 1 cm on every polygon built through b2PolygonShape) does
// not apply: sharp polygons and boxes have radius 0 on both sides, rounded ones our radius. A box
// is its 4-point proxy.
//
// Same motion: b2Sweep{localCenter, c0 = c1, c = c2, a0 = a1, a = a2, alpha0 = 0} from our
// rc::Sweep; both interpolate centre and angle linearly in t (Box2D builds the rotation with the
// C library's sinf/cosf, ours with rc::sincos; they differ by ~1e-7).
//
// Same target. Box2D stops when the CORES are target = max(b2_linearSlop, rA + rB -
// 3 b2_linearSlop) apart, within tolerance 0.25 b2_linearSlop. Ours takes a SURFACE separation
// and folds the radii in itself (core target = target + rA + rB) with the same tolerance, so we
// pass target = that core target - (rA + rB): both then stop with the cores the same distance
// apart. (For sharp shapes that is b2_linearSlop, for rounded pairs a slight overlap of the
// surfaces, 3 b2_linearSlop, as Box2D intends.)
//
// Cases: for each of the 10 unordered pairs of {circle, box, polygon (half sharp, half rounded),
// capsule} and each of those against a segment, 100,000 seeded sweeps, half in each order. Both
// bodies translate and rotate: B drifts up to 0.5 m and turns up to 0.5 rad, A starts 1.5 to 5 m
// away heading for a point near B and turns up to 1 rad, so most sweeps hit.
//
// The measure, time of impact within 0.25 x 0.005 m of motion, is taken against the
// exact time of impact: the first t at which the cores come within the target, found with the
// reference distance alone (support/sweeps.h). Every hit of ours must leave the cores 0 to
// 0.25 b2_linearSlop (plus 1e-4 m of float slack) short of the target at its t, a distance the
// shapes still have to close along the normal, and must not come after that first t. Box2D's
// answers cannot be held to one tolerance of ours: its band is +-tol about the target, ours
// [0, tol), so the two differ by up to 2 tol of separation even when both are right. Against
// Box2D the checks are these:
//
// Checks. States are compared as classes: contact at the start (Box2D e_overlapped, or
// e_touching at t = 0; ours overlapped, or hit at 0), hit (t > 0), separated, failed.
//
// Where both hit and the motion meets the surface head-on (the contact point's velocity relative
// to the other shape, v, within 18 degrees of the normal: dot(v, n) >= 0.95 |v|), the issue's
// measure |t_ours - t_b2| * |v|, the distance the contact point travels between the two answers.
// Each engine stops anywhere within its tolerance band (Box2D: the cores within +-tol of the
// target; ours: in [target, target + tol), never past it), so the two answers are up to 2 tol
// apart in separation, 2 tol / 0.95 along the motion; asserted is 2 tol + 1e-4 m, and printed is
// the share within tol (about 95%).
//
// Oblique and grazing motion makes that measure meaningless: the surfaces stay inside the band
// for a long stretch of t, and any t in it is a correct answer. And Box2D's separating-axis root
// finder sometimes misses an early contact of a fast-turning body, or reports one at the end of
// the step. So every case where the classes differ, and every common hit whose times differ by
// more than tol in M |dt| (M: the largest distance any point of either shape can travel per unit
// t), is arbitrated by a reference built from the GJK distance alone (support/sweeps.h,
// firstBelowLipschitz): tFloor, the first time the cores come closer than the band's floor. A hit
// at t is correct when the cores at t are within the band's ceiling and t <= tFloor (it did not
// pass through the band); separated is correct when tFloor never comes; contact at the start when
// the cores start within the ceiling. Our answer must be correct in every arbitrated case; Box2D's
// wrong answers are counted and printed. Ours giving up ("failed", with a safe fraction) is
// bounded apart.
#include <box2d/b2_distance.h>
#include <box2d/b2_time_of_impact.h>
#include <box2d/box2d.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "physics/distance.h"
#include "physics/random.h"
#include "physics/shapes.h"
#include "physics/toi.h"
#include "support/box2d_adapter.h"
#include "support/random_shapes.h"
#include "support/sanitizers.h"
#include "support/sweeps.h"

namespace {

using rc::Vec2;
using rc::testing::Kind;
using rc::testing::SweepCase;

constexpr int kCasesPerPair = rc::testing::casesUnderSanitizers(100000);
constexpr float kTol = 0.25f * b2_linearSlop;
// GJK distances in float at coordinates of a few metres are good to ~1e-5 m.
constexpr float kSlack = 1e-4f;

enum Outcome { kStart, kHit, kSeparated, kFailed, kOutcomeCount };
const char* const kOutcomeNames[kOutcomeCount] = {"start", "hit", "separated", "failed"};

Outcome outcomeOf(const b2TOIOutput& o) {
  switch (o.state) {
    case b2TOIOutput::e_overlapped:
      return kStart;
    case b2TOIOutput::e_touching:
      return o.t == 0.0f ? kStart : kHit;
    case b2TOIOutput::e_separated:
      return kSeparated;
    default:
      return kFailed;
  }
}
Outcome outcomeOf(const rc::ToiOutput& o) {
  switch (o.state) {
    case rc::ToiState::overlapped:
      return kStart;
    case rc::ToiState::hit:
      return o.fraction == 0.0f ? kStart : kHit;
    case rc::ToiState::separated:
      return kSeparated;
    case rc::ToiState::failed:
      break;
  }
  return kFailed;
}

struct PairStats {
  int oursHit = 0, outsideBand = 0, passedThrough = 0;
  double worstGapAbove = -1e30, worstGapBelow = 1e30;
  int bothHit = 0;
  int headOn = 0, headOnWithinTol = 0, headOnBeyond2Tol = 0;
  double worstHeadOn = 0;
  int arbitrated = 0;
  int box2dWrong = 0;  // arbitrated cases where Box2D's answer is not a correct one
  int oursWrong = 0;
  int oursFailed = 0, box2dFailed = 0;
  int table[kOutcomeCount][kOutcomeCount] = {};  // [ours][box2d]
  double seconds = 0;
  std::string firstWrong;
};

// Whether an answer (class, t) is a correct time of impact for the case, by the reference.
struct Arbiter {
  const SweepCase& c;
  float coreTarget;
  float tFloor = -1;  // computed on first use

  float coreDistance(float t) const { return c.coreDistanceAt(t); }
  float floorCrossing() {
    if (tFloor < 0)
      tFloor = rc::testing::firstBelowLipschitz(
          c, [&](float t) { return coreDistance(t); }, coreTarget - kTol - kSlack, 0.25f * kTol);
    return tFloor;
  }
  bool correct(Outcome o, float t) {
    const float ceiling = coreTarget + kTol + kSlack;
    switch (o) {
      case kStart:
        return coreDistance(0) <= ceiling;
      case kHit:
        return coreDistance(t) <= ceiling && t <= floorCrossing();
      case kSeparated:
        return floorCrossing() == 2.0f;
      default:
        return false;  // gave up: never a correct answer, counted apart
    }
  }
};

// The four solid kinds and the segment (static geometry, or a kinematic body's: it may move).
constexpr Kind kKinds[5] = {Kind::circle, Kind::box, Kind::polygon, Kind::capsule, Kind::segment};

PairStats runPair(int ia, int ib) {
  PairStats st;
  const std::uint64_t pairSeed = ib == 4 ? 7100 + static_cast<std::uint64_t>(ia)
                                         : 7000 + static_cast<std::uint64_t>(ia * 4 + ib);
  const Kind* kinds = kKinds;
  auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < kCasesPerPair; ++i) {
    rc::Random rng(pairSeed * 1'000'003ull + static_cast<std::uint64_t>(i));
    bool swap = (i & 1) == 1;
    SweepCase c = rc::testing::randomSweep(rng, kinds[swap ? ib : ia], kinds[swap ? ia : ib]);

    const float totalRadius = c.a.radius + c.b.radius;
    const float coreTarget = std::max(b2_linearSlop, totalRadius - 3.0f * b2_linearSlop);
    rc::ToiOutput ours = rc::timeOfImpact(c.a, c.sa, c.b, c.sb, 1.0f, coreTarget - totalRadius);

    b2TOIInput in;
    rc::testing::Box2DProxy pa, pb;  // in.proxyA/B point into these
    pa.set(c.a);
    pb.set(c.b);
    in.proxyA = pa.proxy;
    in.proxyB = pb.proxy;
    in.sweepA = rc::testing::toB2(c.sa);
    in.sweepB = rc::testing::toB2(c.sb);
    in.tMax = 1.0f;
    b2TOIOutput theirs;
    b2TimeOfImpact(&theirs, &in);

    EXPECT_TRUE(std::isfinite(ours.fraction) && rc::isFinite(ours.point) &&
                rc::isFinite(ours.normal))
        << "pair " << ia << ib << " case " << i;
    Outcome o = outcomeOf(ours), b = outcomeOf(theirs);
    ++st.table[o][b];
    if (o == kHit) {
      // The measure, against the exact time of impact (the first time the cores come
      // within the target, by the reference distance): at our time the cores are 0 to 0.25 slop
      // short of it (a distance the shapes still have to travel towards each other, along the
      // normal), and we never passed it.
      ++st.oursHit;
      const float gap = c.coreDistanceAt(ours.fraction) - coreTarget;
      st.worstGapAbove = std::max(st.worstGapAbove, static_cast<double>(gap));
      st.worstGapBelow = std::min(st.worstGapBelow, static_cast<double>(gap));
      if (gap > kTol + kSlack || gap < -kSlack) ++st.outsideBand;
      const float reached = rc::testing::firstBelowLipschitz(
          c, [&](float t) { return c.coreDistanceAt(t); }, coreTarget - kSlack, 0.25f * kTol);
      if (ours.fraction > reached) ++st.passedThrough;
    }
    st.oursFailed += o == kFailed;
    st.box2dFailed += b == kFailed;
    if (o == b && o != kHit) continue;
    if (o == kHit && b == kHit) {
      ++st.bothHit;
      const double dt = std::fabs(static_cast<double>(ours.fraction) - theirs.t);
      // Velocity of the contact point on A relative to B, per unit t.
      auto pointVelocity = [&](const rc::Sweep& sw) {
        Vec2 center = rc::lerp(sw.c1, sw.c2, ours.fraction);
        return (sw.c2 - sw.c1) + (sw.a2 - sw.a1) * rc::leftPerp(ours.point - center);
      };
      const Vec2 v = pointVelocity(c.sa) - pointVelocity(c.sb);
      const float speed = rc::length(v);
      if (rc::dot(v, ours.normal) >= 0.95f * speed) {
        ++st.headOn;
        const double measure = dt * speed;
        st.headOnWithinTol += measure <= kTol + kSlack;
        st.headOnBeyond2Tol += measure > 2.0f * kTol + kSlack;
        st.worstHeadOn = std::max(st.worstHeadOn, measure);
      }
      const double m =
          std::max(rc::testing::motionBound(c.a, c.sa), rc::testing::motionBound(c.b, c.sb));
      if (dt * m <= kTol + kSlack) continue;
    }
    if (o == kFailed) continue;  // counted and bounded by the caller
    ++st.arbitrated;
    Arbiter arbiter{c, coreTarget};
    if (!arbiter.correct(b, theirs.t)) ++st.box2dWrong;
    if (!arbiter.correct(o, ours.fraction)) {
      ++st.oursWrong;
      if (st.firstWrong.empty())
        st.firstWrong = "case " + std::to_string(i) + ": ours " + kOutcomeNames[o] + " t " +
                        std::to_string(ours.fraction) + ", core distance there - target " +
                        std::to_string(arbiter.coreDistance(ours.fraction) - coreTarget) +
                        ", first below the band's floor at " +
                        std::to_string(arbiter.floorCrossing()) + "; Box2D " + kOutcomeNames[b] +
                        " t " + std::to_string(theirs.t);
    }
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return st;
}

TEST(ToiOracle, AllPairsAgreeWithBox2D) {
  int headOn = 0, headOnWithinTol = 0, arbitrated = 0, box2dWrong = 0;
  for (int ia = 0; ia < 4; ++ia) {
    for (int ib = ia; ib < 5; ++ib) {
      PairStats st = runPair(ia, ib);
      const char* na = rc::testing::kindName(kKinds[ia]);
      const char* nb = rc::testing::kindName(kKinds[ib]);
      std::printf(
          "[ ToiOracle ] %s / %s: %.2f s; %d both hit, %d head-on: %.1f%% within tol of "
          "motion, worst %.2g m; %d arbitrated: Box2D wrong in %d, ours in %d; gave up: "
          "ours %d, Box2D %d; classes differ:",
          na, nb, st.seconds, st.bothHit, st.headOn,
          100.0 * st.headOnWithinTol / std::max(st.headOn, 1), st.worstHeadOn, st.arbitrated,
          st.box2dWrong, st.oursWrong, st.oursFailed, st.box2dFailed);
      for (int o = 0; o < kOutcomeCount; ++o)
        for (int b = 0; b < kOutcomeCount; ++b)
          if (o != b && st.table[o][b] > 0)
            std::printf(" ours %s/b2 %s %d;", kOutcomeNames[o], kOutcomeNames[b], st.table[o][b]);
      std::printf("\n");
      std::printf(
          "[ ToiOracle ] %s / %s: ours hit %d times; at our time the cores are %.2g to %.2g m "
          "from the exact contact (target), %d outside [0, 0.25 slop], %d past it\n",
          na, nb, st.oursHit, st.worstGapBelow, st.worstGapAbove, st.outsideBand, st.passedThrough);
      EXPECT_EQ(st.outsideBand, 0) << na << " / " << nb;
      EXPECT_EQ(st.passedThrough, 0) << na << " / " << nb;
      EXPECT_EQ(st.oursWrong, 0) << na << " / " << nb << ", first: " << st.firstWrong;
      EXPECT_EQ(st.headOnBeyond2Tol, 0) << na << " / " << nb;
      // Conservative advancement gives up (with a safe fraction) only on long grazing sweeps of a
      // fast-turning body: measured 0 to 3 per 100,000 here.
      EXPECT_LE(st.oursFailed, kCasesPerPair / 10000) << na << " / " << nb;
      // A segment has no width: more sweeps pass it by (measured 42-47% hit, 14-17% head-on).
      const bool segment = ib == 4;
      EXPECT_GE(st.bothHit, kCasesPerPair * (segment ? 35 : 50) / 100) << na << " / " << nb;
      EXPECT_GE(st.headOn, kCasesPerPair * (segment ? 12 : 20) / 100) << na << " / " << nb;
      headOn += st.headOn;
      headOnWithinTol += st.headOnWithinTol;
      arbitrated += st.arbitrated;
      box2dWrong += st.box2dWrong;
    }
  }
  std::printf(
      "[ ToiOracle ] all pairs: %.2f%% of %d head-on common hits within 0.25 slop of "
      "motion of Box2D's, all within 2 x; %d cases arbitrated, Box2D wrong in %d, ours in "
      "none\n",
      100.0 * headOnWithinTol / headOn, headOn, arbitrated, box2dWrong);
}

}  // namespace
