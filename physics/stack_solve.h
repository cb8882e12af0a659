// Ricochet physics: the direct solve of a resting pile's contacts.
//
// Gauss-Seidel passes fix a contact's error locally; a pile of N rows carries its load down N
// contacts, and a pass takes out only pi^2 / N^2 of the slowest (whole-pile) error, so a tall
// pile breathes and sways for hundreds of steps before it is still (tests/bench/README.md, "When
// a settled pile sleeps"). After each relax pass this solve takes out what the passes left:
// every touching point's normal and tangent velocity driven to zero at once, exactly, as a
// linear system, then each point's impulse projected back onto its cone (normal impulse not
// below 0, tangent within friction times normal) and those changes applied, as far along as
// lowers the kinetic energy most (never past the whole step: a correction adds no energy).
//
// The system is written in the bodies' velocities (three unknowns a body, coupled where bodies
// touch) rather than in the contact impulses (two a point, coupled through every body they
// share): (M + J^T C^-1 J) e = -J^T C^-1 J v, with C a small compliance (a fraction of each row's
// own effective mass inverse) which makes the statically indeterminate support (a box on two
// boxes) well posed. It is the same correction as the impulse form (Woodbury's identity:
// lambda = -(J M^-1 J^T + C)^-1 J v), on a matrix a third the size whose envelope in order of
// distance from the ground is one row of the pile wide. Factored by Cholesky in double, solved
// on a float copy of the factor (half the bytes; the next correction takes out the rounding).
//
// Only piles get it: bodies joined by contacts to a static, sleeping or kinematic body, in a
// group whose deepest body is at least minDepth contacts away from it (a crowd on the floor is
// one or two deep and pays only the breadth-first pass).
//
// In the step after each relax pass while a pile moves (WorldDef::stackSolveDepth, physics/
// README.md "Piles"): a base-40 pyramid is still from its first steps (asleep at step 32, the top
// 0.8 mm down, against 217 and 52 mm without), with 9 corrections in 4000 substeps with sleeping
// off (tests/bench/README.md, "Session 29").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "physics/contact_solver.h"
#include "physics/math.h"

namespace rc {

class StackSolver {
 public:
  // What the solve needs of one constraint (prepare's order). slotA / slotB as the contact
  // solver's (-1: static or asleep); moves: contacts change that body's velocity.
  struct Constraint {
    std::int32_t slotA = -1, slotB = -1;
    bool movesA = false, movesB = false;
    int pointCount = 0;
    Vec2 normal{};
    float friction = 0;
    Vec2 rA[2]{}, rB[2]{};
    float separation[2]{};
    float normalImpulse[2]{}, tangentImpulse[2]{};  // carried from the last step
    std::uint8_t touching = 0;                      // its rows: bit k, see touchingPoints
  };

  // Which points of a constraint are rows (bit k): overlapping, or within 1 mm apart and a row
  // last step (was: the contact keeps the bits, so that they are part of the world's state).
  // A resting point hovers about zero; without the margin a base-40 pyramid slept at step 36-38
  // with 1-2 mm instead of 32 with 0.5-0.8 mm, and a fixed margin with no memory was worse.
  static std::uint8_t touchingPoints(const float* separation, int pointCount, std::uint8_t was) {
    constexpr float kRowMargin = 0.001f;
    std::uint8_t bits = 0;
    for (int k = 0; k < pointCount; ++k)
      if (separation[k] <= 0.0f || ((was >> k) & 1 && separation[k] <= kRowMargin))
        bits |= static_cast<std::uint8_t>(1 << k);
    return bits;
  }

  // wide: the triangular solves in four-double vectors (AVX2, where the processor has it) or
  // two; the same bits either way.
  explicit StackSolver(bool wide = widestByDefault()) : wide_(wide) {}

  // Finds the piles, once a step after the constraints are prepared: a function of these
  // constraints alone (no history but their touching bits), so that a world restored from a
  // snapshot corrects as the one it was taken from. invMass / invInertia per solver slot. The
  // spans are read again by the first correction after it (the rows and the factor are made
  // only where one is wanted): they must stay as they are until the next build.
  // sameLinks: the caller knows the constraints' slots, moving sides and touching points are
  // last build's (the piles are then last build's too, without comparing them).
  void build(std::span<const Constraint> constraints, std::span<const float> invMass,
             std::span<const float> invInertia, int minDepth, float compliance,
             bool sameLinks = false);
  bool active() const { return unknowns_ > 0; }
  // Whether a correction is wanted after this relax pass: some body of the piles moves faster
  // than speed (m/s) or turns faster than turn (rad/s); once wanted, until every one is under a
  // tenth of both. Not while some body is over 25 times the bounds (that pile is moving, not
  // settling) nor while a pile overlaps deeper than the slop (a correction cannot push apart):
  // the passes take those. The passes alone keep a still pile still (its warm start is
  // the correction's answer): corrected only when it moves, a pile held still costs the passes.
  bool correctionWanted(std::span<const SolverBody> bodies, float speed, float turn);
  // The last answer, which decides the next one's bounds: part of the world's state.
  bool wanted() const { return wanted_; }
  void setWanted(bool wanted) { wanted_ = wanted; }
  // After a relax pass: the correction, applied to the bodies; impulses as
  // ContactSolver::impulses (four a constraint), read and updated in place. The first after a
  // build makes the rows and the factor (every correction of a step shares them).
  void correct(std::span<SolverBody> bodies, std::span<float> impulses);

  // How far along its step the last correction went: 1 unless some point was cut back to its
  // cone and the whole step would not have lowered the kinetic energy most.
  double lastStep() const { return lastStep_; }

  int unknowns() const { return unknowns_; }
  static bool widestByDefault();
  std::size_t factorSize() const { return factor_.size(); }

 private:
  // One touching point of a pile's constraint: its two rows, normal and tangent.
  struct Row {
    std::int32_t constraint;
    int point;
    std::int32_t slotA, slotB;  // for the velocities (-1: none)
    std::int32_t posA, posB;    // in the system (-1: not an unknown)
    Vec2 n;
    float rnA, rnB, rtA, rtB;
    double weightN, weightT;  // 1 / compliance of each row
    float friction;
  };
  bool wide_;
  std::vector<Row> rows_;
  // Where a row's impulses sit in ContactSolver::impulses' layout.
  static std::size_t normalAt(const Row& r) {
    return 4 * static_cast<std::size_t>(r.constraint) + static_cast<std::size_t>(r.point);
  }
  static std::size_t tangentAt(const Row& r) { return normalAt(r) + 2; }
  std::vector<float> invMass_, invInertia_;  // per position in the system (order_)
  std::vector<std::int32_t> order_;          // system position -> solver slot
  std::vector<std::int32_t> first_;          // per unknown: its row's first column in the envelope
  std::vector<std::size_t> start_;           // per unknown: where its row begins in factor_
  std::vector<double> factor_;  // L, row by row over each row's envelope (made in double)
  std::vector<float> factorF_;  // the same in float, for the solves
  int unknowns_ = 0;
  // What build was given, for the rows.
  std::span<const Constraint> constraints_;
  std::span<const float> invMassBySlot_, invInertiaBySlot_;
  float compliance_ = 0;
  bool rowsMade_ = false;  // and factored, since the last build
  bool wanted_ = false;    // the last correctionWanted's answer
  void findPiles(int minDepth);
  void makeRows();
  void factor();
  float deepest_ = 0;  // the piles' deepest overlap this step (<= 0), once deepestKnown_
  bool deepestKnown_ = false;
  float deepestOverlap();
  // A touching constraint's moving slots and rows: what the piles are found from.
  struct Link {
    std::int32_t slotA, slotB;
    std::uint8_t touching;
    bool operator==(const Link&) const = default;
  };
  std::vector<Link> links_, lastLinks_;
  int lastMinDepth_ = -1;
  // Per slot: its local number while building (-1 otherwise); per local number: its slot.
  std::vector<std::int32_t> local_, slot_;
  // Per local number (a body of a touching constraint) while building.
  std::vector<std::int32_t> level_, pos_, queue_, parent_, depth_;
  // A constraint side's local number if it moves and touches, else -1; a local number's position
  // in the system if it is a pile's body, else -1 (both as the last findPiles left them).
  std::int32_t local(std::int32_t slot, bool moves) const {
    return moves ? local_[static_cast<std::size_t>(slot)] : -1;
  }
  std::int32_t position(std::int32_t local) const {
    return local >= 0 ? pos_[static_cast<std::size_t>(local)] : -1;
  }
  std::vector<std::int32_t> adjStart_, adj_;
  std::vector<double> rhs_;
  std::vector<double> vn_, vt_, delta_;  // delta_: per unknown, the step's impulse
  double lastStep_ = 1;
};

}  // namespace rc
