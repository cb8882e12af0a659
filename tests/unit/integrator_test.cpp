// The integrators (physics/integrate.h) against the theory: convergence orders fitted over
// eight halvings of the step, stability limits on the harmonic oscillator, energy and angular
// momentum on a Kepler orbit, and free fall against the closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "physics/integrate.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace integrator_test {

using rc::Integrator;

// The harmonic oscillator q'' = -omega^2 q.
template <class T>
auto oscillator(T omega) {
  return [omega](std::span<const T> q, std::span<const T>, T, std::span<T> a) {
    a[0] = -omega * omega * q[0];
  };
}

// Error of the state (q, v / omega) at time tEnd against the closed form, from q = 1, v = 0.
long double oscillatorError(Integrator m, long double h, long double tEnd) {
  long double q[1] = {1}, v[1] = {0};
  rc::IntegratorScratch<long double> scratch;
  const long steps = std::lround(tEnd / h);
  auto accel = oscillator<long double>(1);
  for (long k = 0; k < steps; ++k)
    rc::integrate<long double>(m, q, v, static_cast<long double>(k) * h, h, accel, scratch);
  const long double t = static_cast<long double>(steps) * h;
  return std::hypot(q[0] - std::cos(t), v[0] + std::sin(t));
}

struct Fit {
  double slope, correlation;
};
// Least squares of log2(error) against log2(h).
Fit fitOrder(const std::vector<double>& h, const std::vector<double>& err) {
  const double n = static_cast<double>(h.size());
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log2(h[i]), y = std::log2(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    syy += y * y;
    sxy += x * y;
  }
  const double cov = sxy - sx * sy / n, vx = sxx - sx * sx / n, vy = syy - sy * sy / n;
  return {cov / vx, cov / std::sqrt(vx * vy)};
}

// Each method's slope over nine step sizes (eight halvings), in long double so that rounding
// stays far below the smallest error. The largest step is small enough for the leading error
// term to dominate (explicit Euler's error is ~ h t / 2, so its steps start smaller).
TEST(Integrator, ConvergenceOrderOnTheHarmonicOscillator) {
  struct Case {
    Integrator method;
    double expected, firstStep;
  };
  const Case cases[] = {{Integrator::explicitEuler, 1, 1.0 / 64},
                        {Integrator::semiImplicitEuler, 1, 1.0 / 64},
                        {Integrator::velocityVerlet, 2, 1.0 / 16},
                        {Integrator::rk4, 4, 1.0 / 8}};
  for (const Case& c : cases) {
    std::vector<double> hs, errs;
    for (int k = 0; k <= 8; ++k) {
      const double h = c.firstStep / static_cast<double>(1 << k);
      hs.push_back(h);
      errs.push_back(static_cast<double>(oscillatorError(c.method, h, 2.0L)));
    }
    const Fit fit = fitOrder(hs, errs);
    const std::string name(rc::integratorName(c.method));
    std::printf("%-20s slope %.4f correlation %.6f\n", name.c_str(), fit.slope, fit.correlation);
    EXPECT_NEAR(fit.slope, c.expected, 0.02 * c.expected) << name;
    EXPECT_GT(fit.correlation, 0.99) << name;
    // Halving the step divides the error by 2^order at the small end too.
    EXPECT_NEAR(std::log2(errs[7] / errs[8]), c.expected, 0.02 * c.expected) << name;
  }
}

// The largest amplitude sqrt(q^2 + (v / omega)^2) over `steps` steps at z = h omega.
double peakAmplitude(Integrator m, double z, int steps) {
  double q[1] = {1}, v[1] = {0};
  rc::IntegratorScratch<double> scratch;
  auto accel = oscillator<double>(1);
  double peak = 1;
  for (int k = 0; k < steps && peak < 1e30; ++k) {
    rc::integrate<double>(m, q, v, 0.0, z, accel, scratch);
    peak = std::max(peak, std::hypot(q[0], v[0]));
  }
  return peak;
}

TEST(Integrator, StabilityLimits) {
  // Symplectic Euler and Verlet: bounded for z < 2, growing for z > 2 (by 1.22 per step at
  // z = 2.01). Symplectic Euler keeps the ellipse q^2 + v^2 - z q v = 1 exactly, whose largest
  // radius is 1 / sqrt(1 - z / 2) = 14.14 at z = 1.99; Verlet keeps |q| <= 1 and
  // q^2 + v^2 / (1 - z^2 / 4) = 1, largest radius 1 / sqrt(1 - z^2 / 4) = 10.0.
  const double zs = 1.99;
  EXPECT_LT(peakAmplitude(Integrator::semiImplicitEuler, zs, 100000),
            (1 + 1e-9) / std::sqrt(1 - zs / 2));
  EXPECT_LT(peakAmplitude(Integrator::velocityVerlet, zs, 100000),
            (1 + 1e-9) / std::sqrt(1 - zs * zs / 4));
  for (Integrator m : {Integrator::semiImplicitEuler, Integrator::velocityVerlet})
    EXPECT_GT(peakAmplitude(m, 2.01, 1000), 1e30) << rc::integratorName(m);
  // RK4: |R(iz)| < 1 up to z = 2 sqrt(2) = 2.83 (0.979 at 2.82, 1.19 at 2.9).
  EXPECT_LT(peakAmplitude(Integrator::rk4, 2.82, 100000), 1.0 + 1e-12);
  EXPECT_GT(peakAmplitude(Integrator::rk4, 2.9, 1000), 1e30);
  // Explicit Euler: the amplitude grows by exactly sqrt(1 + z^2) per step, at any step.
  for (double z : {0.01, 0.1, 1.0, 2.5}) {
    double q[1] = {1}, v[1] = {0};
    rc::IntegratorScratch<double> scratch;
    auto accel = oscillator<double>(1);
    for (int k = 0; k < 100; ++k) {
      const double before = std::hypot(q[0], v[0]);
      rc::integrate<double>(Integrator::explicitEuler, q, v, 0.0, z, accel, scratch);
      ASSERT_NEAR(std::hypot(q[0], v[0]) / before, std::sqrt(1 + z * z), 1e-14) << z;
    }
  }
}

// Kepler orbit with GM = 1, a = 1 and e = 0.6 from periapsis, 2,000 steps per orbit, 50 orbits,
// in double. Energy error sampled every step; early = orbits 1-5, late = orbits 46-50.
struct OrbitStats {
  double earlyMaxEnergyError = 0, lateMaxEnergyError = 0, finalEnergyError = 0;
  // At the end of orbit 5 and orbit 50: the same phase, so only the secular part differs.
  double energyErrorAfter5 = 0, energyErrorAfter50 = 0;
  double maxAngularMomentumError = 0;
};

OrbitStats kepler(Integrator m) {
  const double e = 0.6, rp = 1 - e, vp = std::sqrt((1 + e) / (1 - e));
  double q[2] = {rp, 0}, v[2] = {0, vp};
  const double energy0 = -0.5, momentum0 = rp * vp;
  auto gravity = [](std::span<const double> x, std::span<const double>, double,
                    std::span<double> a) {
    const double r2 = x[0] * x[0] + x[1] * x[1], inv3 = 1.0 / (r2 * std::sqrt(r2));
    a[0] = -x[0] * inv3;
    a[1] = -x[1] * inv3;
  };
  rc::IntegratorScratch<double> scratch;
  const int perOrbit = 2000, orbits = 50;
  const double h = 2 * std::numbers::pi / perOrbit;
  OrbitStats s;
  for (int k = 0; k < perOrbit * orbits; ++k) {
    rc::integrate<double>(m, q, v, k * h, h, gravity, scratch);
    const double energy = 0.5 * (v[0] * v[0] + v[1] * v[1]) - 1 / std::hypot(q[0], q[1]);
    const double dE = energy - energy0;
    if (k < 5 * perOrbit) s.earlyMaxEnergyError = std::max(s.earlyMaxEnergyError, std::abs(dE));
    if (k >= (orbits - 5) * perOrbit)
      s.lateMaxEnergyError = std::max(s.lateMaxEnergyError, std::abs(dE));
    s.finalEnergyError = dE;
    if (k == 5 * perOrbit - 1) s.energyErrorAfter5 = dE;
    if (k == orbits * perOrbit - 1) s.energyErrorAfter50 = dE;
    const double momentum = q[0] * v[1] - q[1] * v[0];
    s.maxAngularMomentumError =
        std::max(s.maxAngularMomentumError, std::abs(momentum - momentum0) / momentum0);
  }
  return s;
}

TEST(Integrator, KeplerOrbitEnergyAndAngularMomentum) {
  for (Integrator m : {Integrator::semiImplicitEuler, Integrator::velocityVerlet}) {
    const OrbitStats s = kepler(m);
    const std::string name(rc::integratorName(m));
    // Symplectic: the energy error oscillates and does not grow.
    EXPECT_LE(s.lateMaxEnergyError, 1.1 * s.earlyMaxEnergyError) << name;
    // A central force: both kick and drift keep q x v exactly, up to rounding.
    EXPECT_LT(s.maxAngularMomentumError, 1e-12) << name;
  }
  // RK4 is far more accurate per step but drifts: at the same phase of the orbit its error
  // grows in proportion to time (ten times the orbits, ten times the error), one way.
  const OrbitStats rk4 = kepler(Integrator::rk4);
  std::printf("rk4 energy error after 5 orbits %.3g, after 50 %.3g\n", rk4.energyErrorAfter5,
              rk4.energyErrorAfter50);
  EXPECT_NEAR(rk4.energyErrorAfter50 / rk4.energyErrorAfter5, 10.0, 1.0);
  EXPECT_LT(rk4.lateMaxEnergyError, 1e-6);
  // Explicit Euler gains energy, more and more.
  const OrbitStats euler = kepler(Integrator::explicitEuler);
  EXPECT_GT(euler.finalEnergyError, 0.0);
  EXPECT_GT(euler.lateMaxEnergyError, 2.0 * euler.earlyMaxEnergyError);
}

// Free fall for 1 s at 60 Hz in float (the simulation's scalar), from rest.
TEST(Integrator, FreeFallAgainstTheClosedForm) {
  const float g = -10.0f, h = 1.0f / 60.0f;
  auto gravity = [g](std::span<const float>, std::span<const float>, float, std::span<float> a) {
    a[0] = g;
  };
  for (Integrator m : rc::kIntegrators) {
    float q[1] = {0}, v[1] = {0};
    rc::IntegratorScratch<float> scratch;
    for (int k = 0; k < 60; ++k)
      rc::integrate<float>(m, q, v, static_cast<float>(k) * h, h, gravity, scratch);
    const double t = 60.0 * static_cast<double>(h), exact = 0.5 * g * t * t;
    const double error = static_cast<double>(q[0]) - exact;
    const std::string name(rc::integratorName(m));
    EXPECT_NEAR(v[0], g * t, 1e-5) << name;  // every method gets the velocity right
    switch (m) {
      case Integrator::semiImplicitEuler:  // y_n = g h^2 n (n + 1) / 2: ahead by g h t / 2
        EXPECT_NEAR(error, 0.5 * g * h * t, 1e-5) << name;
        break;
      case Integrator::explicitEuler:  // y_n = g h^2 n (n - 1) / 2: behind by g h t / 2
        EXPECT_NEAR(error, -0.5 * g * h * t, 1e-5) << name;
        break;
      default:  // exact for constant acceleration, up to float rounding
        EXPECT_NEAR(error, 0.0, 1e-5) << name;
    }
  }
}

TEST(Integrator, NamesRoundTrip) {
  for (Integrator m : rc::kIntegrators)
    EXPECT_EQ(rc::parseIntegrator(rc::integratorName(m)), m);
  EXPECT_FALSE(rc::parseIntegrator("leapfrog").has_value());
  EXPECT_EQ(rc::evaluationsPerStep(Integrator::rk4), 4);
}

}  // namespace integrator_test
