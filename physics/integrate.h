// Ricochet physics: time integrators for a mechanical system q'' = a(q, q', t).
//
// The world integrates bodies (x, y and angle per body) with one of these, chosen per world; the
// accuracy studies run the same code on double or long double. Forces are evaluated through
// accel(q, v, t, a) at every stage an integrator needs, so user force fields (springs, drag,
// gravity wells) see the stage's positions and velocities and RK4 keeps its fourth order under
// position-dependent forces.
//
//   method               order  evaluations  stability on an oscillator (z = h omega)
//   explicit Euler       1      1            never: amplitude grows by sqrt(1 + z^2) per step
//   semi-implicit Euler  1      1            z < 2, symplectic (energy error bounded)
//   velocity Verlet      2      2            z < 2, symplectic and time-reversible
//   RK4                  4      4            z < 2 sqrt(2), not symplectic (energy drifts)
//
// Semi-implicit (symplectic) Euler is the default: Box2D's integrator, first order but with a
// bounded energy error at the cost of one force evaluation. Velocity Verlet is
// kick-drift-kick: v += a h/2, q += v h, v += a(q_new, v_half) h/2; with velocity-dependent
// forces the second kick uses the half-step velocity, which keeps it explicit (the forces of a
// game are at most linear in v and this is what game engines do).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

namespace rc {

enum class Integrator : std::uint8_t { explicitEuler, semiImplicitEuler, velocityVerlet, rk4 };

inline constexpr Integrator kIntegrators[] = {Integrator::explicitEuler,
                                              Integrator::semiImplicitEuler,
                                              Integrator::velocityVerlet, Integrator::rk4};

// "explicit-euler", "semi-implicit-euler", "verlet", "rk4": the names scene files and the
// command line use.
constexpr std::string_view integratorName(Integrator m) {
  switch (m) {
    case Integrator::explicitEuler:
      return "explicit-euler";
    case Integrator::semiImplicitEuler:
      return "semi-implicit-euler";
    case Integrator::velocityVerlet:
      return "verlet";
    case Integrator::rk4:
      return "rk4";
  }
  return "?";
}

constexpr std::optional<Integrator> parseIntegrator(std::string_view name) {
  for (Integrator m : kIntegrators)
    if (integratorName(m) == name) return m;
  return std::nullopt;
}

// Force evaluations per step.
constexpr int evaluationsPerStep(Integrator m) {
  return m == Integrator::rk4 ? 4 : m == Integrator::velocityVerlet ? 2 : 1;
}

// Scratch space reused from step to step, so stepping never allocates once it has grown.
// Positions may be kept in a wider type than velocities (Q = double, T = float in the world:
// far from the origin a float position cannot take a small step, see World).
template <class T, class Q = T>
struct IntegratorScratch {
  std::vector<T> a, vs, dq, dv;
  std::vector<Q> qs;
  // A view of n elements of one of the buffers, grown when needed. (assign, not resize: g++ 12
  // warns falsely about resize's relocation when n is known to be small.)
  template <class U>
  static std::span<U> take(std::vector<U>& buffer, std::size_t n) {
    if (buffer.size() < n) buffer.assign(n, U{});
    return std::span<U>(buffer.data(), n);
  }
};

// One step of size h from time t: q and v (the same length) are advanced in place.
// accel(std::span<const Q> q, std::span<const T> v, Q t, std::span<T> a) writes the
// accelerations at that state. Increments are computed in T and added to the positions in Q;
// time is kept in Q too (a float clock is coarse after hours: 4 ms steps at 2^15 s).
template <class T, class Q = T, class Accel>
void integrate(Integrator method, std::type_identity_t<std::span<Q>> q,
               std::type_identity_t<std::span<T>> v, std::type_identity_t<Q> t, T h, Accel&& accel,
               IntegratorScratch<T, Q>& s) {
  const std::size_t n = q.size();
  const std::span<T> a = s.take(s.a, n);
  const T half = h / T(2);
  switch (method) {
    case Integrator::explicitEuler:
      accel(std::span<const Q>(q), std::span<const T>(v), t, a);
      for (std::size_t i = 0; i < n; ++i) {
        q[i] += h * v[i];  // with the old velocity
        v[i] += h * a[i];
      }
      return;
    case Integrator::semiImplicitEuler:
      accel(std::span<const Q>(q), std::span<const T>(v), t, a);
      for (std::size_t i = 0; i < n; ++i) {
        v[i] += h * a[i];
        q[i] += h * v[i];  // with the new velocity
      }
      return;
    case Integrator::velocityVerlet:
      accel(std::span<const Q>(q), std::span<const T>(v), t, a);
      for (std::size_t i = 0; i < n; ++i) {
        v[i] += half * a[i];
        q[i] += h * v[i];
      }
      accel(std::span<const Q>(q), std::span<const T>(v), t + Q(h), a);
      for (std::size_t i = 0; i < n; ++i)
        v[i] += half * a[i];
      return;
    case Integrator::rk4: {
      // Classic RK4 on (q, v) with q' = v, v' = a. dq and dv accumulate k1 + 2 k2 + 2 k3 + k4.
      const std::span<Q> qs = s.take(s.qs, n);
      const std::span<T> vs = s.take(s.vs, n), dq = s.take(s.dq, n), dv = s.take(s.dv, n);
      accel(std::span<const Q>(q), std::span<const T>(v), t, a);  // k1
      for (std::size_t i = 0; i < n; ++i) {
        dq[i] = v[i];
        dv[i] = a[i];
        qs[i] = q[i] + half * v[i];
        vs[i] = v[i] + half * a[i];
      }
      // k2 and k3, both at t + h/2; each sets up the next stage, at t + h/2 and at t + h.
      for (const T next : {half, h}) {
        accel(std::span<const Q>(qs), std::span<const T>(vs), t + Q(half), a);
        for (std::size_t i = 0; i < n; ++i) {
          const T kq = vs[i];
          dq[i] += T(2) * kq;
          dv[i] += T(2) * a[i];
          qs[i] = q[i] + next * kq;
          vs[i] = v[i] + next * a[i];
        }
      }
      accel(std::span<const Q>(qs), std::span<const T>(vs), t + Q(h), a);  // k4
      const T sixth = h / T(6);
      for (std::size_t i = 0; i < n; ++i) {
        q[i] += sixth * (dq[i] + vs[i]);
        v[i] += sixth * (dv[i] + a[i]);
      }
      return;
    }
  }
}

}  // namespace rc
