// The stability stress suite (issue 22): scenes built to break a rigid-body engine, run through
// the rc::World API, each checked against a bound that can fail. One line per case,
//   case NAME: figures -> PASS
// (or FAIL and the bounds broken), and exit status 1 when any case fails. Short by default
// (seconds: the default ctest run); --long for the stress label (the 10^6-step soak of 5,000
// bodies and longer versions of every case). tests/README.md has the table of cases and figures.
//
//   stress [--long] [--case NAME]... [--soak-bodies N] [--soak-steps N]
//
// Every scene is built from a fixed seed (rc::Random), so a run replays exactly.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <box2d/box2d.h>

#include "physics/random.h"
#include "physics/trig.h"
#include "physics/world.h"
#include "support/sanitizers.h"

namespace stress {

using rc::AABB;
using rc::BodyId;
using rc::Vec2;
using rc::World;

constexpr float kStep = 1.0f / 60.0f;
constexpr float kPi = 3.14159265f;

// ----------------------------------------------------------------------------- reporting

std::string format(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* f, ...) {
  char buf[1024];
  va_list args;
  va_start(args, f);
  std::vsnprintf(buf, sizeof buf, f, args);
  va_end(args);
  return buf;
}

// What a case measured, and the bounds it broke (none: it passed).
struct Outcome {
  std::string figures;
  std::vector<std::string> broken;
  std::vector<std::string> known;  // known failures that still fail (tests/README.md)
  void add(const std::string& figure) { figures += (figures.empty() ? "" : ", ") + figure; }
  // Records `what` as broken unless `ok`.
  void expect(bool ok, const std::string& what) {
    if (!ok) broken.push_back(what);
  }
  // A bound the engine is known to break, reported every run as KNOWN. If it ever holds, the
  // case fails, so that someone makes it a check and updates tests/README.md.
  void expectKnownFailure(bool ok, const std::string& what) {
    if (ok)
      broken.push_back("a known failure now holds (make it a check): " + what);
    else
      known.push_back(what);
  }
};

// ------------------------------------------------------------------------------ scenes

rc::BodyDef dynamicAt(Vec2 p, Vec2 v = {}, float angle = 0.0f) {
  rc::BodyDef def;
  def.type = rc::BodyType::dynamicBody;
  def.position = p;
  def.linearVelocity = v;
  def.angle = angle;
  return def;
}

// The four walls of a closed box `thickness` thick around `interior`, each as half-extents and
// a centre, overlapping at the corners so that nothing finds a seam.
struct Wall {
  Vec2 half, centre;
};
std::array<Wall, 4> containerWalls(const AABB& interior, float thickness) {
  const Vec2 c = interior.center(), e = interior.extents();
  const float t = 0.5f * thickness;
  return {{{{e.x + thickness, t}, {c.x, interior.lower.y - t}},
           {{e.x + thickness, t}, {c.x, interior.upper.y + t}},
           {{t, e.y + thickness}, {interior.lower.x - t, c.y}},
           {{t, e.y + thickness}, {interior.upper.x + t, c.y}}}};
}

void addContainer(World& w, const AABB& interior, float thickness, const rc::ShapeDef& sd = {}) {
  const BodyId walls = w.createBody({});
  for (const Wall& wall : containerWalls(interior, thickness))
    w.createShape(walls, rc::makeBox(wall.half.x, wall.half.y, wall.centre), sd);
}

Vec2 direction(rc::Random& rng) {
  const rc::SinCos sc = rc::sincos(rng.uniform(0.0f, 2.0f * kPi));
  return {sc.cosine, sc.sine};
}

// How far a centre is past the nearest wall's inner face of a container (negative inside).
float pastWall(const AABB& interior, Vec2 centre) {
  return std::max(std::max(interior.lower.x - centre.x, centre.x - interior.upper.x),
                  std::max(interior.lower.y - centre.y, centre.y - interior.upper.y));
}
// Escaped: the body's centre of mass is outside the container's interior. A body can only get
// there by going into or through a wall as deep as its own smallest half-extent, 5 cm or more
// in the scenes that use this: ten times the slop a resting contact sinks, and more than the
// contacts under the heaviest load here sink (the pressure case's floor).
bool outside(const AABB& interior, Vec2 centre) {
  return pastWall(interior, centre) > 0.0f;
}

bool finite(const World& w, BodyId b) {
  return rc::isFinite(w.worldCenter(b)) && rc::isFinite(w.linearVelocity(b)) &&
         std::isfinite(w.angle(b)) && std::isfinite(w.angularVelocity(b));
}

// The deepest overlap of any touching contact point (m, positive when overlapping).
float deepestPenetration(const World& w) {
  float deepest = 0.0f;
  for (const World::ContactPointView& p : w.contactPoints())
    deepest = std::max(deepest, -p.separation);
  return deepest;
}

// Peak and current resident memory of this process (kB), from /proc/self/status (Linux).
struct Memory {
  long peakKiB = -1, residentKiB = -1;
};
Memory memory() {
  Memory m;
  std::ifstream status("/proc/self/status");
  std::string key;
  long value = 0;
  while (status >> key) {
    if (key == "VmHWM:" && status >> value) m.peakKiB = value;
    if (key == "VmRSS:" && status >> value) m.residentKiB = value;
  }
  return m;
}
double mib(long kib) {
  return static_cast<double>(kib) / 1024.0;
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// -------------------------------------------------------------------------------- soak

// A 200 m arena of thin walls (10 cm) with 20 static obstacles and `count` bodies: nine in ten
// circles, boxes, capsules and hexagons of about 1 m at 5 m/s, one in ten fast movers (5 cm
// circles and boxes, half of them bullets) at 300 m/s, each fired again in a new direction
// whenever it has slowed below 50 m/s; restitution 0.5, friction 0.2, no gravity, sleeping on.
// A fast mover crosses 5 m a step, fifty times the walls' thickness.
Outcome soak(int count, long steps, bool progress) {
  constexpr float fastSpeed = 300.0f, refireBelow = 50.0f;
  rc::WorldDef def;
  def.gravity = {0, 0};
  def.bounds = {{-128, -128}, {128, 128}};
  World w(def);
  const AABB interior{{-100, -100}, {100, 100}};
  rc::ShapeDef sd;
  sd.restitution = 0.5f;
  sd.friction = 0.2f;
  addContainer(w, interior, 0.1f, sd);
  rc::Random rng(22);
  std::vector<AABB> obstacles;
  const BodyId statics = w.createBody({});
  for (int i = 0; i < 20; ++i) {
    const Vec2 c = rng.inBox({-80, -80}, {80, 80}), h = rng.inBox({1, 1}, {4, 4});
    w.createShape(statics, rc::makeBox(h.x, h.y, c), sd);
    obstacles.push_back({c - h, c + h});
  }
  // Bodies on a grid of 1.6 m cells clear of the obstacles, in a seeded order: none overlaps.
  std::vector<Vec2> cells;
  for (float x = -99.0f; x <= 99.0f; x += 1.6f)
    for (float y = -99.0f; y <= 99.0f; y += 1.6f) {
      bool clear = true;
      for (const AABB& o : obstacles)
        clear = clear &&
                (x < o.lower.x - 1 || x > o.upper.x + 1 || y < o.lower.y - 1 || y > o.upper.y + 1);
      if (clear) cells.push_back({x, y});
    }
  for (std::size_t i = cells.size() - 1; i > 0; --i)
    std::swap(cells[i], cells[rng.below(static_cast<std::uint32_t>(i + 1))]);
  if (static_cast<std::size_t>(count) > cells.size()) count = static_cast<int>(cells.size());
  const int fastCount = count / 10;
  std::vector<BodyId> bodies, fast;
  const Vec2 hexagon[] = {{0.45f, 0},  {0.22f, 0.39f},   {-0.22f, 0.39f},
                          {-0.45f, 0}, {-0.22f, -0.39f}, {0.22f, -0.39f}};
  for (int i = 0; i < count; ++i) {
    const bool isFast = i < fastCount;
    rc::BodyDef bd = dynamicAt(cells[static_cast<std::size_t>(i)],
                               (isFast ? fastSpeed : 5.0f) * direction(rng), rng.uniform(-3, 3));
    bd.bullet = isFast && i % 2 == 0;
    const BodyId b = w.createBody(bd);
    if (isFast) {
      if (i % 4 < 2)
        w.createShape(b, rc::makeCircle({}, 0.05f), sd);
      else
        w.createShape(b, rc::makeBox(0.05f, 0.05f), sd);
      fast.push_back(b);
    } else {
      switch (i % 4) {
        case 0:
          w.createShape(b, rc::makeCircle({}, 0.5f), sd);
          break;
        case 1:
          w.createShape(b, rc::makeBox(0.4f, 0.4f), sd);
          break;
        case 2:
          w.createShape(b, rc::makeCapsule({-0.3f, 0}, {0.3f, 0}, 0.25f), sd);
          break;
        default:
          w.createShape(b, rc::makePolygon(hexagon), sd);
      }
    }
    bodies.push_back(b);
  }

  // Memory is measured after this many steps and at the end: 10^4 in the long run (the
  // issue's figure), a third of the run in a short one.
  const long checkpoint = std::min<long>(10000, steps / 3);
  Memory atCheckpoint, atStart = memory();
  std::vector<char> escaped(bodies.size(), 0), broken(bodies.size(), 0);
  long quarantined = 0, refired = 0;
  float fastest = 0.0f;
  const auto start = std::chrono::steady_clock::now();
  for (long k = 1; k <= steps; ++k) {
    w.step(kStep);
    quarantined += static_cast<long>(w.quarantineEvents().size());
    if (k % 10 == 0) {
      for (BodyId b : bodies)
        fastest = std::max(fastest, rc::length(w.linearVelocity(b)));
      for (BodyId b : fast)
        if (rc::length(w.linearVelocity(b)) < refireBelow) {
          w.setLinearVelocity(b, fastSpeed * direction(rng));
          ++refired;
        }
    }
    // Every step: a body through a wall can come back through it (the look costs little beside
    // the step). A quarantined body is disabled for good and counted above, so the full state
    // is looked at every 100 steps.
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Vec2 c = w.worldCenter(bodies[i]);
      if (escaped[i] || !outside(interior, c)) continue;
      escaped[i] = 1;
      // Where and how, to replay it: the step, the body, and its state now.
      const Vec2 v = w.linearVelocity(bodies[i]);
      std::fprintf(
          stderr,
          "soak: step %ld: body %zu (%s) escaped: centre (%.9g, %.9g), %.3g m past the "
          "wall, velocity (%.6g, %.6g), angular velocity %.6g\n",
          k, i,
          i < static_cast<std::size_t>(fastCount) ? (i % 2 == 0 ? "fast, bullet" : "fast") : "slow",
          c.x, c.y, pastWall(interior, c), v.x, v.y, w.angularVelocity(bodies[i]));
    }
    if (k % 100 == 0 || k == steps)
      for (std::size_t i = 0; i < bodies.size(); ++i)
        broken[i] |= !finite(w, bodies[i]) || !w.isEnabled(bodies[i]);
    if (k == checkpoint) atCheckpoint = memory();
    if (progress && k % 100000 == 0)
      std::fprintf(stderr, "soak: %ld steps, %.0f s, peak RSS %.1f MiB\n", k, seconds(start),
                   mib(memory().peakKiB));
  }
  const double elapsed = seconds(start);
  const Memory atEnd = memory();
  const long escapes = std::count(escaped.begin(), escaped.end(), 1);
  const long brokenCount = std::count(broken.begin(), broken.end(), 1);

  Outcome o;
  o.add(format("%d bodies (%d fast), %ld steps in %.1f s (%.0f us/step)", count, fastCount, steps,
               elapsed, 1e6 * elapsed / static_cast<double>(steps)));
  o.add(format("not finite or quarantined %ld, quarantine events %ld, escapes %ld", brokenCount,
               quarantined, escapes));
  o.add(format("fastest %.0f m/s, re-fired %ld", fastest, refired));
  o.add(
      format("peak RSS %.1f MiB at start, %.1f MiB at step %ld, %.1f MiB at step %ld "
             "(resident %.1f MiB)",
             mib(atStart.peakKiB), mib(atCheckpoint.peakKiB), checkpoint, mib(atEnd.peakKiB), steps,
             mib(atEnd.residentKiB)));
  o.expect(brokenCount == 0 && quarantined == 0, "a body not finite or quarantined");
  o.expect(escapes == 0, "a body escaped");
  // Restitution is at most 1, so one collision leaves a body at most 2v - u (a light body struck
  // head on by a heavy one): three times the fastest launch bounds anything short of a blow-up.
  o.expect(fastest <= 3.0f * fastSpeed, "faster than 3 x 300 m/s");
  // Memory is flat: the world's arrays reach their size within the first steps, and a leak or
  // an array that keeps growing would show after step 10^4. The bound leaves room for the
  // allocator and one late capacity doubling of a small array: 1 MiB or 2%, whichever is more.
  const long slack = std::max(1024L, atCheckpoint.peakKiB / 50);
  o.expect(atCheckpoint.peakKiB > 0 && atEnd.peakKiB <= atCheckpoint.peakKiB + slack,
           format("peak RSS grew %.1f MiB after step %ld (bound %.1f)",
                  mib(atEnd.peakKiB - atCheckpoint.peakKiB), checkpoint, mib(slack)));
  return o;
}

// ------------------------------------------------------------------------- mass ratios

// A stack of 1 m boxes on a static ground (top face y = 0), friction 0.6, sleeping off so that
// nothing hides a creep, run in a world of its own at `substeps`. Masses bottom to top; a
// negative mass is a 4 m x 0.5 m plank of that mass resting on two boxes of the mass below it
// (a table).
struct Stack {
  const char* name;
  std::vector<float> masses;
  int substeps = 4;
};

struct StackResult {
  float sank = 0, drift = 0, tilt = 0;  // of the top box: down, sideways, turned
  float law = 0;                        // what the soft contacts' law lets it sink
  bool finite = true;
};

// A soft contact (WorldDef::contactHertz) is a spring whose stiffness is relative to its own
// effective mass m_eff: it settles where the load it carries over m_eff is omega^2 times its
// overlap (World.HeavyBoxOnTwoLightBoxesHolds). The top of a stack sinks by the sum over its
// contacts; a light box under a heavy one sinks by the ratio times a light box's own 0.28 mm.
StackResult runStack(const Stack& stack, int steps) {
  rc::WorldDef def;
  def.enableSleep = false;
  def.substeps = stack.substeps;
  World w(def);
  const BodyId ground = w.createBody({});
  w.createShape(ground, rc::makeBox(50, 1, {0, -1}));
  std::vector<BodyId> bodies;
  auto box = [&](Vec2 p, Vec2 half, float mass) {
    rc::ShapeDef sd;
    sd.density = mass / (4.0f * half.x * half.y);
    bodies.push_back(w.createBody(dynamicAt(p)));
    w.createShape(bodies.back(), rc::makeBox(half.x, half.y), sd);
    return bodies.back();
  };
  const float hertz = std::min(def.contactHertz, 0.25f * static_cast<float>(def.substeps) / kStep);
  const float omega2 = (2.0f * kPi * hertz) * (2.0f * kPi * hertz), g = -def.gravity.y;
  StackResult r;
  BodyId top;
  Vec2 built;
  if (stack.masses.back() < 0) {  // a table: the plank on two legs 3 m apart
    const float m = stack.masses[0], plank = -stack.masses[1];
    box({0, 0.5f}, {0.5f, 0.5f}, m);
    box({3, 0.5f}, {0.5f, 0.5f}, m);
    built = {1.5f, 1.25f};
    top = box(built, {2.0f, 0.25f}, plank);
    // Each leg carries half the plank.
    r.law =
        0.5f * plank * g / (m * plank / (m + plank)) / omega2 + (m + 0.5f * plank) * g / m / omega2;
  } else {
    float above = 0, below = 0;  // the mass over a contact, and under it
    for (float m : stack.masses)
      above += m;
    float y = 0.5f;
    for (float m : stack.masses) {
      built = {0, y};
      top = box(built, {0.5f, 0.5f}, m);
      r.law += above * g / (below > 0 ? below * m / (below + m) : m) / omega2;
      above -= m;
      below = m;
      y += 1.0f;
    }
  }
  for (int k = 0; k < steps; ++k)
    w.step(kStep);
  const Vec2 p = w.position(top);
  r.sank = built.y - p.y;
  r.drift = std::abs(p.x - built.x);
  for (BodyId b : bodies) {
    r.tilt = std::max(r.tilt, std::abs(w.angle(b)));
    r.finite = r.finite && finite(w, b);
  }
  return r;
}

// Stacks with masses 1:1000 must stand where they were built: the top box sinks no more than
// the soft contacts' law lets it (10% more, or a slop a layer where the law is less: a contact
// within the slop is rigid and rests pushed towards half of it), and it neither moves sideways
// nor turns beyond the rounding of a symmetric solve: a tenth of the slop and 1 mrad. (At 4
// substeps the 1:1000 stacks sank without end, 1 m in 2 s, while the push-out cap also capped
// what a contact could carry: see physics/contact_solver.cpp.)
Outcome massRatios(int steps) {
  const std::vector<Stack> stacks = {
      {"light on heavy 1:1000", {1000, 1}},
      {"heavy on light 1:100", {1, 100}},
      {"plank 1000 kg on two 1 kg", {1, -1000}},
      {"heavy on light 1:1000, 32 substeps", {1, 1000}, 32},
      {"alternating 1/1000 x4, 32 substeps", {1, 1000, 1, 1000}, 32},
      {"heavy on light 1:1000", {1, 1000}},
      {"alternating 1/1000 x4", {1, 1000, 1, 1000}},
  };
  Outcome o;
  o.add(format("%d steps", steps));
  for (const Stack& s : stacks) {
    const StackResult r = runStack(s, steps);
    const float layers = static_cast<float>(s.masses.size());
    const float bound = std::max(1.1f * r.law, layers * rc::kLinearSlop);
    o.add(format("%s: sank %.2g m (law %.2g), drift %.2g m, tilt %.2g rad", s.name, r.sank, r.law,
                 r.drift, r.tilt));
    const bool holds = r.finite && std::abs(r.sank) <= bound && r.drift <= 0.1f * rc::kLinearSlop &&
                       r.tilt <= 1e-3f;
    o.expect(holds, format("%s: sank %.3g m (bound %.3g)", s.name, r.sank, bound));
  }
  return o;
}

// ------------------------------------------------------------------------------ bullets

// Bodies at 1000 m/s in a closed 20 m box of 1 cm walls (a step carries them 16.7 m, 1,667 times
// the walls' thickness): 5 cm circles, boxes, capsules and triangles, restitution 1, friction 0,
// no gravity, half of them bullets; four thin dynamic planks (1 cm x 2 m, 20 kg) float among
// them. None may leave the box, no bullet may pass through a plank (bullets are swept against
// moving bodies), and the kinetic energy may not rise.
Outcome bullets(int count, int steps) {
  constexpr float speed = 1000.0f, wallThickness = 0.01f;
  rc::WorldDef def;
  def.gravity = {0, 0};
  def.enableSleep = false;
  def.bounds = {{-16, -16}, {16, 16}};
  World w(def);
  const AABB interior{{-10, -10}, {10, 10}};
  rc::ShapeDef sd;
  sd.restitution = 1.0f;
  sd.friction = 0.0f;
  addContainer(w, interior, wallThickness, sd);
  rc::Random rng(1000);
  constexpr float plankHalf = 1.0f, plankThick = 0.005f;
  std::vector<BodyId> planks;
  for (Vec2 p : {Vec2{-5, -5}, Vec2{5, -5}, Vec2{-5, 5}, Vec2{5, 5}}) {
    rc::ShapeDef heavy = sd;
    heavy.density = 20.0f / (4.0f * plankHalf * plankThick);
    planks.push_back(w.createBody(dynamicAt(p, {}, rng.uniform(0, kPi))));
    w.createShape(planks.back(), rc::makeBox(plankHalf, plankThick), heavy);
  }
  // A grid of 0.5 m cells away from the planks' discs.
  std::vector<Vec2> cells;
  for (float x = -9.5f; x <= 9.5f; x += 0.5f)
    for (float y = -9.5f; y <= 9.5f; y += 0.5f)
      if (std::abs(std::abs(x) - 5) > 1.2f || std::abs(std::abs(y) - 5) > 1.2f)
        cells.push_back({x, y});
  for (std::size_t i = cells.size() - 1; i > 0; --i)
    std::swap(cells[i], cells[rng.below(static_cast<std::uint32_t>(i + 1))]);
  std::vector<BodyId> bodies;
  for (int i = 0; i < count; ++i) {
    rc::BodyDef bd =
        dynamicAt(cells[static_cast<std::size_t>(i)], speed * direction(rng), rng.uniform(-3, 3));
    bd.bullet = i % 2 == 0;
    const BodyId b = w.createBody(bd);
    switch (i / 2 % 4) {
      case 0:
        w.createShape(b, rc::makeCircle({}, 0.05f), sd);
        break;
      case 1:
        w.createShape(b, rc::makeBox(0.05f, 0.05f), sd);
        break;
      case 2:
        w.createShape(b, rc::makeCapsule({-0.03f, 0}, {0.03f, 0}, 0.03f), sd);
        break;
      default:
        w.createShape(b, rc::makeTriangle({-0.05f, -0.04f}, {0.05f, -0.04f}, {0, 0.06f}), sd);
    }
    bodies.push_back(b);
  }
  const double start = w.energy();
  double highest = start;
  long escapes = 0, brokenCount = 0, quarantined = 0;
  long crossings[2] = {0, 0};  // through a plank: [0] plain bodies, [1] bullets
  std::vector<Vec2> before(bodies.size());
  std::vector<rc::Transform> plankBefore(planks.size());
  std::vector<char> escaped(bodies.size(), 0);
  for (int k = 0; k < steps; ++k) {
    for (std::size_t i = 0; i < bodies.size(); ++i)
      before[i] = w.worldCenter(bodies[i]);
    for (std::size_t j = 0; j < planks.size(); ++j)
      plankBefore[j] = w.transform(planks[j]);
    w.step(kStep);
    quarantined += static_cast<long>(w.quarantineEvents().size());
    highest = std::max(highest, w.energy());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Vec2 now = w.worldCenter(bodies[i]);
      if (!escaped[i] && outside(interior, now)) {
        escaped[i] = 1;
        ++escapes;
      }
      brokenCount += !finite(w, bodies[i]);
      // Through a plank: on the other side of its mid-line in its own frame, within its length
      // both times, and clear of it (more than a body's size) both times.
      for (std::size_t j = 0; j < planks.size(); ++j) {
        const Vec2 a = rc::invApply(plankBefore[j], before[i]);
        const Vec2 b = rc::invApply(w.transform(planks[j]), now);
        if (std::abs(a.x) < plankHalf && std::abs(b.x) < plankHalf && a.y * b.y < 0 &&
            std::abs(a.y) > 0.06f && std::abs(b.y) > 0.06f)
          ++crossings[w.isBullet(bodies[i]) ? 1 : 0];
      }
    }
  }
  Outcome o;
  o.add(format("%d bodies at %.0f m/s, %d steps", count, speed, steps));
  o.add(format("escapes %ld, through a plank: bullets %ld, plain bodies %ld", escapes, crossings[1],
               crossings[0]));
  o.add(format("kinetic energy highest %.6f x start", highest / start));
  o.expect(escapes == 0, "a body left the box");
  o.expect(crossings[1] == 0, "a bullet passed through a plank");
  o.expect(brokenCount == 0 && quarantined == 0, "a body not finite or quarantined");
  // Restitution 1 and friction 0 keep the energy at best; the bound is the unit tests' 0.1%
  // (World.FastDiscsEnergyNeverRises) for the rounding of many collisions.
  o.expect(highest <= 1.001 * start, "kinetic energy rose");
  return o;
}

// --------------------------------------------------------------------------- far away

// The same scene at the origin and 10 km out along both axes: a base-10 pyramid, a tower of ten
// boxes and a box sliding at 10 m/s on friction 0.5 (it stops after v^2 / (2 mu g) = 10 m),
// sleeping off. Positions are kept in double and contacts computed relative to a body, so the
// far scene must follow the near one closely, though a float coordinate out there is 1 mm
// coarse (2^-10 m between floats at 1e4).
Outcome farAway(int steps) {
  struct Run {
    std::vector<std::array<double, 2>> relative;
    float topDrift = 0, apexSank = 0, slid = 0;
    bool finite = true;
  };
  auto run = [steps](Vec2 origin) {
    rc::WorldDef def;
    def.enableSleep = false;
    def.bounds = {origin - Vec2{64, 64}, origin + Vec2{64, 64}};
    World w(def);
    rc::ShapeDef sd;
    sd.friction = 0.5f;
    rc::BodyDef groundDef;
    groundDef.position = origin + Vec2{0, -1};
    w.createShape(w.createBody(groundDef), rc::makeBox(40, 1), sd);
    std::vector<BodyId> boxes;
    auto add = [&](Vec2 p, Vec2 v = {}) {
      boxes.push_back(w.createBody(dynamicAt(origin + p, v)));
      w.createShape(boxes.back(), rc::makeBox(0.5f, 0.5f), sd);
    };
    for (int row = 0; row < 10; ++row)
      for (int i = 0; i < 10 - row; ++i)
        add({static_cast<float>(i) - 0.5f * static_cast<float>(9 - row) - 10.0f,
             0.5f + static_cast<float>(row)});
    const std::size_t apex = boxes.size() - 1;
    for (int i = 0; i < 10; ++i)
      add({10.0f, 0.5f + static_cast<float>(i)});
    const std::size_t tower = boxes.size() - 1;
    add({20.0f, 0.5f}, {10, 0});
    for (int k = 0; k < steps; ++k)
      w.step(kStep);
    Run r;
    for (BodyId b : boxes) {
      const std::array<double, 2> p = w.precisePosition(b);
      r.relative.push_back({p[0] - origin.x, p[1] - origin.y});
      r.finite = r.finite && finite(w, b);
    }
    r.topDrift = static_cast<float>(std::abs(r.relative[tower][0] - 10.0));
    r.apexSank = static_cast<float>(9.5 - r.relative[apex][1]);
    r.slid = static_cast<float>(r.relative.back()[0] - 20.0);
    return r;
  };
  const Run near = run({0, 0}), far = run({10000, 10000});
  double worst = 0;
  for (std::size_t i = 0; i < near.relative.size(); ++i)
    worst = std::max(worst, std::hypot(near.relative[i][0] - far.relative[i][0],
                                       near.relative[i][1] - far.relative[i][1]));
  Outcome o;
  o.add(format("%d steps, worst box %.3g m from its place at the origin", steps, worst));
  o.add(
      format("pyramid top sank %.4f m near, %.4f m far; tower top drift %.2g m near, %.2g m "
             "far",
             near.apexSank, far.apexSank, near.topDrift, far.topDrift));
  o.add(format("slide %.4f m near, %.4f m far (v^2/(2 mu g) = 10)", near.slid, far.slid));
  // One float step out there: what the world's float transforms (the broadphase, the shapes'
  // AABBs) round positions to; the solver works in double and relative coordinates.
  o.expect(worst <= 1e-3, format("a box %.3g m from the near scene's (bound 1 mm)", worst));
  o.expect(near.finite && far.finite, "a body not finite");
  return o;
}

// ------------------------------------------------------------------------------ one point

struct OnePointResult {
  float fastest = 0, deepest = 0;  // over the run; the deepest overlap at the end
  int separatedAt = -1;            // the first step after which no overlap is deeper than 2 slops
  int asleepAt = -1;               // the first step with nothing awake
  float deepestAsleep = 0;         // the deepest overlap then
  long escapes = 0;
  bool finite = true;
  double seconds = 0;
};

// `count` circles of 0.25 m all created at the same point, at rest, in a closed 40 m box, no
// gravity, restitution from 0 to 1. Every pair overlaps fully, and coincident centres give no
// normal: the narrowphase moves each shape a fraction of a millimetre in a direction of its own
// (physics/contact.cpp), so the crowd is pushed apart in every direction.
OnePointResult runOnePoint(int count, int steps) {
  rc::WorldDef def;
  def.gravity = {0, 0};
  def.bounds = {{-32, -32}, {32, 32}};
  World w(def);
  const AABB interior{{-20, -20}, {20, 20}};
  addContainer(w, interior, 1.0f);
  rc::Random rng(1001);
  std::vector<BodyId> bodies;
  for (int i = 0; i < count; ++i) {
    bodies.push_back(w.createBody(dynamicAt({0.0f, 0.0f})));
    rc::ShapeDef sd;
    sd.restitution = rng.uniform();
    w.createShape(bodies.back(), rc::makeCircle({}, 0.25f), sd);
  }
  OnePointResult r;
  std::vector<char> out(bodies.size(), 0);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 1; k <= steps; ++k) {
    w.step(kStep);
    r.finite = r.finite && w.quarantineEvents().empty();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      r.fastest = std::max(r.fastest, rc::length(w.linearVelocity(bodies[i])));
      r.finite = r.finite && finite(w, bodies[i]);
      out[i] |= outside(interior, w.worldCenter(bodies[i]));
    }
    if (r.separatedAt < 0 && deepestPenetration(w) <= 2.0f * rc::kLinearSlop) r.separatedAt = k;
    if (r.asleepAt < 0 && w.awakeBodyCount() == 0) {
      r.asleepAt = k;
      r.deepestAsleep = deepestPenetration(w);
    }
  }
  r.deepest = deepestPenetration(w);
  r.escapes = std::count(out.begin(), out.end(), 1);
  r.seconds = seconds(start);
  return r;
}

// Circles born at one point must come apart: no NaN, none out of the box, no overlap deeper
// than 2 slops at the end, and never faster than the push-out speed (WorldDef::maxPushoutSpeed,
// 3 m/s: overlapping bodies are pushed apart at most that fast and the relax pass takes the push
// back, so a crowd that comes apart faster is exploding). Measured: 30 apart after 300 steps,
// 100 after 540, 300 after 1,080, at up to 1.8 m/s; none asleep while a quarter of a diameter
// deep. A thousand is a known failure: they spread at 3 cm/s and are not apart by the end.
Outcome onePoint(int count, int steps, int knownCount, int knownSteps) {
  Outcome o;
  auto judge = [&](int n, int k, bool known) {
    const OnePointResult r = runOnePoint(n, k);
    o.add(
        format("%d circles, %d steps in %.1f s: apart after step %d (deepest at the end %.2g m), "
               "fastest %.2f m/s, asleep from step %d, escapes %ld",
               n, k, r.seconds, r.separatedAt, r.deepest, r.fastest, r.asleepAt, r.escapes));
    const bool apart = r.separatedAt > 0 && r.deepest <= 2.0f * rc::kLinearSlop;
    const float pushout = rc::WorldDef{}.maxPushoutSpeed;
    const std::string what = format("%d circles at one point: apart %s, fastest %.2f m/s", n,
                                    apart ? "yes" : "no", r.fastest);
    o.expect(r.finite, "a body not finite or quarantined");
    o.expect(r.escapes == 0, "a circle left the box");
    o.expect(r.fastest <= pushout, format("fastest %.2f m/s (bound %.1f)", r.fastest, pushout));
    // Asleep only once no contact is deeper than a quarter of a diameter (physics/island.cpp).
    o.expect(r.asleepAt < 0 || r.deepestAsleep <= 0.125f,
             format("asleep at step %d %.3g m deep (bound 0.125 m)", r.asleepAt, r.deepestAsleep));
    if (known)
      o.expectKnownFailure(apart, what);
    else
      o.expect(apart, what);
  };
  judge(count, steps, false);
  if (knownCount > 0) judge(knownCount, knownSteps, true);
  return o;
}

// ------------------------------------------------------------------------------ pressure

struct PressureResult {
  float deepest = 0;    // the deepest overlap of any contact, sampled every 10 steps (m)
  float law = 0;        // the soft contacts' law for the bottom of a column (m)
  float deepestAt = 0;  // height of the deepest overlap (m)
  float settled = 0;    // the deepest overlap at the end (m)
  long escapes = 0;     // circles out of the box, or above the piston's underside
  double sank = 0;      // how far the piston went down in the run's second half (m)
  float pistonAt = 0;   // the piston's underside at the end (m)
  bool finite = true;
};

// The pressure case's scene, the same in both engines: `count` circles of 0.10 to 0.15 m
// (density 1, radii drawn in order from one seed) on a grid 0.32 m apart, 31 to a row (the
// largest never start touching), in a 10 m wide box of 2 m walls; above them a piston, a
// fixed-rotation box 5 cm narrower than the box (no circle fits past it).
struct PressurePile {
  static constexpr int perRow = 31;
  static constexpr float wallThickness = 2.0f;
  static constexpr float pistonHalfWidth = 4.975f, pistonHalfHeight = 0.25f;
  AABB interior{{-5, 0}, {5, 30}};
  std::vector<Vec2> centres;
  std::vector<float> radii;
  Vec2 piston;  // its centre, 0.5 m above the top row

  explicit PressurePile(int count) {
    rc::Random rng(1002);
    float top = 0;
    for (int i = 0; i < count; ++i) {
      centres.push_back({-4.8f + 0.32f * static_cast<float>(i % perRow),
                         0.2f + 0.32f * static_cast<float>(i / perRow)});
      radii.push_back(rng.uniform(0.10f, 0.15f));
      top = std::max(top, centres.back().y);
    }
    piston = {0, top + 0.5f};
  }
  static float pistonDensity(float mass) {
    return mass / (2.0f * pistonHalfWidth * 2.0f * pistonHalfHeight);
  }
  // The piston pushed down by a force rising over a second to `force`.
  static float pistonForce(float force, double time) {
    return -force * static_cast<float>(std::min(1.0, time));
  }
  // A circle out of the box, or above the piston's underside.
  bool out(Vec2 centre, float pistonY) const {
    return outside(interior, centre) || centre.y > pistonY - pistonHalfHeight;
  }
};

// The pile under gravity, pressed by a piston of `pistonMass` pushed down by up to `force` N.
PressureResult runPressure(int count, int steps, float pistonMass, float force) {
  rc::WorldDef def;
  def.bounds = {{-16, -8}, {16, 40}};
  World w(def);
  const PressurePile pile(count);
  addContainer(w, pile.interior, PressurePile::wallThickness);
  std::vector<BodyId> circles;
  float lightest = 1e9f, weight = 0;
  for (int i = 0; i < count; ++i) {
    circles.push_back(w.createBody(dynamicAt(pile.centres[static_cast<std::size_t>(i)])));
    w.createShape(circles.back(), rc::makeCircle({}, pile.radii[static_cast<std::size_t>(i)]));
    lightest = std::min(lightest, w.mass(circles.back()));
    weight += w.mass(circles.back()) * -def.gravity.y;
  }
  rc::BodyDef pistonDef = dynamicAt(pile.piston);
  pistonDef.fixedRotation = true;
  const BodyId piston = w.createBody(pistonDef);
  rc::ShapeDef pistonShape;
  pistonShape.density = PressurePile::pistonDensity(pistonMass);
  w.createShape(piston, rc::makeBox(PressurePile::pistonHalfWidth, PressurePile::pistonHalfHeight),
                pistonShape);
  w.addForceField([&](rc::ForceStage& s) {
    s.addForce(piston, {0, PressurePile::pistonForce(force, s.time())});
  });
  PressureResult r;
  std::vector<char> out(circles.size(), 0);
  // A column's bottom contact carries the column and its share of the piston, over the lightest
  // circle's mass (see the mass-ratio case).
  const float omega = 2.0f * kPi * def.contactHertz;
  r.law = (weight + pistonMass * -def.gravity.y + force) /
          static_cast<float>(PressurePile::perRow) / lightest / (omega * omega);
  double pistonAtHalf = 0;
  for (int k = 1; k <= steps; ++k) {
    w.step(kStep);
    r.finite = r.finite && w.quarantineEvents().empty();
    if (k % 10 == 0 || k == steps) {
      for (const World::ContactPointView& p : w.contactPoints())
        if (-p.separation > r.deepest) {
          r.deepest = -p.separation;
          r.deepestAt = p.point.y;
        }
      const float pistonY = w.worldCenter(piston).y;
      for (std::size_t i = 0; i < circles.size(); ++i) {
        r.finite = r.finite && finite(w, circles[i]);
        out[i] |= pile.out(w.worldCenter(circles[i]), pistonY);
      }
    }
    if (k == steps / 2) pistonAtHalf = w.precisePosition(piston)[1];
  }
  r.finite = r.finite && finite(w, piston);
  r.escapes = std::count(out.begin(), out.end(), 1);
  r.sank = pistonAtHalf - w.precisePosition(piston)[1];
  r.settled = deepestPenetration(w);
  r.pistonAt = w.worldCenter(piston).y - PressurePile::pistonHalfHeight;
  return r;
}

// The same pile and piston in Box2D 2.4.1 (8 velocity and 3 position iterations, its testbed's
// defaults), for `steps` steps: the circles out of the box or past the piston, the independent
// measure of what a load does. Its polygons carry a 0.01 m skin: the piston is given 0.01 m
// smaller so that its surface is where ours is (the walls are thick enough not to care).
long box2dPressureEscapes(int count, int steps, float pistonMass, float force) {
  b2World w(b2Vec2(0.0f, -10.0f));
  const PressurePile pile(count);
  b2BodyDef groundDef;
  b2Body* ground = w.CreateBody(&groundDef);
  for (const Wall& wall : containerWalls(pile.interior, PressurePile::wallThickness)) {
    b2PolygonShape box;
    box.SetAsBox(wall.half.x, wall.half.y, b2Vec2(wall.centre.x, wall.centre.y), 0.0f);
    ground->CreateFixture(&box, 0.0f);
  }
  std::vector<b2Body*> circles;
  for (int i = 0; i < count; ++i) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(pile.centres[static_cast<std::size_t>(i)].x,
                    pile.centres[static_cast<std::size_t>(i)].y);
    b2CircleShape circle;
    circle.m_radius = pile.radii[static_cast<std::size_t>(i)];
    b2FixtureDef fd;
    fd.shape = &circle;
    fd.density = 1.0f;
    fd.friction = rc::ShapeDef{}.friction;
    circles.push_back(w.CreateBody(&bd));
    circles.back()->CreateFixture(&fd);
  }
  b2BodyDef pistonDef;
  pistonDef.type = b2_dynamicBody;
  pistonDef.fixedRotation = true;
  pistonDef.position.Set(pile.piston.x, pile.piston.y);
  b2Body* piston = w.CreateBody(&pistonDef);
  b2PolygonShape pistonBox;
  pistonBox.SetAsBox(PressurePile::pistonHalfWidth - b2_polygonRadius,
                     PressurePile::pistonHalfHeight - b2_polygonRadius);
  b2FixtureDef pf;
  pf.shape = &pistonBox;
  pf.density = PressurePile::pistonDensity(pistonMass);
  pf.friction = rc::ShapeDef{}.friction;
  piston->CreateFixture(&pf);
  std::vector<char> out(circles.size(), 0);
  for (int k = 1; k <= steps; ++k) {
    const double time = static_cast<double>(k - 1) * kStep;
    piston->ApplyForceToCenter(b2Vec2(0.0f, PressurePile::pistonForce(force, time)), true);
    w.Step(kStep, 8, 3);
    if (k % 10 == 0 || k == steps)
      for (std::size_t i = 0; i < circles.size(); ++i) {
        const b2Vec2 c = circles[i]->GetPosition();
        out[i] |= pile.out({c.x, c.y}, piston->GetPosition().y);
      }
  }
  return std::count(out.begin(), out.end(), 1);
}

// Confined circles under pressure: a pile of `count` circles pressed by a 5 kg piston with the
// pile's weight again (doubling the load at the bottom). None may leave the box or get past the
// piston, and the piston must stop. The overlaps are a known failure: the soft contacts' law
// (see the mass-ratio case) lets a contact sink by its load over its own effective mass, and
// force chains gather several columns' load on one contact, so circles overlap by much of a
// radius, where a fifth of the smallest (2 cm) is what a game would want. Then the same pile
// under a 50 kg piston pushed with 5e4 N (70 times the pile's weight): known to give way, and
// (the long run) set beside Box2D 2.4.1 under the same load.
Outcome pressure(int count, int steps, bool withBox2D) {
  Outcome o;
  const float weight = static_cast<float>(count) * 0.0497f * 10.0f;  // mean circle 0.0497 kg
  const PressureResult r = runPressure(count, steps, 5.0f, weight);
  o.add(
      format("%d circles, piston 5 kg + %.0f N, %d steps: deepest overlap %.3g m at y = %.1f "
             "(piston's underside %.1f), %.3g m at the end (a column's bottom by the law "
             "%.3g), escapes %ld, piston sank %.2g m in the second half",
             count, weight, steps, r.deepest, r.deepestAt, r.pistonAt, r.settled, r.law, r.escapes,
             r.sank));
  o.expect(r.finite, "a body not finite or quarantined");
  o.expect(r.escapes == 0, "a circle left the box or got past the piston");
  o.expect(std::abs(r.sank) <= 0.01, format("piston still sinking: %.3g m", r.sank));
  o.expectKnownFailure(r.settled <= 0.02f,
                       format("overlap at the end %.3g m (bound 2 cm)", r.settled));
  const PressureResult over = runPressure(count, steps, 50.0f, 5e4f);
  o.add(
      format("overload (50 kg + 5e4 N): deepest %.3g m (law %.3g), %ld circles out of the box "
             "or past the piston, piston sank %.2g m",
             over.deepest, over.law, over.escapes, over.sank));
  // Box2D 2.4.1 beside us on the short run's pile: at 1,500 circles its contacts pile up by the
  // ten thousand and its pair search (linear in a body's contacts) takes it most of an hour.
  if (withBox2D)
    o.add(format("overload on 600 circles for 600 steps: ours %ld out, Box2D 2.4.1 %ld",
                 runPressure(600, 600, 50.0f, 5e4f).escapes,
                 box2dPressureEscapes(600, 600, 50.0f, 5e4f)));
  o.expectKnownFailure(
      over.finite && over.escapes == 0,
      format("overload: %ld circles out of the box or past the piston", over.escapes));
  return o;
}

// -------------------------------------------------------------------------- random scenes

// A seeded random scene in a closed 20 x 20 m box whose floor's top is y = 0: 60 bodies of every
// solid shape (circles, boxes, capsules, convex polygons, rounded ones, two-shape compounds) from
// 5 cm to 1.8 m across, densities 0.1 to 100 (ratio 1000), restitution 0 to 1 (1 one time in
// ten), friction 0 to 1, velocities up to 20 m/s and 10 rad/s, some bullets, some fixed rotation,
// some under a constant force; gravity down, none, or slanted. Returns the bodies' constant forces
// (zero for most) so the caller can add their work.
struct RandomScene {
  std::vector<BodyId> bodies;
  std::vector<Vec2> forces;
  AABB interior{{-10, 0}, {10, 20}};
};

RandomScene randomScene(World& w, rc::Random& rng) {
  RandomScene scene;
  rc::ShapeDef wall;
  wall.restitution = rng.uniform();
  wall.friction = rng.uniform();
  addContainer(w, scene.interior, 1.0f, wall);
  std::vector<Vec2> cells;  // 2 m cells; every body fits in a 1.8 m disc
  for (int i = 0; i < 100; ++i)
    cells.push_back(
        {-9.0f + 2.0f * static_cast<float>(i % 10), 1.0f + 2.0f * static_cast<float>(i / 10)});
  for (std::size_t i = cells.size() - 1; i > 0; --i)
    std::swap(cells[i], cells[rng.below(static_cast<std::uint32_t>(i + 1))]);
  const float g = rc::length(w.def().gravity);
  for (int i = 0; i < 60; ++i) {
    rc::BodyDef bd = dynamicAt(cells[static_cast<std::size_t>(i)],
                               rng.uniform(0, 20) * direction(rng), rng.uniform(-3, 3));
    bd.angularVelocity = rng.uniform(-10, 10);
    bd.bullet = rng.below(10) == 0;
    bd.fixedRotation = rng.below(10) == 0;
    bd.gravityScale = rng.below(5) == 0 ? rng.uniform(0, 2) : 1.0f;
    const BodyId b = w.createBody(bd);
    rc::ShapeDef sd;
    sd.density = std::pow(10.0f, rng.uniform(-1, 2));
    sd.restitution = rng.below(10) == 0 ? 1.0f : rng.uniform();
    sd.friction = rng.uniform();
    const float size = rng.uniform(0.05f, 0.9f);  // the bounding radius
    switch (rng.below(6)) {
      case 0:
        w.createShape(b, rc::makeCircle({}, size), sd);
        break;
      case 1: {
        const float a = rng.uniform(0.2f, 1.0f);  // aspect: from a plank to a square
        w.createShape(b, rc::makeBox(0.7f * size, 0.7f * size * a), sd);
        break;
      }
      case 2: {
        const float r = size * rng.uniform(0.1f, 0.5f);
        w.createShape(b, rc::makeCapsule({r - size, 0}, {size - r, 0}, r), sd);
        break;
      }
      case 3:
      case 4: {
        // A random convex hull of up to 8 points in the disc; a rounded one every other time.
        Vec2 points[8];
        const int n = 3 + static_cast<int>(rng.below(6));
        for (int j = 0; j < n; ++j)
          points[j] = rng.uniform(0.3f, 1.0f) * size * direction(rng);
        const float rounding = rng.below(2) ? 0.0f : 0.1f * size;
        try {
          w.createShape(b, rc::makePolygon(std::span(points, n), rounding), sd);
        } catch (const rc::InvalidShape&) {  // too thin a hull: a box instead
          w.createShape(b, rc::makeBox(0.5f * size, 0.5f * size), sd);
        }
        break;
      }
      default:
        w.createShape(b, rc::makeCircle({0.5f * size, 0}, 0.5f * size), sd);
        w.createShape(b, rc::makeBox(0.3f * size, 0.3f * size, {-0.4f * size, 0}), sd);
    }
    scene.bodies.push_back(b);
    // One in four pushed by a constant force of up to twice its weight (or 20 N/kg without
    // gravity).
    const float push = rng.below(4) == 0 ? rng.uniform(0, 2) * std::max(g, 10.0f) : 0.0f;
    scene.forces.push_back(push * w.mass(b) * direction(rng));
  }
  return scene;
}

// One seeded scene stepped `steps` times: what rose, what sank, what left.
struct SceneRun {
  double start = 0;     // energy at the start (J): kinetic plus gravity's potential
  double excess = 0;    // the most the energy rose above start + work (J)
  double lift = 0;      // sum of m g 2 slops over the bodies (J)
  float deepest = 0;    // the deepest a body's centre went past a wall's inner face (m)
  int escaped = 0;      // bodies outside the container by more than the margin, ever
  int broken = 0;       // bodies not finite or quarantined
  int excessStep = -1;  // the step of the largest excess
};

SceneRun runRandomScene(std::uint64_t seed, int steps) {
  rc::Random rng(seed * 7919);
  rc::WorldDef def;
  switch (rng.below(4)) {
    case 0:
      def.gravity = {0, 0};
      break;
    case 1:
      def.gravity = {rng.uniform(-5, 5), -rng.uniform(2, 20)};
      break;
    default:
      def.gravity = {0, -10};
  }
  def.bounds = {{-16, -8}, {16, 24}};
  World w(def);
  const RandomScene scene = randomScene(w, rng);
  SceneRun run;
  std::vector<Vec2> origin;
  for (BodyId b : scene.bodies) {
    origin.push_back(w.worldCenter(b));
    run.lift += w.mass(b) * w.gravityScale(b) * rc::length(def.gravity) * 2.0 * rc::kLinearSlop;
  }
  w.addForceField([&scene](rc::ForceStage& s) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (scene.forces[i].x != 0 || scene.forces[i].y != 0)
        s.addForce(scene.bodies[i], scene.forces[i]);
  });
  run.start = w.energy();
  std::vector<char> escaped(scene.bodies.size(), 0), broken(scene.bodies.size(), 0);
  for (int k = 1; k <= steps; ++k) {
    w.step(kStep);
    double work = 0;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const BodyId b = scene.bodies[i];
      const Vec2 c = w.worldCenter(b);
      work += static_cast<double>(scene.forces[i].x) * (c.x - origin[i].x) +
              static_cast<double>(scene.forces[i].y) * (c.y - origin[i].y);
      broken[i] |= !finite(w, b) || !w.isEnabled(b);
      const float depth = pastWall(scene.interior, c);
      run.deepest = std::max(run.deepest, depth);
      // Escaped: past the middle of the 1 m wall, from where its contact pushes it out the
      // other side. Not the face: a light sliver under bodies up to 3 x 10^5 times heavier sinks
      // into the floor by the soft contacts' law (see the mass-ratio case), 23 cm at worst in 200
      // seeds, and comes back out; that depth is reported.
      escaped[i] |= depth > 0.5f;
    }
    const double excess = w.energy() - (run.start + work);
    if (excess > run.excess) {
      run.excess = excess;
      run.excessStep = k;
    }
  }
  run.escaped = static_cast<int>(std::count(escaped.begin(), escaped.end(), 1));
  run.broken = static_cast<int>(std::count(broken.begin(), broken.end(), 1));
  return run;
}

// Energy never rises above its start plus the work of the external forces, beyond a stated
// allowance. Kinetic energy plus gravity's potential (World::energy) is the total; a constant
// force's work on a body is F . (c - c0), exact whatever path it took. Contacts with
// restitution <= 1 and friction only take energy out, but two mechanisms of the engine add a
// little, both measured here (tests/README.md):
//  - the push-out moves overlapping bodies apart without kinetic energy, raising a pile by up
//    to what it overlapped: sum m g 2 slops;
//  - restitution reverses the approach of the substep the impact is in, which for a body
//    speeding up into a surface (falling onto it) is up to g h faster than at the impact.
//    Allowed: 0.1% of the scene's start energy (the worst of 200 seeds is 5e-6; it was 0.3%
//    when restitution reversed the fastest approach of the step's substeps, which gave a body
//    decelerating into a ceiling up to g dt more speed back: an 82 kg body at 17 m/s, 173 J).
// `only`: that seed alone (--seed), 0 for seeds 1 to `seeds`.
Outcome randomScenes(int seeds, int steps, long only) {
  double worstRatio = 0;  // excess over the start energy
  std::uint64_t worstSeed = 0;
  float deepest = 0;
  int escapes = 0, broken = 0, failed = 0;
  std::string failedSeeds;
  const auto first = static_cast<std::uint64_t>(only > 0 ? only : 1);
  const auto last = only > 0 ? first : static_cast<std::uint64_t>(seeds);
  for (std::uint64_t seed = first; seed <= last; ++seed) {
    const SceneRun run = runRandomScene(seed, steps);
    const double ratio = run.excess / run.start;
    if (ratio > worstRatio) {
      worstRatio = ratio;
      worstSeed = seed;
    }
    deepest = std::max(deepest, run.deepest);
    escapes += run.escaped;
    broken += run.broken;
    const bool bad = run.excess > run.lift + 0.001 * run.start || run.escaped || run.broken;
    if (bad && failed++ < 5) failedSeeds += format(" %llu", static_cast<unsigned long long>(seed));
  }
  Outcome o;
  o.add(only > 0 ? format("seed %ld x %d steps", only, steps)
                 : format("%d seeds x %d steps", seeds, steps));
  o.add(format("energy above start + work: worst %.2g of the start (seed %llu)", worstRatio,
               static_cast<unsigned long long>(worstSeed)));
  o.add(format("deepest centre past a wall %.3f m, escapes %d, not finite %d", deepest, escapes,
               broken));
  o.expect(failed == 0, format("%d seeds broke a bound (first:%s)", failed, failedSeeds.c_str()));
  return o;
}

// ------------------------------------------------------------------------------ the suite

struct Options {
  bool longRun = false;
  std::vector<std::string> only;  // --case: run these alone
  int soakBodies = 0;             // 0: the run's default
  long soakSteps = 0;
  long seed = 0;  // random-scenes: this seed alone (0: all)
};

struct Case {
  const char* name;
  std::function<Outcome()> run;
};

std::vector<Case> cases(const Options& opt) {
  const bool L = opt.longRun;
  // Short: seconds in Release; under ASan+UBSan, whose cost is 10x, a tenth of the steps of
  // the same scenes where that still tests what the case claims, fewer bodies where it would not.
  auto steps = [L](int shortSteps, int longSteps) {
    return L ? longSteps : std::max(60, rc::testing::casesUnderSanitizers(shortSteps));
  };
  const int soakBodies = opt.soakBodies ? opt.soakBodies : (L ? 5000 : 1000);
  const long soakSteps = opt.soakSteps ? opt.soakSteps : (L ? 1000000L : steps(1500, 0));
  return {
      {"soak", [=] { return soak(soakBodies, soakSteps, L); }},
      // Seven small stacks cost little, and the known collapses take more than a second.
      {"mass-ratio", [=] { return massRatios(L ? 36000 : 600); }},
      {"bullets", [=] { return bullets(200, steps(300, 6000)); }},
      {"far-away", [=] { return farAway(steps(600, 6000)); }},
      // The counts shrink under the sanitizers instead of the steps: a crowd needs its steps to
      // come apart, a pile to settle under its piston.
      {"one-point",
       [=] {
         if (L) return onePoint(300, 1800, 1000, 600);
         return rc::testing::kSanitized ? onePoint(30, 400, 0, 0) : onePoint(100, 900, 0, 0);
       }},
      {"pressure",
       [=] {
         if (L) return pressure(1500, 6000, true);
         return pressure(rc::testing::kSanitized ? 150 : 600, 600, false);
       }},
      {"random-scenes",
       [=] {
         if (L) return randomScenes(200, 3600, opt.seed);
         return randomScenes(rc::testing::kSanitized ? 2 : 10, 600, opt.seed);
       }},
  };
}

int run(const Options& opt) {
  int failed = 0, ran = 0, known = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const Case& c : cases(opt)) {
    if (!opt.only.empty() && std::find(opt.only.begin(), opt.only.end(), c.name) == opt.only.end())
      continue;
    const auto t = std::chrono::steady_clock::now();
    const Outcome o = c.run();
    ++ran;
    std::string verdict = "PASS";
    for (const std::string& k : o.known)
      verdict += "; KNOWN: " + k;
    known += static_cast<int>(o.known.size());
    if (!o.broken.empty()) {
      ++failed;
      verdict = "FAIL:";
      for (const std::string& b : o.broken)
        verdict += " " + b + ";";
    }
    std::printf("case %s: %s (%.1f s) -> %s\n", c.name, o.figures.c_str(), seconds(t),
                verdict.c_str());
    std::fflush(stdout);
  }
  if (ran == 0) {
    std::fprintf(stderr, "stress: no case is named that (try --help)\n");
    return 2;
  }
  std::printf("stress: %d cases, %d failed, %d known failures, %.1f s (%s run)\n", ran, failed,
              known, seconds(start), opt.longRun ? "long" : "short");
  return failed ? 1 : 0;
}

}  // namespace stress

int main(int argc, char** argv) {
  stress::Options opt;
  auto number = [&](int& i, const char* name) {
    char* end = nullptr;
    const long v = i + 1 < argc ? std::strtol(argv[i + 1], &end, 10) : 0;
    if (i + 1 >= argc || *end != '\0' || v <= 0) {
      std::fprintf(stderr, "stress: %s needs a whole number above 0\n", name);
      std::exit(2);
    }
    ++i;
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--long") {
      opt.longRun = true;
    } else if (a == "--case" && i + 1 < argc) {
      opt.only.push_back(argv[++i]);
    } else if (a == "--soak-bodies") {
      opt.soakBodies = static_cast<int>(number(i, "--soak-bodies"));
    } else if (a == "--soak-steps") {
      opt.soakSteps = number(i, "--soak-steps");
    } else if (a == "--seed") {
      opt.seed = number(i, "--seed");
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: stress [--long] [--case NAME]... [--soak-bodies N] [--soak-steps N] [--seed N]\n"
          "The stability stress suite: one line per case with its figures and PASS or FAIL;\n"
          "exit 1 when a case fails. Short by default (seconds); --long for the 10^6-step soak\n"
          "of 5,000 bodies and longer versions of every case (the ctest label stress).\n"
          "Cases: soak, mass-ratio, bullets, far-away, one-point, pressure, random-scenes.\n"
          "--seed N: random-scenes replays that seed alone (the seed a failure names).\n");
      return 0;
    } else {
      std::fprintf(stderr, "stress: unknown option '%s' (try --help)\n", a.c_str());
      return 2;
    }
  }
  return stress::run(opt);
}
