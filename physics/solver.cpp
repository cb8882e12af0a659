// The solve: contact constraints prepared, then substeps of free motion, warm start, soft
// contact solve, position update and relax; restitution; impulses stored for the next step.
#include <algorithm>
#include <bit>
#include <cmath>

#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

namespace {

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

template <class Solve>
void WorldState::forEachBouncy(Solve&& solve) {
  for (ContactConstraint& cc : bouncy_) {
    Vec2 vA{}, vB{};
    float wA = 0.0f, wB = 0.0f;
    const std::size_t iA = 3 * static_cast<std::size_t>(std::max(cc.slotA, 0));
    const std::size_t iB = 3 * static_cast<std::size_t>(std::max(cc.slotB, 0));
    if (cc.slotA >= 0) vA = {v_[iA], v_[iA + 1]}, wA = v_[iA + 2];
    if (cc.slotB >= 0) vB = {v_[iB], v_[iB + 1]}, wB = v_[iB + 2];
    solve(cc, vA, wA, vB, wB);
    if (cc.slotA >= 0) v_[iA] = vA.x, v_[iA + 1] = vA.y, v_[iA + 2] = wA;
    if (cc.slotB >= 0) v_[iB] = vB.x, v_[iB + 1] = vB.y, v_[iB + 2] = wB;
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
      ContactSoftness::make(h, def_.contactHertz, def_.contactDampingRatio, def_.maxPushoutSpeed);
  for (int sub = 0; sub < def_.substeps; ++sub) {
    integrateFreeMotion(sub, h);
    warmStart();
    // Symmetric Gauss-Seidel: the relax pass sweeps the colours the other way from the solve
    // pass, and each substep starts the way the last one ended.
    const bool backward = sub % 2 == 1;
    contactSolver_.solve(solverBodies_, soft, true, backward);
    integratePositions(h);
    contactSolver_.solve(solverBodies_, soft, false, !backward);  // relax
    storeVelocities();
  }
  storeImpulses();
  applyRestitution();
}

// One constraint per touching contact with an awake side, anchors from the centres of mass. The
// solver colours them first (it needs only their bodies), then each constraint is prepared
// straight into its lane.
void WorldState::prepareContacts() {
  constraintSources_.clear();
  constraintBodies_.clear();
  bouncy_.clear();
  bouncyIndex_.clear();
  profile_.colours = profile_.overflow = 0;
  if (awakeCount_ == 0) return;
  for (std::size_t ci = 0; ci < contacts_.size(); ++ci) {
    const Contact& c = contacts_[ci];
    if (!c.touching) continue;
    const std::int32_t bodyA = shapes_[static_cast<std::size_t>(c.shapeA)].body;
    const std::int32_t bodyB = shapes_[static_cast<std::size_t>(c.shapeB)].body;
    const Body& a = bodies_[static_cast<std::size_t>(bodyA)];
    const Body& b = bodies_[static_cast<std::size_t>(bodyB)];
    const std::int32_t slotA = awake(a) ? a.slot : -1, slotB = awake(b) ? b.slot : -1;
    if (slotA < 0 && slotB < 0) continue;  // asleep against asleep or static
    constraintSources_.push_back({static_cast<std::int32_t>(ci), bodyA, bodyB});
    constraintBodies_.push_back({slotA, slotB, a.invMass > 0.0f || a.invInertia > 0.0f,
                                 b.invMass > 0.0f || b.invInertia > 0.0f, c.manifold.pointCount});
  }
  contactSolver_.prepare(constraintBodies_, awakeCount_, def_.maxSolverLanes);
  profile_.colours = contactSolver_.colourCount();
  profile_.overflow = contactSolver_.overflowCount();
  profile_.lanes = contactSolver_.laneCount();

  for (std::size_t i = 0; i < constraintSources_.size(); ++i) {
    const ConstraintSource& source = constraintSources_[i];
    const Contact& c = contacts_[static_cast<std::size_t>(source.contact)];
    const Body& a = bodies_[static_cast<std::size_t>(source.bodyA)];
    const Body& b = bodies_[static_cast<std::size_t>(source.bodyB)];
    ContactConstraint cc;
    cc.contact = source.contact;
    cc.slotA = constraintBodies_[i].slotA;
    cc.slotB = constraintBodies_[i].slotB;
    // A sleeping body stays put for this step: it counts as static (and the solver's null body,
    // which static sides share, must never be moved).
    cc.invMassA = cc.slotA >= 0 ? a.invMass : 0.0f;
    cc.invIA = cc.slotA >= 0 ? a.invInertia : 0.0f;
    cc.invMassB = cc.slotB >= 0 ? b.invMass : 0.0f;
    cc.invIB = cc.slotB >= 0 ? b.invInertia : 0.0f;
    cc.normal = c.manifold.normal;
    cc.friction = c.friction;
    cc.restitution = c.restitution;
    cc.pointCount = c.manifold.pointCount;
    const Vec2 offsetA = rotate(a.xf.q, a.localCenter), offsetB = rotate(b.xf.q, b.localCenter);
    const Vec2 vA = cc.slotA >= 0 ? Vec2{v_[3 * static_cast<std::size_t>(cc.slotA)],
                                         v_[3 * static_cast<std::size_t>(cc.slotA) + 1]}
                                  : Vec2{};
    const float wA = cc.slotA >= 0 ? v_[3 * static_cast<std::size_t>(cc.slotA) + 2] : 0.0f;
    const Vec2 vB = cc.slotB >= 0 ? Vec2{v_[3 * static_cast<std::size_t>(cc.slotB)],
                                         v_[3 * static_cast<std::size_t>(cc.slotB) + 1]}
                                  : Vec2{};
    const float wB = cc.slotB >= 0 ? v_[3 * static_cast<std::size_t>(cc.slotB) + 2] : 0.0f;
    for (int k = 0; k < cc.pointCount; ++k) {
      const ManifoldPoint& mp = c.manifold.points[k];
      ConstraintPoint& p = cc.points[k];
      p.rA = mp.anchorA - offsetA;
      p.rB = mp.anchorB - offsetB;
      p.baseSeparation = mp.separation;
      p.normalImpulse = c.normalImpulse[k];
      p.tangentImpulse = c.tangentImpulse[k];
      p.maxNormalImpulse = 0.0f;
      const Vec2 dv = (vB + cross(wB, p.rB)) - (vA + cross(wA, p.rA));
      p.relativeVelocity = dot(dv, cc.normal);
    }
    contactSolver_.set(i, cc);
    if (cc.restitution != 0.0f) {
      bouncy_.push_back(cc);
      bouncyIndex_.push_back(static_cast<std::int32_t>(i));
    }
  }
  contactSolver_.computeMasses();
}

// Per awake slot: where it starts (the solver measures motion from there), whether it is round,
// whether it is damped, and the step's constant accelerations.
void WorldState::prepareBodies(float dt) {
  const auto slots = static_cast<std::size_t>(awakeCount_);
  startCenter_.resize(2 * slots);
  startAngle_.resize(slots);
  slotRound_.resize(slots);
  baseAccel_.resize(3 * slots);
  damped_.clear();
  solverBodies_.assign(slots + 1, SolverBody{});  // the last: the null body
  for (std::size_t s = 0; s < slots; ++s) {
    const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    startCenter_[2 * s] = q_[3 * s];
    startCenter_[2 * s + 1] = q_[3 * s + 1];
    startAngle_[s] = q_[3 * s + 2];
    slotRound_[s] = b.round;
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
  // Bodies begin the step no faster than quarantineSpeed (checked after every step and after
  // the game's changes); without force fields, free motion can make one unusable only if some
  // acceleration could add that much in the step. Otherwise the substeps skip the check.
  std::uint32_t worst = 0;
  for (float a : baseAccel_)
    worst = std::max(worst, std::bit_cast<std::uint32_t>(a) & 0x7FFFFFFFu);
  checkFreeMotion_ =
      !fields_.empty() || worst > std::bit_cast<std::uint32_t>(def_.quarantineSpeed / dt);
}

// The awake bodies' velocities into solver bodies (v and w; the rest as it is).
void WorldState::loadVelocities(std::vector<SolverBody>& to) const {
  for (std::size_t s = 0; s < static_cast<std::size_t>(awakeCount_); ++s) {
    to[s].v = {v_[3 * s], v_[3 * s + 1]};
    to[s].w = v_[3 * s + 2];
  }
}

// Free motion by the world's integrator (forces evaluated at its stages), then damping
// (implicit, unconditionally stable); the free velocities are kept for the position update.
void WorldState::integrateFreeMotion(int substep, float h) {
  const auto slots = static_cast<std::size_t>(awakeCount_);
  const double t = time_ + static_cast<double>(substep) * static_cast<double>(h);
  const std::span<double> q(q_.data(), 3 * slots);
  const std::span<float> v(v_.data(), 3 * slots);
  // Restitution reverses the approach speed at the impact, read from the velocity the
  // integrator moves the bodies with over the substep: semi-implicit Euler moves them with the
  // velocity after the substep's forces (taken in warmStart()), explicit Euler with the one
  // before; Verlet and RK4 with one between the two, of which the one before is the lower bound
  // (the one after bounced a ball dropped from 10 m to 10.035 m at restitution 1).
  if (!bouncy_.empty() && def_.integrator != Integrator::semiImplicitEuler) {
    freeMotion_.assign(slots + 1, SolverBody{});
    loadVelocities(freeMotion_);
  }
  auto accel = [this](std::span<const double> qs, std::span<const float> vs, double ts,
                      std::span<float> a) { accelerations(qs, vs, ts, a); };
  integrate<float, double>(def_.integrator, q, v, t, h, accel, scratch_);
  // Only the damped bodies: reading every awake body's damping is a cache miss per body.
  for (const std::int32_t slot : damped_) {
    const auto s = static_cast<std::size_t>(slot);
    const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    if (b.linearDamping > 0.0f) {
      const float f = 1.0f / (1.0f + h * b.linearDamping);
      v_[3 * s] *= f;
      v_[3 * s + 1] *= f;
    }
    if (b.angularDamping > 0.0f) v_[3 * s + 2] *= 1.0f / (1.0f + h * b.angularDamping);
  }
  if (checkFreeMotion_) quarantineUnusable(QuarantineCause::motion, true);
  freeV_.assign(v.begin(), v.end());
}

// A body whose velocity is not finite or beyond WorldDef::quarantineSpeed (its position then
// follows from it) is put back where it began the step, at rest, before the contacts can hand the
// value on; it is disabled once the step is done. One branch-free pass over the velocities
// finds whether there is any. Before the step has begun (inStep false: a velocity or impulse
// the game gave it) it is only stopped where it is.
void WorldState::quarantineUnusable(QuarantineCause cause, bool inStep) {
  const std::size_t n = 3 * static_cast<std::size_t>(awakeCount_);
  const float limit = def_.quarantineSpeed;
  // On the magnitude's bits, NaN and infinity sort above every finite float: an integer maximum
  // (a vector instruction) finds the worst.
  std::uint32_t worst = 0;
  for (std::size_t i = 0; i < n; ++i)
    worst = std::max(worst, std::bit_cast<std::uint32_t>(v_[i]) & 0x7FFFFFFFu);
  if (worst <= std::bit_cast<std::uint32_t>(limit)) return;
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

// The carried impulses applied to the free velocities; restitution's approach speeds are read
// before any warm start (see ContactSolver::warmStart).
void WorldState::warmStart() {
  const bool bouncy = !bouncy_.empty();
  loadVelocities(solverBodies_);
  if (bouncy && def_.integrator == Integrator::semiImplicitEuler)
    freeMotion_.assign(solverBodies_.begin(), solverBodies_.end());
  contactSolver_.warmStart(solverBodies_, bouncy ? std::span<const SolverBody>{freeMotion_}
                                                 : std::span<const SolverBody>{});
}

// Positions: the free motion plus what the contacts changed in the velocity (read from the
// solver's bodies; v_ takes them after the relax pass), and each solver body's motion since the
// step began, which the relax pass's separations are measured with.
void WorldState::integratePositions(float h) {
  const auto slots = static_cast<std::size_t>(awakeCount_);
  reserveTurns(slots);
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
    if (turned != 0.0f && !slotRound_[s]) {
      turnAngles_.push_back(turned);
      turnOwners_.push_back(static_cast<std::int32_t>(s));
    }
  }
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
  for (std::size_t i = 0; i < constraintSources_.size(); ++i) {
    Contact& c = contacts_[static_cast<std::size_t>(constraintSources_[i].contact)];
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      const SolvedPoint p = contactSolver_.solved(i, k);
      c.normalImpulse[k] = p.normalImpulse;
      c.tangentImpulse[k] = p.tangentImpulse;
    }
  }
}

// Restitution, once after the substeps, for the constraints that have it (in the constraints'
// order); their normal impulses stored again with it.
void WorldState::applyRestitution() {
  if (bouncy_.empty()) return;
  for (std::size_t j = 0; j < bouncy_.size(); ++j) {
    ContactConstraint& cc = bouncy_[j];
    for (int k = 0; k < cc.pointCount; ++k)
      cc.points[k] = contactSolver_.point(static_cast<std::size_t>(bouncyIndex_[j]), k);
  }
  const float threshold = def_.restitutionThreshold;
  forEachBouncy([&](ContactConstraint& cc, Vec2& vA, float& wA, Vec2& vB, float& wB) {
    if (cc.restitution == 0.0f) return;
    const Vec2 n = cc.normal;
    for (int k = 0; k < cc.pointCount; ++k) {
      ConstraintPoint& p = cc.points[k];
      // Only points that were approaching fast enough and that the solver pushed, and that
      // were not already overlapping past the slop when the step began: an impact, not an
      // overlap the push-out is resolving (a circle born inside two overlapping static boxes,
      // bounced off both faces at once, would double its speed every few steps).
      if (p.relativeVelocity > -threshold || p.maxNormalImpulse == 0.0f) continue;
      if (p.baseSeparation < -kLinearSlop) continue;
      const float vn = dot(vB - vA, n) + wB * p.rnB - wA * p.rnA;
      const float impulse = -p.normalMass * (vn + cc.restitution * p.relativeVelocity);
      const float total = std::max(p.normalImpulse + impulse, 0.0f);
      const float applied = total - p.normalImpulse;
      p.normalImpulse = total;
      p.maxNormalImpulse = std::max(p.maxNormalImpulse, applied);
      const Vec2 P = applied * n;
      applyImpulse(cc, p, P, vA, wA, vB, wB);
    }
  });
  for (const ContactConstraint& cc : bouncy_) {
    Contact& c = contacts_[static_cast<std::size_t>(cc.contact)];
    for (int k = 0; k < cc.pointCount; ++k)
      c.normalImpulse[k] = cc.points[k].normalImpulse;
  }
}

}  // namespace rc
