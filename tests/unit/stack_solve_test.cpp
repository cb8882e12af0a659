// The direct solve of a pile's contacts (physics/stack_solve.h) alone, on hand-built piles,
// against closed forms: a column's contacts carry the weight above them and stop every box in
// a few corrections (one gives the compliant chain's answer); a box on two boxes loads both alike;
// a sliding box is left to slide and does not spin; a box leaving the ground is not pulled back;
// neighbours in a row are left alone; bodies that cannot turn do not; a row stays one within a
// millimetre; the same constraints give the same bits whatever came before; a correction is wanted
// while the pile moves; no correction adds kinetic energy, whatever the pile's velocities and
// impulses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <vector>

#include "physics/stack_solve.h"

namespace stack_solve_test {

using rc::SolverBody;
using rc::StackSolver;
using rc::Vec2;

constexpr float kG = 10.0f;
constexpr float kH = 1.0f / 240.0f;  // a substep at 60 Hz, 4 substeps
// The compliance the world would solve with (a fraction of each row's effective mass inverse).
// What it lets through (a row's velocity is its compliance times its impulse change) is a few
// parts in a thousand of a substep's fall: where a test needs the answer of a rigid contact it
// compares with that of the same compliant contacts, worked out another way.
constexpr float kStiff = 1e-3f;

// A unit box (1 kg, 1 m square) resting on what is below it (slot -1: the ground) across its
// bottom edge: two points at its corners, separation -2.5 mm.
StackSolver::Constraint onTop(std::int32_t below, std::int32_t above, float friction = 0.6f) {
  StackSolver::Constraint c;
  c.slotA = below;
  c.slotB = above;
  c.movesA = below >= 0;
  c.movesB = true;
  c.pointCount = 2;
  c.normal = {0.0f, 1.0f};
  c.friction = friction;
  for (int k = 0; k < 2; ++k) {
    const float x = k == 0 ? -0.5f : 0.5f;
    c.rA[k] = {x, 0.5f};
    c.rB[k] = {x, -0.5f};
    c.separation[k] = -0.0025f;
  }
  c.touching = StackSolver::touchingPoints(c.separation, c.pointCount, 0);
  return c;
}

struct Pile {
  std::vector<StackSolver::Constraint> constraints;
  std::vector<float> invMass, invInertia;
  std::vector<SolverBody> bodies;  // one more: the null body
  std::vector<float> impulses;

  explicit Pile(int n) : invMass(n, 1.0f), invInertia(n, 6.0f), bodies(n + 1) {}
  void finish() { impulses.assign(4 * constraints.size(), 0.0f); }
  // Every box as after a substep's free fall from rest.
  void falling() {
    for (std::size_t s = 0; s + 1 < bodies.size(); ++s)
      bodies[s].v = {0.0f, -kG * kH};
  }
  // The solve built (piles from one contact deep) and run 30 times, as the substeps would run
  // it: each correction takes out what the compliance let through the last. Whether it found
  // a pile.
  bool settle() {
    StackSolver solver;
    solver.build(constraints, invMass, invInertia, 1, kStiff);
    for (int again = 0; again < 30; ++again)
      solver.correct(bodies, impulses);
    return solver.active();
  }
  float normal(std::size_t c, int k) const { return impulses[4 * c + k]; }
  float tangent(std::size_t c, int k) const { return impulses[4 * c + 2 + k]; }
};

// The column by symmetry as a chain of masses: nothing turns, the two points of a contact carry
// half its impulse each, and a contact's closing speed is its points' compliance times that
// half. Box j's velocity u_j after the correction solves
//   m (u_j - v0) = L_j - L_{j+1},  L_j = -(2 / c_j) (u_j - u_{j-1})  (u_{-1} = 0, L_N = 0),
// a tridiagonal system, solved here by elimination in double.
std::vector<double> chainImpulses(int n, double v0, double compliance) {
  // A point's effective mass inverse: 1 / m and i r_n^2 (r_n = 0.5) for each moving side.
  auto weight = [&](int j) { return 2.0 / (compliance * (j == 0 ? 2.5 : 5.0)); };
  std::vector<double> lower(n), diag(n), upper(n), rhs(n, v0);
  for (int j = 0; j < n; ++j) {
    diag[j] = 1.0 + weight(j) + (j + 1 < n ? weight(j + 1) : 0.0);
    lower[j] = j > 0 ? -weight(j) : 0.0;
    upper[j] = j + 1 < n ? -weight(j + 1) : 0.0;
  }
  for (int j = 1; j < n; ++j) {
    const double f = lower[j] / diag[j - 1];
    diag[j] -= f * upper[j - 1];
    rhs[j] -= f * rhs[j - 1];
  }
  std::vector<double> u(n);
  for (int j = n - 1; j >= 0; --j)
    u[j] = (rhs[j] - (j + 1 < n ? upper[j] * u[j + 1] : 0.0)) / diag[j];
  std::vector<double> impulse(n);
  for (int j = 0; j < n; ++j)
    impulse[j] = -weight(j) * (u[j] - (j > 0 ? u[j - 1] : 0.0));
  return impulse;
}

TEST(StackSolve, AColumnCarriesTheWeightAboveEachContactAndStops) {
  constexpr int kN = 20;
  Pile pile(kN);
  pile.constraints.push_back(onTop(-1, 0));
  for (int j = 1; j < kN; ++j)
    pile.constraints.push_back(onTop(j - 1, j));
  pile.finish();
  pile.falling();
  StackSolver solver;
  solver.build(pile.constraints, pile.invMass, pile.invInertia, 1, kStiff);
  ASSERT_TRUE(solver.active());
  EXPECT_EQ(solver.unknowns(), 3 * kN);
  solver.correct(pile.bodies, pile.impulses);
  const std::vector<double> chain = chainImpulses(kN, -kG * kH, kStiff);
  const float fall = kG * kH;
  for (int j = 0; j < kN; ++j) {
    const float weight = static_cast<float>(kN - j) * fall;
    // The compliant chain's answer, to float rounding (the impulses are sums of about 20
    // terms of the fall's size).
    EXPECT_NEAR(pile.normal(j, 0) + pile.normal(j, 1), chain[j], 1e-5 * weight) << j;
    EXPECT_NEAR(pile.normal(j, 0), pile.normal(j, 1), 1e-5f * weight) << j;
    EXPECT_NEAR(pile.tangent(j, 0) + pile.tangent(j, 1), 0.0f, 1e-6f) << j;
  }
  // What the compliance let through (a quarter of the load at the bottom of 20 boxes: it
  // grows as the square of the height) is what the next correction takes out, as the next
  // substep's would: each leaves a fraction of the last one's residual, so a few give the
  // rigid column's answer, every contact carrying the boxes above it and every box still.
  for (int again = 0; again < 30; ++again)
    solver.correct(pile.bodies, pile.impulses);
  for (int j = 0; j < kN; ++j) {
    const float weight = static_cast<float>(kN - j) * fall;
    EXPECT_NEAR(pile.normal(j, 0) + pile.normal(j, 1), weight, 1e-4f * weight) << j;
  }
  for (int s = 0; s < kN; ++s) {
    EXPECT_NEAR(pile.bodies[s].v.x, 0.0f, 1e-6f) << s;
    EXPECT_NEAR(pile.bodies[s].v.y, 0.0f, 1e-4f * fall) << s;
    EXPECT_NEAR(pile.bodies[s].w, 0.0f, 1e-6f) << s;
  }
}

TEST(StackSolve, ABoxOnTwoBoxesLoadsBothAlike) {
  // Boxes 0 and 1 on the ground at x = -0.5 and 0.5, box 2 on both at x = 0: each upper
  // contact spans half a box, from the lower box's inner corner to its middle.
  Pile pile(3);
  pile.constraints.push_back(onTop(-1, 0));
  pile.constraints.push_back(onTop(-1, 1));
  for (int side = 0; side < 2; ++side) {
    StackSolver::Constraint c = onTop(side, 2);
    const float inner = side == 0 ? 0.5f : -0.5f;  // the lower box's corner under the middle
    c.rA[0] = {0.0f, 0.5f};
    c.rA[1] = {inner, 0.5f};
    c.rB[0] = {-inner, -0.5f};
    c.rB[1] = {0.0f, -0.5f};
    pile.constraints.push_back(c);
  }
  pile.finish();
  pile.falling();
  pile.settle();
  const float one = kG * kH;
  const float left = pile.normal(2, 0) + pile.normal(2, 1);
  const float right = pile.normal(3, 0) + pile.normal(3, 1);
  EXPECT_NEAR(left + right, one, 1e-5f);
  EXPECT_NEAR(left, right, 1e-5f);
  EXPECT_NEAR(pile.normal(0, 0) + pile.normal(0, 1), 1.5f * one, 1e-5f);
  EXPECT_NEAR(pile.normal(1, 0) + pile.normal(1, 1), 1.5f * one, 1e-5f);
  for (int s = 0; s < 3; ++s) {
    EXPECT_NEAR(pile.bodies[s].v.y, 0.0f, 1e-6f) << s;
    EXPECT_NEAR(pile.bodies[s].w, 0.0f, 1e-6f) << s;
  }
}

TEST(StackSolve, ASlidingBoxIsLeftToSlideAndDoesNotSpin) {
  // Two boxes, one on the other, the lower one sliding at 2 m/s, its ground points' friction
  // at the cone last step: the solve holds both up and leaves the sliding friction to the
  // passes. Solved as if it stuck, the ground friction would have been cut back to the cone
  // after the normal impulses had been chosen to balance all of it, and the box would spin.
  constexpr float kMu = 0.5f;
  Pile pile(2);
  pile.constraints.push_back(onTop(-1, 0, kMu));
  pile.constraints.push_back(onTop(0, 1, kMu));
  for (int k = 0; k < 2; ++k) {
    pile.constraints[0].normalImpulse[k] = kG * kH;
    pile.constraints[0].tangentImpulse[k] = -kMu * kG * kH;
  }
  pile.finish();
  pile.falling();
  pile.bodies[0].v.x = 2.0f;
  pile.bodies[1].v.x = 2.0f;
  pile.settle();
  const float fall = kG * kH;
  EXPECT_NEAR(pile.normal(0, 0) + pile.normal(0, 1), 2.0f * fall, 1e-4f * fall);
  EXPECT_NEAR(pile.normal(1, 0) + pile.normal(1, 1), fall, 1e-4f * fall);
  for (int s = 0; s < 2; ++s) {
    EXPECT_NEAR(pile.bodies[s].v.x, 2.0f, 1e-5f) << s;
    EXPECT_NEAR(pile.bodies[s].v.y, 0.0f, 1e-4f * fall) << s;
    EXPECT_NEAR(pile.bodies[s].w, 0.0f, 1e-4f * fall) << s;
  }
}

TEST(StackSolve, ABoxLeavingTheGroundIsNotPulledBack) {
  Pile pile(2);
  pile.constraints.push_back(onTop(-1, 0));
  pile.constraints.push_back(onTop(0, 1));
  pile.finish();
  pile.bodies[0].v = {0.3f, 1.0f};
  pile.bodies[1].v = {0.3f, 1.0f};
  StackSolver solver;
  solver.build(pile.constraints, pile.invMass, pile.invInertia, 1, kStiff);
  solver.correct(pile.bodies, pile.impulses);
  for (float impulse : pile.impulses)
    EXPECT_EQ(impulse, 0.0f);
  for (int s = 0; s < 2; ++s) {
    EXPECT_EQ(pile.bodies[s].v.x, 0.3f);
    EXPECT_EQ(pile.bodies[s].v.y, 1.0f);
    EXPECT_EQ(pile.bodies[s].w, 0.0f);
  }
}

TEST(StackSolve, NeighboursInARowAreLeftToThePasses) {
  // Two boxes on frictionless ground closing on each other sideways at 1 m/s: their contact
  // joins two bodies of one level, so the solve leaves it (and their sideways motion) alone.
  Pile pile(2);
  pile.constraints.push_back(onTop(-1, 0, 0.0f));
  pile.constraints.push_back(onTop(-1, 1, 0.0f));
  StackSolver::Constraint side;
  side.slotA = 0;
  side.slotB = 1;
  side.movesA = side.movesB = true;
  side.pointCount = 2;
  side.normal = {1.0f, 0.0f};
  for (int k = 0; k < 2; ++k) {
    const float y = k == 0 ? -0.5f : 0.5f;
    side.rA[k] = {0.5f, y};
    side.rB[k] = {-0.5f, y};
    side.separation[k] = -0.001f;
    side.touching = StackSolver::touchingPoints(side.separation, side.pointCount, 0);
  }
  pile.constraints.push_back(side);
  // And a box on top of box 0, so that the pile is two deep.
  pile.constraints.push_back(onTop(0, 2, 0.0f));
  pile.invMass.push_back(1.0f);
  pile.invInertia.push_back(6.0f);
  pile.bodies.emplace_back();
  pile.finish();
  pile.falling();
  pile.bodies[0].v.x = 1.0f;
  pile.bodies[1].v.x = -1.0f;
  pile.bodies[2].v.x = 1.0f;
  ASSERT_TRUE(pile.settle());
  EXPECT_EQ(pile.normal(2, 0), 0.0f);
  EXPECT_EQ(pile.normal(2, 1), 0.0f);
  EXPECT_NEAR(pile.bodies[0].v.x, 1.0f, 1e-6f);
  EXPECT_NEAR(pile.bodies[1].v.x, -1.0f, 1e-6f);
  EXPECT_NEAR(pile.bodies[0].v.y, 0.0f, 1e-6f);
  EXPECT_NEAR(pile.bodies[2].v.y, 0.0f, 1e-6f);
}

TEST(StackSolve, ABodyThatCannotTurnDoesNot) {
  Pile pile(2);
  pile.invInertia = {0.0f, 0.0f};  // fixed rotation
  pile.constraints.push_back(onTop(-1, 0));
  StackSolver::Constraint off = onTop(0, 1);  // the upper box half off the lower one's edge
  off.rA[0] = {0.0f, 0.5f};
  off.rB[0] = {-0.5f, -0.5f};
  off.rB[1] = {0.0f, -0.5f};
  pile.constraints.push_back(off);
  pile.finish();
  pile.falling();
  pile.settle();
  EXPECT_EQ(pile.bodies[0].w, 0.0f);
  EXPECT_EQ(pile.bodies[1].w, 0.0f);
  EXPECT_NEAR(pile.bodies[1].v.y, 0.0f, 1e-6f);
  EXPECT_NEAR(pile.normal(1, 0) + pile.normal(1, 1), kG * kH, 1e-5f);
}

TEST(StackSolve, OnlyPilesAtLeastMinDepthDeepAreSolved) {
  Pile pile(2);
  pile.constraints.push_back(onTop(-1, 0));
  pile.constraints.push_back(onTop(0, 1));
  pile.finish();
  StackSolver solver;
  solver.build(pile.constraints, pile.invMass, pile.invInertia, 1, kStiff);
  EXPECT_TRUE(solver.active());  // levels 0 and 1
  solver.build(pile.constraints, pile.invMass, pile.invInertia, 2, kStiff);
  EXPECT_FALSE(solver.active());
  // Nothing resting on the ground: not a pile.
  std::vector<StackSolver::Constraint> flying{onTop(0, 1)};
  solver.build(flying, pile.invMass, pile.invInertia, 0, kStiff);
  EXPECT_FALSE(solver.active());
}

// A point is a row while it overlaps, and one that was stays one up to 1 mm apart (the contact
// keeps the bits from step to step, as the world does).
TEST(StackSolve, ARowStaysOneWhileWithinAMillimetre) {
  const float apart[2] = {-0.0001f, 0.0005f};
  EXPECT_EQ(StackSolver::touchingPoints(apart, 2, 0), 1);   // the second not touching yet
  EXPECT_EQ(StackSolver::touchingPoints(apart, 2, 3), 3);   // a row last step: still one
  EXPECT_EQ(StackSolver::touchingPoints(apart, 1, 3), 1);   // a one-point manifold
  const float lifted[2] = {0.0f, 0.0011f};                  // touching at 0
  EXPECT_EQ(StackSolver::touchingPoints(lifted, 2, 3), 1);  // past the margin
}

// Put the constraints' touching bits as the world does each step, from last step's.
void touch(std::vector<StackSolver::Constraint>& constraints) {
  for (auto& c : constraints)
    c.touching = StackSolver::touchingPoints(c.separation, c.pointCount, c.touching);
}

// A correction is wanted while some body of a pile moves or turns faster than the bounds, and
// once wanted until every one is under a tenth of them, but not while one is over 25 times them;
// bodies outside the piles do not count.
TEST(StackSolve, ACorrectionIsWantedWhileThePileMoves) {
  Pile pile(4);
  for (int j = 0; j < 3; ++j)
    pile.constraints.push_back(onTop(j - 1, j));  // slot 3 touches nothing
  pile.finish();
  StackSolver solver;
  EXPECT_FALSE(solver.correctionWanted(pile.bodies, 0.02f, 0.01f));  // no piles found yet
  solver.build(pile.constraints, pile.invMass, pile.invInertia, 1, kStiff);
  constexpr float kSpeed = 0.02f, kTurn = 0.01f;
  auto wanted = [&] { return solver.correctionWanted(pile.bodies, kSpeed, kTurn); };
  EXPECT_FALSE(wanted());
  // Each row sets one body's velocity and turn, in order: the answer depends on the one before.
  struct Move {
    int body;
    Vec2 v;
    float w;
    bool wanted;
  };
  const Move moves[] = {
      {3, {1.0f, 0.0f}, 0.0f, false},            // not in a pile
      {2, {0.0f, -0.5f * kSpeed}, 0.0f, false},  // under the bound
      {2, {0.0f, -1.5f * kSpeed}, 0.0f, true},   // over it
      {2, {0.0f, -0.5f * kSpeed}, 0.0f, true},   // wanted until all are under a tenth
      {2, {0.0f, -0.11f * kSpeed}, 0.0f, true},
      {2, {0.0f, -0.09f * kSpeed}, 0.0f, false},
      {2, {0.0f, -0.5f * kSpeed}, 0.0f, false},
      {0, {}, 1.5f * kTurn, true},   // turning over the bound
      {0, {}, 0.05f * kTurn, true},  // body 2 still at half the speed bound
      {2, {}, 0.0f, false},
      // A pile with a body over 25 times the bounds is moving, not settling: left to the passes.
      {1, {0.0f, -20.0f * kSpeed}, 0.0f, true},
      {0, {26.0f * kSpeed, 0.0f}, 0.0f, false},
      {0, {}, 26.0f * kTurn, false},
      {0, {}, 0.0f, true},  // body 1 still at 20 times
  };
  for (std::size_t i = 0; i < std::size(moves); ++i) {
    const Move& m = moves[i];
    pile.bodies[static_cast<std::size_t>(m.body)].v = m.v;
    pile.bodies[static_cast<std::size_t>(m.body)].w = m.w;
    EXPECT_EQ(wanted(), m.wanted) << "move " << i;
  }
}

// A pyramid of unit boxes, base `base`, each resting on the two below it across half its bottom
// edge each (two points on each). Slots level by level from the ground.
Pile pyramid(int base, float friction) {
  int n = 0;
  for (int level = 0; level < base; ++level)
    n += base - level;
  Pile pile(n);
  std::vector<int> first;  // each level's first slot
  for (int level = 0, slot = 0; level < base; slot += base - level, ++level)
    first.push_back(slot);
  for (int i = 0; i < base; ++i)
    pile.constraints.push_back(onTop(-1, first[0] + i, friction));
  for (int level = 1; level < base; ++level)
    for (int i = 0; i < base - level; ++i)
      for (int side = 0; side < 2; ++side) {
        StackSolver::Constraint c = onTop(first[level - 1] + i + side, first[level] + i, friction);
        // The half of the upper box's bottom over this lower box: its left half on the left one.
        const float x0 = side == 0 ? -0.5f : 0.0f;
        for (int k = 0; k < 2; ++k) {
          const float x = x0 + 0.5f * static_cast<float>(k);
          c.rB[k] = {x, -0.5f};
          c.rA[k] = {x + (side == 0 ? 0.5f : -0.5f), 0.5f};
        }
        pile.constraints.push_back(c);
      }
  pile.finish();
  return pile;
}

double kineticEnergy(const Pile& pile) {
  double e = 0;
  for (std::size_t s = 0; s + 1 < pile.bodies.size(); ++s) {
    const SolverBody& b = pile.bodies[s];
    e += 0.5 * (b.v.x * b.v.x + b.v.y * b.v.y) / pile.invMass[s] +
         0.5 * b.w * b.w / pile.invInertia[s];
  }
  return e;
}

// The velocity problem a correction works on is the least kinetic energy over impulses in their
// cones; the projection is that minimum where no cone binds, and where one does the step is
// taken only as far as lowers the energy. Drawn here: velocities up to 0.5 m/s and 1 rad/s either
// way and impulses anywhere in their cones, so that many draws cut points back to their cones
// and some steps stop short (both counted: without them this test would not test the cut).
// splitmix64: the same draws on every standard library.
struct Draws {
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  float operator()(float lo, float hi) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<float>(static_cast<double>(z >> 11) * 0x1.0p-53);
  }
};

TEST(StackSolve, NoCorrectionAddsKineticEnergy) {
  Draws uniform;
  constexpr float kFriction = 0.6f;
  int cut = 0, short_ = 0;
  for (int draw = 0; draw < 300; ++draw) {
    Pile pile = pyramid(5, kFriction);
    for (std::size_t s = 0; s + 1 < pile.bodies.size(); ++s) {
      pile.bodies[s].v = {uniform(-0.5f, 0.5f), uniform(-0.5f, 0.5f)};
      pile.bodies[s].w = uniform(-1.0f, 1.0f);
    }
    for (std::size_t c = 0; c < pile.constraints.size(); ++c)
      for (int k = 0; k < 2; ++k) {
        const float n = uniform(0.0f, 0.05f);
        pile.impulses[4 * c + k] = n;
        pile.impulses[4 * c + 2 + k] = uniform(-kFriction * n, kFriction * n);
      }
    const double before = kineticEnergy(pile);
    StackSolver solver;
    solver.build(pile.constraints, pile.invMass, pile.invInertia, 1, kStiff);
    ASSERT_TRUE(solver.active());
    solver.correct(pile.bodies, pile.impulses);
    // Float velocities: the energy to a few float roundings of it.
    EXPECT_LE(kineticEnergy(pile), before * (1 + 1e-6)) << draw;
    bool anyCut = false;
    for (std::size_t c = 0; c < pile.constraints.size(); ++c)
      for (int k = 0; k < 2; ++k) {
        const float n = pile.normal(c, k), t = pile.tangent(c, k);
        EXPECT_GE(n, 0.0f) << draw;
        EXPECT_LE(std::abs(t), kFriction * n * (1 + 1e-5f) + 1e-9f) << draw;
        anyCut = anyCut || n == 0.0f || std::abs(t) >= kFriction * n * (1 - 1e-6f);
      }
    cut += anyCut;
    short_ += solver.lastStep() < 1.0;
  }
  EXPECT_GT(cut, 100);
  EXPECT_GT(short_, 10);
}

// The triangular solves run four doubles a vector where the processor has AVX2, two otherwise:
// the same bits either way (the world's hashes must not depend on the machine).
TEST(StackSolve, BothVectorWidthsGiveTheSameBits) {
  if (!StackSolver::widestByDefault()) GTEST_SKIP() << "no AVX2 here: one width to run";
  Draws uniform;
  Pile narrow = pyramid(12, 0.6f);  // envelopes of up to 36 unknowns: the vector loops run
  for (std::size_t s = 0; s + 1 < narrow.bodies.size(); ++s) {
    narrow.bodies[s].v = {uniform(-0.2f, 0.2f), uniform(-0.2f, 0.2f)};
    narrow.bodies[s].w = uniform(-0.5f, 0.5f);
  }
  Pile wide = narrow;
  StackSolver two(false), four(true);
  two.build(narrow.constraints, narrow.invMass, narrow.invInertia, 1, kStiff);
  four.build(wide.constraints, wide.invMass, wide.invInertia, 1, kStiff);
  ASSERT_TRUE(two.active());
  for (int again = 0; again < 5; ++again) {
    two.correct(narrow.bodies, narrow.impulses);
    four.correct(wide.bodies, wide.impulses);
  }
  bool moved = false;
  for (std::size_t s = 0; s + 1 < narrow.bodies.size(); ++s) {
    EXPECT_EQ(narrow.bodies[s].v.x, wide.bodies[s].v.x) << s;
    EXPECT_EQ(narrow.bodies[s].v.y, wide.bodies[s].v.y) << s;
    EXPECT_EQ(narrow.bodies[s].w, wide.bodies[s].w) << s;
    moved = moved || narrow.bodies[s].v.y != 0.0f;
  }
  EXPECT_TRUE(moved);
  for (std::size_t k = 0; k < narrow.impulses.size(); ++k)
    EXPECT_EQ(narrow.impulses[k], wide.impulses[k]) << k;
}

// The correction is a function of the constraints and bodies it is given, whatever the solver
// did before: a world restored from a snapshot must correct as the one it was taken from. A
// solver taken through other piles, rows that came and went and corrections, then given a pile,
// gives the bits a new solver gives, and again when the same pile comes back (found again for
// nothing: the same links as its last build).
TEST(StackSolve, TheSameConstraintsGiveTheSameBitsWhateverCameBefore) {
  Pile pile(3);
  for (int j = 0; j < 3; ++j)
    pile.constraints.push_back(onTop(j - 1, j));
  pile.finish();
  StackSolver solver;
  Draws uniform;
  auto jostle = [&](Pile& p) {
    for (std::size_t s = 0; s + 1 < p.bodies.size(); ++s) {
      p.bodies[s].v = {uniform(-0.1f, 0.1f), uniform(-0.1f, 0.1f)};
      p.bodies[s].w = uniform(-0.2f, 0.2f);
    }
  };
  for (int step = 0; step < 6; ++step) {  // points lifting and joining, one at a time
    pile.constraints[static_cast<std::size_t>(step % 3)].separation[step % 2] =
        step % 2 == 0 ? 0.01f : -0.001f;
    touch(pile.constraints);
    jostle(pile);
    solver.build(pile.constraints, pile.invMass, pile.invInertia, 1, kStiff);
    for (int sub = 0; sub < 2; ++sub)
      solver.correct(pile.bodies, pile.impulses);
  }
  Pile other = pyramid(4, 0.6f);  // another pile between
  jostle(other);
  solver.build(other.constraints, other.invMass, other.invInertia, 1, kStiff);
  solver.correct(other.bodies, other.impulses);
  for (int again = 0; again < 2; ++again) {
    solver.build(pile.constraints, pile.invMass, pile.invInertia, 1, kStiff);
    jostle(pile);
    Pile fresh = pile;
    solver.correct(pile.bodies, pile.impulses);
    StackSolver none;
    none.build(fresh.constraints, fresh.invMass, fresh.invInertia, 1, kStiff);
    none.correct(fresh.bodies, fresh.impulses);
    ASSERT_TRUE(none.active());
    for (std::size_t k = 0; k < pile.impulses.size(); ++k)
      EXPECT_EQ(pile.impulses[k], fresh.impulses[k]) << again << " " << k;
    for (std::size_t b = 0; b < pile.bodies.size(); ++b) {
      EXPECT_EQ(pile.bodies[b].v.x, fresh.bodies[b].v.x) << again << " " << b;
      EXPECT_EQ(pile.bodies[b].v.y, fresh.bodies[b].v.y) << again << " " << b;
      EXPECT_EQ(pile.bodies[b].w, fresh.bodies[b].w) << again << " " << b;
    }
  }
}

}  // namespace stack_solve_test
