#include <cmath>
#include <cstdio>

#include "game/cli.h"
#include "physics/collide.h"
#include "physics/distance.h"
#include "physics/raycast.h"
#include "physics/shapes.h"
#include "physics/toi.h"

namespace game {
namespace {

int failures = 0;

// Prints one check: what was computed, what theory says, and whether they agree.
void check(const char* what, double got, double expected, double tolerance) {
  bool ok = std::fabs(got - expected) <= tolerance;
  if (!ok) ++failures;
  std::printf("  %-52s %12.7f  expected %12.7f  %s\n", what, got, expected, ok ? "ok" : "MISMATCH");
}

}  // namespace

int runDemo(std::span<const std::string_view> args) {
  for (std::string_view a : args) {
    if (a == "--help" || a == "-h") {
      std::puts(
          "usage: ricochet demo\n"
          "Builds a few shapes, runs the geometry core on them and prints each result beside the\n"
          "value worked out by hand. Exits 1 if any result disagrees.");
      return 0;
    }
    std::fprintf(stderr, "ricochet demo: unknown option '%.*s'\n", static_cast<int>(a.size()),
                 a.data());
    return 2;
  }
  constexpr double pi = 3.14159265358979323846;
  std::puts("Mass properties at density 1 kg/m^2 (inertia about the centre of mass):");
  rc::MassData disc = rc::computeMass(rc::makeCircle({0, 0}, 0.5f), 1.0f);
  check("circle r=0.5: mass = pi r^2", disc.mass, pi * 0.25, 1e-5);
  check("circle r=0.5: inertia = m r^2 / 2", disc.inertia, pi * 0.25 * 0.25 / 2, 1e-6);
  rc::MassData box = rc::computeMass(rc::makeBox(1.0f, 0.5f), 1.0f);
  check("box 2x1: inertia = m (w^2 + h^2) / 12", box.inertia, 2.0 * 5.0 / 12.0, 1e-5);
  rc::MassData obox = rc::computeMass(rc::makeOrientedBox(1.0f, 0.5f, {3, 4}, 0.7f), 1.0f);
  check("same box rotated 0.7 rad at (3,4): inertia", obox.inertia, 2.0 * 5.0 / 12.0, 1e-4);
  check("  ... centre x", obox.center.x, 3.0, 1e-5);
  rc::MassData tri = rc::computeMass(rc::makeTriangle({0, 0}, {3, 0}, {0, 3}), 1.0f);
  check("right triangle legs 3: area = 4.5", tri.area, 4.5, 1e-5);
  check("  ... centroid x = 1", tri.center.x, 1.0, 1e-5);
  rc::MassData cap = rc::computeMass(rc::makeCapsule({-1, 0}, {1, 0}, 0.5f), 1.0f);
  check("capsule length 2 r=0.5: area = 2 + pi/4", cap.area, 2.0 + pi / 4, 1e-5);

  std::puts("\nQueries:");
  rc::Shape unit = rc::makeCircle({0, 0}, 1.0f);
  rc::CastOutput ray = rc::rayCast(unit, {}, {{-5, 0}, {10, 0}, 1.0f});
  check("ray (-5,0)+t(10,0) vs unit circle: fraction 0.4", ray.fraction, 0.4, 1e-6);
  check("  ... normal x = -1", ray.normal.x, -1.0, 1e-6);
  rc::CastOutput wall = rc::rayCast(rc::makeBox(0.5f, 2.0f), {{3, 0}, rc::Rot::fromAngle(0.3f)},
                                    {{0, 0}, {10, 0}, 1.0f});
  check("ray along x vs box tilted 0.3 rad at x=3: hit x", wall.point.x, 3.0 - 0.5 / std::cos(0.3),
        1e-5);
  rc::DistanceOutput gap = rc::shapeDistance(unit, {}, rc::makeBox(1, 1), {{4, 0.5f}, {}});
  check("unit circle to box 2x2 at (4,0.5): distance 2", gap.distance, 2.0, 1e-5);
  rc::CastOutput swept = rc::sweptCircles({0, 0}, 0.5f, {10, 0}, {5, 0}, 0.5f, {0, 0});
  check("circle r=.5 moving 10 m at circle 5 m away: t 0.4", swept.fraction, 0.4, 1e-6);
  rc::CastOutput far = rc::sweptCircles({0, 0}, 0.05f, {1e5f, 0}, {5e4f, 0}, 0.05f, {0, 0});
  check("r=.05 circles 1e6 radii apart: t = (5e4-0.1)/1e5", far.fraction, (5e4 - 0.1) / 1e5, 1e-7);
  rc::Manifold rest = rc::collide(rc::makeBox(5, 0.5f), {{0, -0.5f}, {}}, rc::makeBox(0.5f, 0.5f),
                                  {{0, 0.49f}, {}});
  check("box resting 1 cm into the ground: contact points", rest.pointCount, 2, 0);
  check("  ... separation -0.01 m", rest.points[0].separation, -0.01, 1e-6);
  std::printf("%s\n", failures == 0 ? "All results agree with theory." : "Some results disagree.");
  return failures == 0 ? 0 : 1;
}

}  // namespace game
