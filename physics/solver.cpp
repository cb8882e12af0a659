// The solve: contact constraints prepared, then substeps of free motion, warm start, soft
// contact solve, position update and relax; restitution; impulses stored for the next step.
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

#include "physics/bytes.h"
#include "physics/constants.h"
#include "physics/union_find.h"
#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

namespace {

// Whether any value's magnitude is beyond the limit (not negative), or is NaN or infinite: on
// the magnitude's bits, as integers, NaN and infinity sort above every finite float. Branch-free
// and on 32-bit signed arithmetic alone (limit - m goes negative exactly when m > limit, both
// being below 2^31), which every vector instruction set has: a pass over every awake velocity
// costs a few instructions per four values.
bool anyBeyond(std::span<const float> values, float limit) {
  const std::int32_t lim = std::bit_cast<std::int32_t>(limit);
  std::int32_t over = 0;
  for (const float v : values)
    over |= lim - (std::bit_cast<std::int32_t>(v) & 0x7FFFFFFF);
  return over < 0;
}

// Impulse P at one contact point: -P on A, +P on B.
template <class Constraint, class Point>
void applyImpulse(const Constraint& cc, const Point& p, Vec2 P, Vec2& vA, float& wA, Vec2& vB,
                  float& wB) {
  vA -= cc.invMassA * P;
  wA -= cc.invIA * cross(p.rA, P);
  vB += cc.invMassB * P;
  wB += cc.invIB * cross(p.rB, P);
}

}  // namespace

void WorldState::accelerations(std::span<const double> q, std::span<const float> v, double t,
                               std::span<float> a) {
  // The step's constant part (gathered in solve(): gravity, forces, torques), then the fields.
  std::copy_n(baseAccel_.begin(), 3 * static_cast<std::size_t>(awakeCount_), a.begin());
  if (!fields_.empty()) {
    ForceStage stage(*this, q, v, a, t);
    for (ForceField& field : fields_)
      field(stage);
  }
}

// The solve, as its stages. A substep moves every awake body as if nothing touched it (free
// motion), then the contacts change the velocities (warm start, solve with the soft push-out
// bias), the positions follow the change, and a relax pass without bias takes out the push-out's
// velocity. Restitution is applied once, after the last substep.
void WorldState::solve(float dt) {
  prepareContacts();
  if (awakeCount_ == 0) {
    // Nothing to solve; force fields still look once, so that one can wake what it pushes.
    if (!fields_.empty()) accelerations({}, {}, time_, {});
    return;
  }
  prepareBodies(dt);
  const float h = dt / static_cast<float>(def_.substeps);
  const ContactSoftness soft =
      ContactSoftness::make(h, def_.contactHertz, def_.contactDampingRatio);
  for (int sub = 0; sub < def_.substeps; ++sub) {
    integrateFreeMotion(sub, h);
    warmStart();
    // Symmetric Gauss-Seidel: the relax pass sweeps the colours the other way from the solve
    // pass, and each substep starts the way the last one ended.
    const bool backward = sub % 2 == 1;
    // From the second substep on, the bodies are where the last relax pass measured them.
    contactSolver_.solve(solverBodies_, soft, true, backward, sub > 0);
    integratePositions(h);
    contactSolver_.solve(solverBodies_, soft, false, !backward);  // relax
    if (stackSolver_.active()) correctPiles();
    if (!tracked_.empty()) measureContactWork();
    storeVelocities();
  }
  storeImpulses();
  applyRestitution();
}

// What the stack solve finds the piles from, for a prepared constraint: its bodies and their
// masses (a kept lane's are last step's), then its points' separations (pileTouching), and its
// points' rows kept in its contact for the next step. The rest of what the rows need waits for a
// correction (pileDetails): most steps of a still pile have none.
[[gnu::always_inline]] inline void WorldState::pileConstraint(std::size_t i,
                                                              const ContactConstraint& cc) {
  StackSolver::Constraint& sc = stackConstraints_[i];
  sc.slotA = cc.slotA;
  sc.slotB = cc.slotB;
  sc.movesA = constraintBodies_[i].movesA && cc.slotA >= 0;
  sc.movesB = constraintBodies_[i].movesB && cc.slotB >= 0;
  sc.pointCount = cc.pointCount;
  if (cc.slotA >= 0) {
    slotInvMass_[static_cast<std::size_t>(cc.slotA)] = cc.invMassA;
    slotInvInertia_[static_cast<std::size_t>(cc.slotA)] = cc.invIA;
  }
  if (cc.slotB >= 0) {
    slotInvMass_[static_cast<std::size_t>(cc.slotB)] = cc.invMassB;
    slotInvInertia_[static_cast<std::size_t>(cc.slotB)] = cc.invIB;
  }
}

[[gnu::always_inline]] inline void WorldState::pileTouching(std::size_t i, Contact& c) {
  StackSolver::Constraint& sc = stackConstraints_[i];
  for (int k = 0; k < sc.pointCount; ++k)
    sc.separation[k] = c.manifold.points[k].separation;
  const std::uint8_t before = sc.touching;  // last step's, of this constraint if the layout is
  sc.touching =
      StackSolver::touchingPoints(sc.separation, sc.pointCount, pileLayoutKept_ ? c.stackRows : 0);
  c.stackRows = sc.touching;
  pileTouchChanged_ = pileTouchChanged_ || sc.touching != before;
}

// Whether the constraints' layout is the one before (pileLayoutKept_, for pileConstraint).
void WorldState::advancePileLayout(bool sameAsLast) {
  // A point stays a row within 1 mm apart only while the constraints are those of the steps
  // before: kept through changes (a point that lifted off as a pile was let go held 1 mm short
  // as a row), a base-40 pyramid slept at step 75-81 with 5-9 mm instead of 32 with 0.5-0.8
  // mm; without the margin, at 36-38 with 1-2 mm, and a 1:1000 stack at 32 substeps drifted 2
  // mm and tilted (tests/stress, mass-ratio). "The same" as the contact solver keeps its
  // layout: as last step's, and after a change of count only from the second step of the new
  // count (kept from the first, base 40 slept at 84-213). Its hash and count, not the contact
  // solver's cache, so that a restored world decides as the one it was taken from.
  // Where the contact solver kept its layout, these constraints are byte for byte those of the
  // last call (a restored world's solver starts with none kept), whose hash pileLayout_ holds:
  // hashing them again was 1% of a resting pile's step.
  std::uint64_t layout = pileLayout_;
  if (!sameAsLast) {
    layout = kFnvOffset ^ static_cast<std::uint64_t>(awakeCount_);
    for (const ConstraintBodies& cb : constraintBodies_) {
      const std::uint64_t word = static_cast<std::uint64_t>(static_cast<std::uint32_t>(cb.slotA)) |
                                 static_cast<std::uint64_t>(static_cast<std::uint32_t>(cb.slotB))
                                     << 32;
      layout = (layout ^ word) * kFnvPrime;
      layout =
          (layout ^ static_cast<std::uint64_t>(cb.pointCount | cb.movesA << 2 | cb.movesB << 3)) *
          kFnvPrime;
    }
  }
  const auto count = static_cast<std::uint32_t>(constraintBodies_.size());
  pileLayoutKept_ = pileLayoutValid_ && layout == pileLayout_;
  if (!pileLayoutKept_) {
    pileLayoutValid_ = count == pileLayoutCount_;
    pileLayout_ = layout;
    pileLayoutCount_ = count;
  }
}

// One constraint per touching contact with an awake side, anchors from the centres of mass. The
// solver colours them first (it needs only their bodies), then each constraint is prepared
// straight into its lane.
void WorldState::prepareContacts() {
  bouncy_.clear();
  bouncyIndex_.clear();
  tracked_.clear();
  profile_.colours = profile_.overflow = 0;
  profile_.layoutKept = false;
  profile_.lanesKept = 0;
  profile_.pileBodies = profile_.pileCorrections = 0;
  // The last step's overlap counts back to zero (only the slots it counted: clearing every
  // slot each step was a memset of the awake bodies).
  for (const std::int32_t slot : overlapping_)
    slotOverlaps_[static_cast<std::size_t>(slot)] = 0;
  overlapping_.clear();
  if (awakeCount_ == 0) {
    constraintSources_.clear();
    constraintBodies_.clear();
    lanesCurrent_ = false;  // the contacts may change before the solver next sees them
    return;
  }
  // shared: a body with two contacts overlapping past the slop.
  bool shared = false;
  // Written by index into lists as long as the contacts that might need them, cut to the count
  // after (a push_back each was a capacity test and a size store, an eighth of this loop), and
  // from local copies of the arrays' addresses: the byte stores below may alias any member, and
  // each vector's start was loaded again after them.
  const std::vector<std::int32_t>& listed = awakeContactList();
  constraintSources_.resize(listed.size());
  constraintBodies_.resize(listed.size());
  ConstraintSource* const sources = constraintSources_.data();
  ConstraintBodies* const sourceBodies = constraintBodies_.data();
  Contact* const contacts = contacts_.data();
  const ShapeRecord* const shapes = shapes_.data();
  const Body* const bodies = bodies_.data();
  const std::int32_t awakeSlots = awakeCount_;
  auto awakeSlot = [awakeSlots](const Body& body) {
    return body.slot >= 0 && body.slot < awakeSlots ? body.slot : -1;
  };
  std::size_t made = 0;
  for (const std::int32_t index : listed) {
    const auto ci = static_cast<std::size_t>(index);
    const Contact& c = contacts[ci];
    if (!c.touching) continue;
    const std::int32_t bodyA = shapes[static_cast<std::size_t>(c.shapeA)].body;
    const std::int32_t bodyB = shapes[static_cast<std::size_t>(c.shapeB)].body;
    const Body& a = bodies[static_cast<std::size_t>(bodyA)];
    const Body& b = bodies[static_cast<std::size_t>(bodyB)];
    const std::int32_t slotA = awakeSlot(a), slotB = awakeSlot(b);
    if (slotA < 0 && slotB < 0) continue;  // asleep against asleep or static
    const bool movesA = a.invMass > 0.0f || a.invInertia > 0.0f;
    const bool movesB = b.invMass > 0.0f || b.invInertia > 0.0f;
    sources[made] = {static_cast<std::int32_t>(ci), bodyA, bodyB};
    sourceBodies[made] = {slotA, slotB, c.manifold.pointCount, movesA, movesB};
    ++made;
    // The push-out speed is a body's, not each contact's: a body overlapping k others past the
    // slop is pushed out of each at 1/k of it, so that together they push it no faster than the
    // push-out speed (what the relax pass cannot take back of a push stays in the body as
    // speed).
    const float deepest = c.manifold.pointCount == 2 ? std::min(c.manifold.points[0].separation,
                                                                c.manifold.points[1].separation)
                                                     : c.manifold.points[0].separation;
    if (deepest < -kLinearSlop) {
      if (slotOverlaps_.size() < static_cast<std::size_t>(awakeCount_))
        slotOverlaps_.resize(static_cast<std::size_t>(awakeCount_), 0);
      for (const std::int32_t slot : {movesA ? slotA : -1, movesB ? slotB : -1}) {
        if (slot < 0) continue;
        std::int32_t& count = slotOverlaps_[static_cast<std::size_t>(slot)];
        if (count == 0) overlapping_.push_back(slot);
        shared = ++count > 1 || shared;
      }
    }
  }
  constraintSources_.resize(made);
  constraintBodies_.resize(made);
  profile_.layoutKept = contactSolver_.prepare(constraintBodies_, awakeCount_, def_.maxSolverLanes);
  profile_.colours = contactSolver_.colourCount();
  profile_.overflow = contactSolver_.overflowCount();
  profile_.lanes = contactSolver_.laneCount();
  // A kept layout's lanes hold last step's constraints: a recycled manifold's is written again
  // only where it changes (below).
  const bool lanesKept = profile_.layoutKept && lanesCurrent_;
  laneContacts_.resize(constraintSources_.size());

  const bool piles = def_.stackSolveDepth > 0;
  if (piles) {
    advancePileLayout(profile_.layoutKept);
    pileTouchChanged_ = false;  // pileConstraint sets it
    stackConstraints_.resize(constraintSources_.size());
    slotInvMass_.resize(static_cast<std::size_t>(awakeCount_));
    slotInvInertia_.resize(static_cast<std::size_t>(awakeCount_));
  }
  // (The lists' addresses, still those above: cutting them to `made` moved nothing. The lanes'
  // contacts and the push-out speed in registers too.)
  std::int32_t* const laneContacts = laneContacts_.data();
  const float pushout = def_.maxPushoutSpeed;
  for (std::size_t i = 0; i < made; ++i) {
    const ConstraintSource& source = sources[i];
    Contact& c = contacts[static_cast<std::size_t>(source.contact)];
    const std::int32_t slotA = sourceBodies[i].slotA, slotB = sourceBodies[i].slotB;
    // Its share of the push-out speed (see above).
    float maxPushout = pushout;
    if (shared) {
      const std::int32_t kA = slotA >= 0 ? slotOverlaps_[static_cast<std::size_t>(slotA)] : 0;
      const std::int32_t kB = slotB >= 0 ? slotOverlaps_[static_cast<std::size_t>(slotB)] : 0;
      const std::int32_t shares = std::max(kA, kB);
      if (shares > 1) maxPushout /= static_cast<float>(shares);
    }
    const Manifold& m = c.manifold;
    // A recycled manifold is the made one carried along: its normal and lever arms are those it
    // was made with (each body has turned by less than recycle's bound since), so a resting
    // contact's constraint is the same step after step but for its separations and push-out
    // speed, and its lane, if it still holds it, needs only those; its pile constraint only its
    // separations (its slots and their masses are last step's). A bouncy one is copied whole
    // for restitution.
    if (lanesKept && laneContacts[i] == source.contact && c.recycled && c.restitution == 0.0f &&
        contactSolver_.refresh(i, m.pointCount, m.points[0].separation,
                               m.pointCount == 2 ? m.points[1].separation : 0.0f, maxPushout)) {
      if (piles) pileTouching(i, c);
      ++profile_.lanesKept;
      continue;
    }
    const Body& a = bodies_[static_cast<std::size_t>(source.bodyA)];
    const Body& b = bodies_[static_cast<std::size_t>(source.bodyB)];
    ContactConstraint cc;
    cc.contact = source.contact;
    cc.slotA = slotA;
    cc.slotB = slotB;
    // A sleeping body stays put for this step: it counts as static (and the solver's null body,
    // which static sides share, must never be moved).
    cc.invMassA = slotA >= 0 ? a.invMass : 0.0f;
    cc.invIA = slotA >= 0 ? a.invInertia : 0.0f;
    cc.invMassB = slotB >= 0 ? b.invMass : 0.0f;
    cc.invIB = slotB >= 0 ? b.invInertia : 0.0f;
    cc.normal = m.normal;
    cc.friction = c.friction;
    cc.restitution = c.restitution;
    cc.maxPushout = maxPushout;
    cc.pointCount = m.pointCount;
    // The lever arms from the centres of mass as the manifold was made.
    const Vec2 offsetA = rotate(c.madeQA, a.localCenter), offsetB = rotate(c.madeQB, b.localCenter);
    for (int k = 0; k < cc.pointCount; ++k) {
      const ManifoldPoint& mp = m.points[k];
      ConstraintPoint& p = cc.points[k];
      p.rA = mp.anchorA - offsetA;
      p.rB = mp.anchorB - offsetB;
      p.baseSeparation = mp.separation;
      p.normalImpulse = c.normalImpulse[k];
      p.tangentImpulse = c.tangentImpulse[k];
      // Not pushed yet: the first warm start sets every point's approach speed from the
      // substep's free motion (restitution reads nothing else; without it nothing reads it).
      p.maxNormalImpulse = 0.0f;
      p.relativeVelocity = 0.0f;
    }
    contactSolver_.set(i, cc);
    laneContacts[i] = source.contact;
    if (piles) {
      pileConstraint(i, cc);
      pileTouching(i, c);
    }
    if (cc.restitution != 0.0f) {
      bouncy_.push_back(cc);
      bouncyIndex_.push_back(static_cast<std::int32_t>(i));
    }
  }
  contactSolver_.computeMasses();
  lanesCurrent_ = true;
  if (!bouncy_.empty()) prepareBounceGroups();
  if (piles) {
    // The solve's compliance: a thousandth of each row's own effective mass inverse, enough to
    // make a box on two boxes well posed (stack_solve.h).
    constexpr float kPileCompliance = 0.001f;
    // The contact solver's kept layout is last step's slots and moving sides: with the same
    // touching points, the piles' links are last step's.
    stackSolver_.build(stackConstraints_, slotInvMass_, slotInvInertia_, def_.stackSolveDepth,
                       kPileCompliance, profile_.layoutKept && !pileTouchChanged_);
    pileDetails_ = false;
    profile_.pileBodies = stackSolver_.unknowns() / 3;
  }
}

// After a relax pass: the piles' contacts solved exactly while a pile moves (StackSolver), the
// impulses exchanged with the contact solver only then.
void WorldState::correctPiles() {
  // 0.4 of the sleep tolerances: above it the passes are left to hold the pile for hundreds of
  // steps (tests/bench/README.md, "Session 29"); a pile corrected below it is still (base 40:
  // 9 corrections in 4000 substeps).
  constexpr float kPileBound = 0.4f;
  if (!stackSolver_.correctionWanted(solverBodies_, kPileBound * def_.linearSleepTolerance,
                                     kPileBound * def_.angularSleepTolerance))
    return;
  if (!pileDetails_) pileDetails();
  stackImpulses_.resize(4 * stackConstraints_.size());
  contactSolver_.impulses(stackImpulses_);
  stackSolver_.correct(solverBodies_, stackImpulses_);
  contactSolver_.setImpulses(stackImpulses_);
  ++profile_.pileCorrections;
}

// The rest of each constraint as prepared, for the rows of the step's first correction: its
// normal, friction and lever arms, and its carried impulses (the contact's until the step's end).
void WorldState::pileDetails() {
  pileDetails_ = true;
  for (std::size_t i = 0; i < stackConstraints_.size(); ++i) {
    StackSolver::Constraint& sc = stackConstraints_[i];
    const Contact& c = contacts_[static_cast<std::size_t>(constraintSources_[i].contact)];
    sc.normal = c.manifold.normal;
    sc.friction = c.friction;
    for (int k = 0; k < sc.pointCount; ++k) {
      const ConstraintPoint p = contactSolver_.point(i, k);
      sc.rA[k] = p.rA;
      sc.rB[k] = p.rB;
      sc.normalImpulse[k] = c.normalImpulse[k];
      sc.tangentImpulse[k] = c.tangentImpulse[k];
    }
  }
}

// The groups restitution's energy budget is kept by: awake bodies joined by constraints
// between two of them that contacts move (union-find over slots), those with a bouncy
// constraint tracked. A lone constraint with one point (its bodies touch nothing else) is not:
// Newton's law gives its pair e^2 of its approach's energy, no more. A kinematic body does
// work on what it touches that no contact measures, so a group touching one is marked driven
// (see limitBounceEnergy).
void WorldState::prepareBounceGroups() {
  bounceGroups_.clear();
  // A side the contacts move (a dynamic body awake), else -1.
  auto movingA = [](const ConstraintBodies& cb) { return cb.movesA ? cb.slotA : -1; };
  auto movingB = [](const ConstraintBodies& cb) { return cb.movesB ? cb.slotB : -1; };
  // Whether a side is the only constraint on its slot: the colouring already counted them
  // (a slot moved by k constraints took k colours), unless some overflowed; then they are
  // counted here, 2 standing for more.
  const std::span<const std::uint32_t> colours = contactSolver_.bodyColours();
  const bool counted = contactSolver_.overflowCount() > 0;
  if (counted) {
    slotDegree_.assign(static_cast<std::size_t>(awakeCount_), 0);
    for (const ConstraintBodies& cb : constraintBodies_) {
      for (const std::int32_t slot : {movingA(cb), movingB(cb)}) {
        if (slot < 0) continue;
        std::uint8_t& count = slotDegree_[static_cast<std::size_t>(slot)];
        count = count < 2 ? static_cast<std::uint8_t>(count + 1) : count;
      }
    }
  }
  auto single = [&](std::int32_t slot) {
    if (slot < 0) return true;
    const auto s = static_cast<std::size_t>(slot);
    // (One bit set, without std::has_single_bit: the baseline x86-64 has no POPCNT, and it
    // became a library call.)
    const std::uint32_t bits = colours[s];
    return counted ? slotDegree_[s] == 1 : bits != 0 && (bits & (bits - 1)) == 0;
  };
  // Per constraint: -2 if lone (or moving nothing), else -1, then its root slot, then its
  // group.
  // The constraints that are not lone, listed once: the passes below walk only them (in a
  // sparse scene most contacts are lone pairs).
  constraintGroup_.resize(constraintBodies_.size());
  grouped_.clear();
  for (std::size_t i = 0; i < constraintBodies_.size(); ++i) {
    const ConstraintBodies& cb = constraintBodies_[i];
    const bool moves = movingA(cb) >= 0 || movingB(cb) >= 0;
    const bool lone = cb.pointCount == 1 && single(movingA(cb)) && single(movingB(cb));
    constraintGroup_[i] = moves && !lone ? -1 : -2;
    if (moves && !lone) grouped_.push_back(static_cast<std::int32_t>(i));
  }
  bool any = false;
  for (const std::int32_t i : bouncyIndex_)
    any = any || constraintGroup_[static_cast<std::size_t>(i)] == -1;
  if (!any) return;
  // Union-find over the slots of the constraints that are not lone (only those are read).
  slotParent_.resize(static_cast<std::size_t>(awakeCount_));
  for (const std::int32_t i : grouped_) {
    const ConstraintBodies& cb = constraintBodies_[static_cast<std::size_t>(i)];
    for (const std::int32_t slot : {movingA(cb), movingB(cb)})
      if (slot >= 0) slotParent_[static_cast<std::size_t>(slot)] = slot;
  }
  auto root = [&](std::int32_t x) { return unionFindRoot(slotParent_, x); };
  for (const std::int32_t i : grouped_) {
    const ConstraintBodies& cb = constraintBodies_[static_cast<std::size_t>(i)];
    if (movingA(cb) >= 0 && movingB(cb) >= 0)
      slotParent_[static_cast<std::size_t>(root(cb.slotA))] = root(cb.slotB);
  }
  rootGroup_.resize(static_cast<std::size_t>(awakeCount_));
  for (const std::int32_t i : grouped_) {
    const ConstraintBodies& cb = constraintBodies_[static_cast<std::size_t>(i)];
    const std::int32_t r = root(movingA(cb) >= 0 ? movingA(cb) : movingB(cb));
    constraintGroup_[static_cast<std::size_t>(i)] = r;
    rootGroup_[static_cast<std::size_t>(r)] = -1;
  }
  for (std::size_t j = 0; j < bouncy_.size(); ++j) {
    const std::int32_t r = constraintGroup_[static_cast<std::size_t>(bouncyIndex_[j])];
    if (r < 0) continue;
    std::int32_t& group = rootGroup_[static_cast<std::size_t>(r)];
    if (group < 0) {
      group = static_cast<std::int32_t>(bounceGroups_.size());
      bounceGroups_.emplace_back();
    }
    BounceGroup& g = bounceGroups_[static_cast<std::size_t>(group)];
    g.restitution = std::max(g.restitution, bouncy_[j].restitution);
  }
  // Each constraint's group (-1: none), which groups are driven, the tracked bodies (each
  // once: marked in slotParent_, done with as a union-find).
  for (const std::int32_t i : grouped_) {
    const std::int32_t r = constraintGroup_[static_cast<std::size_t>(i)];
    const std::int32_t group = rootGroup_[static_cast<std::size_t>(r)];
    constraintGroup_[static_cast<std::size_t>(i)] = group;
    if (group < 0) continue;
    const ConstraintBodies& cb = constraintBodies_[static_cast<std::size_t>(i)];
    BounceGroup& g = bounceGroups_[static_cast<std::size_t>(group)];
    g.driven = g.driven || (cb.slotA >= 0 && !cb.movesA) || (cb.slotB >= 0 && !cb.movesB);
  }
  for (const std::int32_t i : grouped_) {
    const std::int32_t group = constraintGroup_[static_cast<std::size_t>(i)];
    if (group < 0) continue;
    const ConstraintBodies& cb = constraintBodies_[static_cast<std::size_t>(i)];
    for (const std::int32_t slot : {movingA(cb), movingB(cb)}) {
      if (slot < 0 || slotParent_[static_cast<std::size_t>(slot)] < 0) continue;
      slotParent_[static_cast<std::size_t>(slot)] = -1;
      const Body& b = bodies_[static_cast<std::size_t>(slotBody_[static_cast<std::size_t>(slot)])];
      tracked_.push_back({slot, group, b.mass, b.invInertia > 0.0f ? b.inertia : 0.0f});
    }
  }
}

// What the contacts did to each tracked body's kinetic energy this substep: from the free
// motion's velocity to the velocity after the relax pass (the warm start, both passes and
// their impulses, nothing else, come between).
void WorldState::measureContactWork() {
  for (const TrackedBody& t : tracked_) {
    const auto s = static_cast<std::size_t>(t.slot);
    const SolverBody& b = solverBodies_[s];
    const float vx = freeV_[3 * s], vy = freeV_[3 * s + 1], w = freeV_[3 * s + 2];
    // (v1 - v0) . (v1 + v0): the difference of squares without cancelling.
    const float linear = (b.v.x - vx) * (b.v.x + vx) + (b.v.y - vy) * (b.v.y + vy);
    const float angular = (b.w - w) * (b.w + w);
    bounceGroups_[static_cast<std::size_t>(t.group)].work +=
        0.5 * static_cast<double>(t.mass) * linear + 0.5 * static_cast<double>(t.inertia) * angular;
  }
}

// Per awake slot: where it starts (the solver measures motion from there), whether it is round,
// whether it is damped, and the step's constant accelerations.
void WorldState::prepareBodies(float dt) {
  const auto slots = static_cast<std::size_t>(awakeCount_);
  startCenter_.resize(2 * slots);
  startAngle_.resize(slots);
  slotRound_.resize(slots);
  slotHalfMinExtent_.resize(slots);
  slotMaxExtent_.resize(slots);
  baseAccel_.resize(3 * slots);
  damped_.clear();
  solverBodies_.assign(slots + 1, SolverBody{});  // the last: the null body
  for (std::size_t s = 0; s < slots; ++s) {
    const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    startCenter_[2 * s] = q_[3 * s];
    startCenter_[2 * s + 1] = q_[3 * s + 1];
    startAngle_[s] = q_[3 * s + 2];
    slotRound_[s] = b.round;
    slotHalfMinExtent_[s] = b.type == BodyType::dynamicBody && !b.shapes.empty()
                                ? 0.5f * b.minExtent
                                : std::numeric_limits<float>::infinity();
    slotMaxExtent_[s] = b.maxExtent;
    if (b.linearDamping > 0.0f || b.angularDamping > 0.0f)
      damped_.push_back(static_cast<std::int32_t>(s));
    // Gravity, force and torque do not change during the step: gathered once here, copied out
    // at every stage of the integrator.
    float* a = &baseAccel_[3 * s];
    if (b.type == BodyType::dynamicBody) {
      a[0] = b.gravityScale * def_.gravity.x + b.invMass * b.force.x;
      a[1] = b.gravityScale * def_.gravity.y + b.invMass * b.force.y;
      a[2] = b.invInertia * b.torque;
    } else {
      a[0] = a[1] = a[2] = 0.0f;
    }
  }
  slotExtentsEpoch_ = awakeEpoch_;
  // Bodies begin the step no faster than quarantineSpeed (checked after every step and after
  // the game's changes); without force fields, free motion can make one unusable only if some
  // acceleration could add that much in the step. Otherwise the substeps skip the check.
  checkFreeMotion_ = !fields_.empty() || anyBeyond(baseAccel_, def_.quarantineSpeed / dt);
}

// The first `slots` bodies' velocities as the contact solver's rows (ContactSolver::warmStart):
// three floats a body, then the null body's zeros and one float of padding.
void WorldState::velocityRows(std::span<const float> v, std::size_t slots,
                              std::vector<float>& rows) {
  rows.resize(3 * slots + 4);
  std::copy_n(v.begin(), 3 * slots, rows.begin());
  std::fill_n(rows.begin() + static_cast<std::ptrdiff_t>(3 * slots), 4, 0.0f);
}

// Free motion by the world's integrator (forces evaluated at its stages) and damping; the free
// velocities are kept for the position update.
void WorldState::integrateFreeMotion(int substep, float h) {
  const auto slots = static_cast<std::size_t>(awakeCount_);
  const double t = time_ + static_cast<double>(substep) * static_cast<double>(h);
  // The free velocities as the contact solver's rows (velocityRows): the null body's zeros and
  // the padding after the bodies' rows, which neither path below writes.
  freeV_.resize(3 * slots + 4);
  std::fill_n(freeV_.begin() + static_cast<std::ptrdiff_t>(3 * slots), 4, 0.0f);
  if (def_.integrator == Integrator::semiImplicitEuler && fields_.empty() && damped_.empty() &&
      !checkFreeMotion_) {
    // The common case in one pass: constant accelerations (gravity, the step's forces), no
    // damping, nothing to check. The same operations as integrate() with accelerations() and
    // the copies below (there, a copy of the accelerations, the update, and the copies were
    // three passes over the bodies).
    const float* accel = baseAccel_.data();
    for (std::size_t s = 0; s < slots; ++s) {
      float* vs = &v_[3 * s];
      double* qs = &q_[3 * s];
      for (std::size_t k = 0; k < 3; ++k) {
        vs[k] += h * accel[3 * s + k];
        qs[k] += h * vs[k];
        freeV_[3 * s + k] = vs[k];
      }
      solverBodies_[s].v = {vs[0], vs[1]};
      solverBodies_[s].w = vs[2];
    }
    return;
  }
  const std::span<double> q(q_.data(), 3 * slots);
  const std::span<float> v(v_.data(), 3 * slots);
  // Restitution reverses the approach speed at the impact, read from the velocity the
  // integrator moves the bodies with over the substep: semi-implicit Euler moves them with the
  // velocity after the substep's forces (the free velocities below), explicit Euler with the
  // one before; Verlet and RK4 with one between the two, of which the one before is the lower
  // bound (the one after bounced a ball dropped from 10 m to 10.035 m at restitution 1).
  if (!bouncy_.empty() && def_.integrator != Integrator::semiImplicitEuler)
    velocityRows(v_, slots, approachV_);
  auto accel = [this](std::span<const double> qs, std::span<const float> vs, double ts,
                      std::span<float> a) { accelerations(qs, vs, ts, a); };
  // Damping is implicit (v /= 1 + h c: stable at any c h), placed where each integrator is most
  // accurate on a projectile with drag (contact_precision's drag scene, position error after
  // 3 s at 1 / 4 substeps): semi-implicit Euler damps after and moves the body with the damped
  // velocity, as Box2D does, and matches it (0.088 / 0.022 m; moved with the undamped one: 0.220
  // / 0.055 m; damped first: 0.326 / 0.082 m); the others start from the damped velocity (RK4
  // 0.080 / 0.020 m; damped after: 0.115 / 0.029 m, and moved with it: 0.169 / 0.042 m).
  const bool dampFirst = def_.integrator != Integrator::semiImplicitEuler;
  if (dampFirst) applyDamping(h, false);
  integrate<float, double>(def_.integrator, q, v, t, h, accel, scratch_);
  if (!dampFirst) applyDamping(h, true);
  if (checkFreeMotion_) quarantineUnusable(QuarantineCause::motion, true);
  // The free velocities, kept for the position update (and with semi-implicit Euler the
  // approach restitution reads, laid out as velocityRows does), and the solver's bodies'
  // velocities, in one pass.
  for (std::size_t s = 0; s < slots; ++s) {
    const float vx = v_[3 * s], vy = v_[3 * s + 1], w = v_[3 * s + 2];
    freeV_[3 * s] = vx;
    freeV_[3 * s + 1] = vy;
    freeV_[3 * s + 2] = w;
    solverBodies_[s].v = {vx, vy};
    solverBodies_[s].w = w;
  }
}

// Only the damped bodies: reading every awake body's damping is a cache miss per body. With
// `move`, the substep's position update is redone with the damped velocity.
void WorldState::applyDamping(float h, bool move) {
  for (const std::int32_t slot : damped_) {
    const auto s = static_cast<std::size_t>(slot);
    const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    const float before[3] = {v_[3 * s], v_[3 * s + 1], v_[3 * s + 2]};
    if (b.linearDamping > 0.0f) {
      const float f = 1.0f / (1.0f + h * b.linearDamping);
      v_[3 * s] *= f;
      v_[3 * s + 1] *= f;
    }
    if (b.angularDamping > 0.0f) v_[3 * s + 2] *= 1.0f / (1.0f + h * b.angularDamping);
    if (move)
      for (std::size_t k = 0; k < 3; ++k)
        q_[3 * s + k] += static_cast<double>(h * (v_[3 * s + k] - before[k]));
  }
}

// A body whose velocity is not finite or beyond WorldDef::quarantineSpeed (its position then
// follows from it) is put back where it began the step, at rest, before the contacts can hand the
// value on; it is disabled once the step is done. One branch-free pass over the velocities
// finds whether there is any. Before the step has begun (inStep false: a velocity or impulse
// the game gave it) it is only stopped where it is.
void WorldState::quarantineUnusable(QuarantineCause cause, bool inStep) {
  const std::size_t n = 3 * static_cast<std::size_t>(awakeCount_);
  const float limit = def_.quarantineSpeed;
  if (!anyBeyond(std::span<const float>(v_.data(), n), limit)) return;
  for (std::size_t s = 0; s < static_cast<std::size_t>(awakeCount_); ++s) {
    bool bad = false;
    for (std::size_t k = 0; k < 3; ++k)
      bad = bad || !(std::fabs(v_[3 * s + k]) <= limit) || !std::isfinite(q_[3 * s + k]);
    if (!bad) continue;
    if (inStep) {
      q_[3 * s] = startCenter_[2 * s];
      q_[3 * s + 1] = startCenter_[2 * s + 1];
      q_[3 * s + 2] = startAngle_[s];
    }
    v_[3 * s] = v_[3 * s + 1] = v_[3 * s + 2] = 0.0f;
    requestQuarantine(slotBody_[s], cause);
  }
}

// Where the body began the step (it is put back there when the step is done): the solve's start
// for an awake body during the step, where it is otherwise.
void WorldState::requestQuarantine(std::int32_t body, QuarantineCause cause) {
  const Body& b = bodies_[static_cast<std::size_t>(body)];
  std::array<double, 3> start{};
  const auto s = static_cast<std::size_t>(b.slot);
  if (stepping_ && awake(b) && 2 * s + 1 < startCenter_.size()) {
    start = {startCenter_[2 * s], startCenter_[2 * s + 1], startAngle_[s]};
  } else if (b.slot >= 0) {
    start = {q_[3 * s], q_[3 * s + 1], q_[3 * s + 2]};
  }
  quarantine_.push_back({body, cause, start});
}

// The carried impulses applied to the free velocities (in the solver's bodies since the free
// motion); restitution's approach speeds are read before any warm start (see
// ContactSolver::warmStart).
void WorldState::warmStart() {
  std::span<const float> approach;
  if (!bouncy_.empty())
    approach = def_.integrator == Integrator::semiImplicitEuler ? freeV_ : approachV_;
  contactSolver_.warmStart(solverBodies_, approach);
}

// Positions: the free motion plus what the contacts changed in the velocity (read from the
// solver's bodies; v_ takes them after the relax pass), and each solver body's motion since the
// step began, which the relax pass's separations are measured with.
void WorldState::integratePositions(float h) {
  const auto slots = static_cast<std::size_t>(awakeCount_);
  // The turning bodies listed without a branch: each body's entry written, the count moved on
  // only for one that turns (a push_back each was a capacity test and a size store a body).
  turnAngles_.resize(slots);
  turnOwners_.resize(slots);
  float* angles = turnAngles_.data();
  std::int32_t* owners = turnOwners_.data();
  std::size_t turns = 0;
  for (std::size_t s = 0; s < slots; ++s) {
    SolverBody& sb = solverBodies_[s];
    // Kept in registers: read back from q_, the three double stores would stall the loads.
    const double x = q_[3 * s] + h * (sb.v.x - freeV_[3 * s]);
    const double y = q_[3 * s + 1] + h * (sb.v.y - freeV_[3 * s + 1]);
    const double a = q_[3 * s + 2] + h * (sb.w - freeV_[3 * s + 2]);
    q_[3 * s] = x;
    q_[3 * s + 1] = y;
    q_[3 * s + 2] = a;
    sb.dp = {static_cast<float>(x - startCenter_[2 * s]),
             static_cast<float>(y - startCenter_[2 * s + 1])};
    // Bodies that do not turn (fixed rotation, or just not spinning) cost no trigonometry,
    // and neither do round ones: the anchors rotate with the body so that a turning body's
    // corners move, but a circle about the centre of mass has no corners, and rotating its
    // anchor would only tilt the separation estimate by r (1 - cos turned).
    const auto turned = static_cast<float>(a - startAngle_[s]);
    sb.dq = Rot{};
    angles[turns] = turned;
    owners[turns] = static_cast<std::int32_t>(s);
    turns += turned != 0.0f && !slotRound_[s];
  }
  turnAngles_.resize(turns);
  turnOwners_.resize(turns);
  applyTurns([&](std::int32_t s, Rot dq) { solverBodies_[static_cast<std::size_t>(s)].dq = dq; });
}

void WorldState::storeVelocities() {
  for (std::size_t s = 0; s < static_cast<std::size_t>(awakeCount_); ++s) {
    v_[3 * s] = solverBodies_[s].v.x;
    v_[3 * s + 1] = solverBodies_[s].v.y;
    v_[3 * s + 2] = solverBodies_[s].w;
  }
}

// The impulses back into the contacts, for the next step's warm start.
void WorldState::storeImpulses() {
  solvedImpulses_.resize(4 * constraintSources_.size());
  contactSolver_.impulses(solvedImpulses_);
  for (std::size_t i = 0; i < constraintSources_.size(); ++i) {
    Contact& c = contacts_[static_cast<std::size_t>(constraintSources_[i].contact)];
    const float* p = &solvedImpulses_[4 * i];
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      c.normalImpulse[k] = p[k];
      c.tangentImpulse[k] = p[2 + k];
    }
  }
}

// Restitution, once after the substeps, for the constraints that have it (in the constraints'
// order), within each group's energy budget. Its impulses are not stored for the next step's
// warm start: that starts each substep with the impulse of a substep, and a bounce's, given
// once for the whole step, kicks the pair apart again in the next one, a kick the solve must
// take back, and through a row of touching bodies passes on before it can.
void WorldState::applyRestitution() {
  if (bouncy_.empty()) return;
  const float threshold = def_.restitutionThreshold;
  // The constraints that may bounce (a point the solver pushed, approaching fast enough), in
  // order; the others are left alone below, so only these are read whole. None: nothing
  // changes, and the energy bound has nothing to limit.
  bouncing_.clear();
  for (std::size_t j = 0; j < bouncy_.size(); ++j) {
    const auto i = static_cast<std::size_t>(bouncyIndex_[j]);
    for (int k = 0; k < bouncy_[j].pointCount; ++k) {
      const SolvedPoint p = contactSolver_.solved(i, k);
      if (p.maxNormalImpulse != 0.0f && p.relativeVelocity <= -threshold) {
        bouncing_.push_back(static_cast<std::int32_t>(j));
        break;
      }
    }
  }
  if (bouncing_.empty()) return;
  beforeBounce_.resize(3 * tracked_.size());
  for (std::size_t i = 0; i < tracked_.size(); ++i)
    std::copy_n(&v_[3 * static_cast<std::size_t>(tracked_[i].slot)], 3, &beforeBounce_[3 * i]);
  for (const std::int32_t j : bouncing_) {
    ContactConstraint& cc = bouncy_[static_cast<std::size_t>(j)];
    for (int k = 0; k < cc.pointCount; ++k)
      cc.points[k] = contactSolver_.point(
          static_cast<std::size_t>(bouncyIndex_[static_cast<std::size_t>(j)]), k);
    // Which points bounce: those that were approaching fast enough and that the solver pushed,
    // and that were not already overlapping past the slop when the step began (an impact, not
    // an overlap the push-out is resolving: a circle born inside two overlapping static boxes,
    // bounced off both faces at once, would double its speed every few steps). The other
    // pushed point of a manifold holds: the bounce may push it too, so that it does not
    // approach, but never takes back what the solver gave it.
    Bounce roles[2] = {Bounce::none, Bounce::none};
    bool any = false;
    for (int k = 0; k < cc.pointCount; ++k) {
      const ConstraintPoint& p = cc.points[k];
      if (p.maxNormalImpulse == 0.0f) continue;
      const bool bounces = p.relativeVelocity <= -threshold && p.baseSeparation >= -kLinearSlop;
      roles[k] = bounces ? Bounce::bounces : Bounce::holds;
      any = any || bounces;
    }
    if (!any) continue;
    Vec2 vA{}, vB{};
    float wA = 0.0f, wB = 0.0f;
    const std::size_t iA = 3 * static_cast<std::size_t>(std::max(cc.slotA, 0));
    const std::size_t iB = 3 * static_cast<std::size_t>(std::max(cc.slotB, 0));
    if (cc.slotA >= 0) vA = {v_[iA], v_[iA + 1]}, wA = v_[iA + 2];
    if (cc.slotB >= 0) vB = {v_[iB], v_[iB + 1]}, wB = v_[iB + 2];
    const bool together = cc.pointCount == 2 && roles[0] != Bounce::none &&
                          roles[1] != Bounce::none && bounceTogether(cc, roles, vA, wA, vB, wB);
    for (int k = 0; k < cc.pointCount && !together; ++k) {
      if (roles[k] != Bounce::bounces) continue;
      ConstraintPoint& p = cc.points[k];
      const float vn = dot(vB - vA, cc.normal) + wB * p.rnB - wA * p.rnA;
      const float impulse = -p.normalMass * (vn + cc.restitution * p.relativeVelocity);
      const float total = std::max(p.normalImpulse + impulse, 0.0f);
      const float applied = total - p.normalImpulse;
      p.normalImpulse = total;
      applyImpulse(cc, p, applied * cc.normal, vA, wA, vB, wB);
    }
    if (cc.slotA >= 0) v_[iA] = vA.x, v_[iA + 1] = vA.y, v_[iA + 2] = wA;
    if (cc.slotB >= 0) v_[iB] = vB.x, v_[iB + 1] = vB.y, v_[iB + 2] = wB;
  }
  limitBounceEnergy();
}

// Both points of a manifold at once: one after the other, the first point's bounce turns the
// body and the second is left less to do (a unit box meeting a wall flat at 6 m/s, e = 0.5,
// came back at 2.64 m/s spinning at 0.72 rad/s, not at 3 m/s without turning). Each bouncing
// point aims at e times its approach, each holding point at not approaching; as a linear
// complementarity problem in the two impulses' totals x (a bouncing point's at least 0, a
// holding point's at least what the solver gave it, lo): the normal velocities after,
// vn + K (x - x0), are at least their targets, and a point whose impulse is above its bound is
// at its target. K is the pair's 2x2 effective mass matrix (symmetric, positive definite where
// it is well conditioned), so exactly one of four cases holds (both points pushing, either
// alone, neither), and they are tried in turn, as Box2D's block solver does for the normal
// constraint. False where K is ill conditioned (the points nearly on top of each other): the
// caller then bounces them one after the other.
bool WorldState::bounceTogether(ContactConstraint& cc, const Bounce (&roles)[2], Vec2& vA,
                                float& wA, Vec2& vB, float& wB) {
  ConstraintPoint &p0 = cc.points[0], &p1 = cc.points[1];
  const float m = cc.invMassA + cc.invMassB;
  const float k11 = m + cc.invIA * p0.rnA * p0.rnA + cc.invIB * p0.rnB * p0.rnB;
  const float k22 = m + cc.invIA * p1.rnA * p1.rnA + cc.invIB * p1.rnB * p1.rnB;
  const float k12 = m + cc.invIA * p0.rnA * p1.rnA + cc.invIB * p0.rnB * p1.rnB;
  const float det = k11 * k22 - k12 * k12;
  // The solver's own test of the block (massesBatch): conditioned to within 1000.
  if (!(k11 * k11 < 1000.0f * det)) return false;
  auto target = [&](const ConstraintPoint& p, Bounce role) {
    return role == Bounce::bounces ? -cc.restitution * p.relativeVelocity : 0.0f;
  };
  auto lower = [](const ConstraintPoint& p, Bounce role) {
    return role == Bounce::bounces ? 0.0f : p.normalImpulse;
  };
  const Vec2 dv = vB - vA;
  const float lo0 = lower(p0, roles[0]), lo1 = lower(p1, roles[1]);
  // In y = x - lo >= 0: the velocities after, less the targets, are w = K y + b >= 0.
  const float d0 = lo0 - p0.normalImpulse, d1 = lo1 - p1.normalImpulse;
  const float b0 =
      dot(dv, cc.normal) + wB * p0.rnB - wA * p0.rnA - target(p0, roles[0]) + k11 * d0 + k12 * d1;
  const float b1 =
      dot(dv, cc.normal) + wB * p1.rnB - wA * p1.rnA - target(p1, roles[1]) + k12 * d0 + k22 * d1;
  float y0 = 0.0f, y1 = 0.0f;
  // Both pushing (w = 0), the first alone (y1 = 0, w0 = 0), the second alone, neither (y = 0).
  if (const float s0 = (k12 * b1 - k22 * b0) / det, s1 = (k12 * b0 - k11 * b1) / det;
      s0 >= 0.0f && s1 >= 0.0f) {
    y0 = s0, y1 = s1;
  } else if (const float a0 = -b0 / k11; a0 >= 0.0f && k12 * a0 + b1 >= 0.0f) {
    y0 = a0;
  } else if (const float a1 = -b1 / k22; a1 >= 0.0f && k12 * a1 + b0 >= 0.0f) {
    y1 = a1;
  } else if (!(b0 >= 0.0f && b1 >= 0.0f)) {
    return false;  // rounding left no case standing: one after the other
  }
  const float applied0 = lo0 + y0 - p0.normalImpulse, applied1 = lo1 + y1 - p1.normalImpulse;
  p0.normalImpulse += applied0;
  p1.normalImpulse += applied1;
  applyImpulse(cc, p0, applied0 * cc.normal, vA, wA, vB, wB);
  applyImpulse(cc, p1, applied1 * cc.normal, vA, wA, vB, wB);
  return true;
}

// Newton's law (each point's normal velocity reversed, times the restitution) keeps a lone
// pair to its energy, but not bodies that touch several others at once: the approach a point
// reverses is the one it had when the step began, and what the solve passed on meanwhile
// through the neighbouring contacts is not in it. So each group gives back at most e^2 of the
// kinetic energy its contacts took out of it over the substeps (Stronge's energetic
// restitution, e the group's highest restitution): where the bounce would give more, its
// velocity changes are scaled down by one factor for the whole group, which keeps momentum. A
// lone pair's bounce is within the budget: its contact took out the whole approach. A group
// driven by a kinematic body is left as Newton's law made it: that body's work is not measured.
void WorldState::limitBounceEnergy() {
  for (BounceGroup& g : bounceGroups_)
    g.bounceSquare = g.bounceCross = 0.0;
  for (std::size_t i = 0; i < tracked_.size(); ++i) {
    const TrackedBody& t = tracked_[i];
    const float* before = &beforeBounce_[3 * i];
    const float* after = &v_[3 * static_cast<std::size_t>(t.slot)];
    const double weight[3] = {t.mass, t.mass, t.inertia};
    BounceGroup& g = bounceGroups_[static_cast<std::size_t>(t.group)];
    for (int k = 0; k < 3; ++k) {
      const double change = static_cast<double>(after[k]) - before[k];
      g.bounceSquare += 0.5 * weight[k] * change * change;
      g.bounceCross += weight[k] * before[k] * change;
    }
  }
  // The group's kinetic energy with a fraction f of the bounce applied is E + f c + f^2 a
  // (a: bounceSquare, c: bounceCross); the largest f in [0, 1] with f c + f^2 a <= budget.
  for (BounceGroup& g : bounceGroups_) {
    const double a = g.bounceSquare, c = g.bounceCross;
    const double budget =
        static_cast<double>(g.restitution) * g.restitution * std::max(-g.work, 0.0);
    g.kept = 1.0;
    if (g.driven || a + c <= budget) continue;
    const double root = std::sqrt(c * c + 4.0 * a * budget);
    // The positive root of a f^2 + c f - budget, in the form that does not cancel.
    g.kept = c > 0.0 ? 2.0 * budget / (c + root) : (root - c) / (2.0 * a);
  }
  for (std::size_t i = 0; i < tracked_.size(); ++i) {
    const TrackedBody& t = tracked_[i];
    const double kept = bounceGroups_[static_cast<std::size_t>(t.group)].kept;
    if (kept >= 1.0) continue;
    const float* before = &beforeBounce_[3 * i];
    float* after = &v_[3 * static_cast<std::size_t>(t.slot)];
    for (int k = 0; k < 3; ++k)
      after[k] = static_cast<float>(before[k] + kept * (static_cast<double>(after[k]) - before[k]));
  }
}

}  // namespace rc
