// Ricochet physics: 2D vector math. Bottom layer; depends on the standard library only.
//
// float is the simulation scalar. Everything here is inline and free of FMA contraction
// (the build uses -ffp-contract=off) so results are bit-identical across builds.
#pragma once

#include <algorithm>
#include <cmath>

#include "physics/trig.h"

namespace rc {

// Trivially default-constructible like a plain struct of two floats: `Vec2 v;` is
// uninitialised (arrays of vertices cost nothing to declare), `Vec2 v{};` is zero.
struct Vec2 {
  float x;
  float y;

  Vec2() = default;
  constexpr Vec2(float x_, float y_) : x(x_), y(y_) {}

  constexpr Vec2 operator-() const { return {-x, -y}; }
  constexpr Vec2& operator+=(Vec2 v) {
    x += v.x;
    y += v.y;
    return *this;
  }
  constexpr Vec2& operator-=(Vec2 v) {
    x -= v.x;
    y -= v.y;
    return *this;
  }
  constexpr Vec2& operator*=(float s) {
    x *= s;
    y *= s;
    return *this;
  }
  friend constexpr bool operator==(Vec2 a, Vec2 b) = default;
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
constexpr Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
constexpr Vec2 operator*(float s, Vec2 v) {
  return {s * v.x, s * v.y};
}
constexpr Vec2 operator*(Vec2 v, float s) {
  return {s * v.x, s * v.y};
}

constexpr float dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
// z-component of the 3D cross product: positive when b is counter-clockwise of a.
constexpr float cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
constexpr Vec2 cross(Vec2 v, float s) {
  return {s * v.y, -s * v.x};
}
constexpr Vec2 cross(float s, Vec2 v) {
  return {-s * v.y, s * v.x};
}
constexpr Vec2 leftPerp(Vec2 v) {
  return {-v.y, v.x};
}
constexpr Vec2 rightPerp(Vec2 v) {
  return {v.y, -v.x};
}
constexpr Vec2 lerp(Vec2 a, Vec2 b, float t) {
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
}
constexpr Vec2 mulAdd(Vec2 a, float s, Vec2 b) {
  return {a.x + s * b.x, a.y + s * b.y};
}
constexpr Vec2 mulSub(Vec2 a, float s, Vec2 b) {
  return {a.x - s * b.x, a.y - s * b.y};
}
constexpr Vec2 min(Vec2 a, Vec2 b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y)};
}
constexpr Vec2 max(Vec2 a, Vec2 b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y)};
}
inline Vec2 abs(Vec2 v) {
  return {std::fabs(v.x), std::fabs(v.y)};
}

constexpr float lengthSquared(Vec2 v) {
  return v.x * v.x + v.y * v.y;
}
inline float length(Vec2 v) {
  return std::sqrt(v.x * v.x + v.y * v.y);
}
inline float distance(Vec2 a, Vec2 b) {
  return length(b - a);
}
constexpr float distanceSquared(Vec2 a, Vec2 b) {
  return lengthSquared(b - a);
}
inline bool isFinite(float f) {
  return std::isfinite(f);
}
inline bool isFinite(Vec2 v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}

// Unit vector along v, or zero when v is too short to have a direction.
inline Vec2 normalize(Vec2 v) {
  float len = length(v);
  if (len < 1e-30f) return {0.0f, 0.0f};
  float inv = 1.0f / len;
  return {inv * v.x, inv * v.y};
}
// Normalizes v in place and returns its former length (zero vector stays zero).
inline float normalizeInPlace(Vec2& v) {
  float len = length(v);
  if (len < 1e-30f) {
    v = {0.0f, 0.0f};
    return 0.0f;
  }
  float inv = 1.0f / len;
  v = {inv * v.x, inv * v.y};
  return len;
}

// A rotation stored as cosine/sine. Built from an angle with our own sincos so the result is the
// same on every platform and library version.
struct Rot {
  float c = 1.0f;
  float s = 0.0f;

  static Rot fromAngle(float radians) {
    SinCos sc = sincos(radians);
    return {sc.cosine, sc.sine};
  }
  float angle() const { return atan2(s, c); }
  bool isIdentity() const { return s == 0.0f && c == 1.0f; }
  friend constexpr bool operator==(Rot a, Rot b) = default;
};

constexpr Vec2 rotate(Rot q, Vec2 v) {
  return {q.c * v.x - q.s * v.y, q.s * v.x + q.c * v.y};
}
constexpr Vec2 invRotate(Rot q, Vec2 v) {
  return {q.c * v.x + q.s * v.y, -q.s * v.x + q.c * v.y};
}
// q * r
constexpr Rot mul(Rot q, Rot r) {
  return {q.c * r.c - q.s * r.s, q.s * r.c + q.c * r.s};
}
// inverse(q) * r
constexpr Rot invMul(Rot q, Rot r) {
  return {q.c * r.c + q.s * r.s, q.c * r.s - q.s * r.c};
}

struct Transform {
  Vec2 p{};
  Rot q{};
  friend constexpr bool operator==(const Transform&, const Transform&) = default;
};

constexpr Vec2 apply(const Transform& t, Vec2 v) {
  return rotate(t.q, v) + t.p;
}
constexpr Vec2 invApply(const Transform& t, Vec2 v) {
  return invRotate(t.q, v - t.p);
}
// a * b: first b, then a.
constexpr Transform mul(const Transform& a, const Transform& b) {
  return {rotate(a.q, b.p) + a.p, mul(a.q, b.q)};
}
// inverse(a) * b: b expressed in a's frame.
constexpr Transform invMul(const Transform& a, const Transform& b) {
  return {invRotate(a.q, b.p - a.p), invMul(a.q, b.q)};
}

struct AABB {
  Vec2 lower{};
  Vec2 upper{};

  constexpr Vec2 center() const { return {0.5f * (lower.x + upper.x), 0.5f * (lower.y + upper.y)}; }
  constexpr Vec2 extents() const {
    return {0.5f * (upper.x - lower.x), 0.5f * (upper.y - lower.y)};
  }
  constexpr float perimeter() const { return 2.0f * ((upper.x - lower.x) + (upper.y - lower.y)); }
  constexpr bool contains(const AABB& b) const {
    return lower.x <= b.lower.x && lower.y <= b.lower.y && b.upper.x <= upper.x &&
           b.upper.y <= upper.y;
  }
  constexpr bool contains(Vec2 p) const {
    return lower.x <= p.x && p.x <= upper.x && lower.y <= p.y && p.y <= upper.y;
  }
  bool isValid() const {
    return isFinite(lower) && isFinite(upper) && lower.x <= upper.x && lower.y <= upper.y;
  }
  friend constexpr bool operator==(const AABB&, const AABB&) = default;
};

constexpr bool overlaps(const AABB& a, const AABB& b) {
  return !(b.lower.x > a.upper.x || b.lower.y > a.upper.y || a.lower.x > b.upper.x ||
           a.lower.y > b.upper.y);
}
constexpr AABB unionOf(const AABB& a, const AABB& b) {
  return {min(a.lower, b.lower), max(a.upper, b.upper)};
}
constexpr AABB inflate(const AABB& a, float margin) {
  return {{a.lower.x - margin, a.lower.y - margin}, {a.upper.x + margin, a.upper.y + margin}};
}

// The index after i in a cycle of n (a compare, not an integer division: % costs ~25 cycles of
// latency in the hot loops over polygon edges).
constexpr int nextIndex(int i, int n) {
  return i + 1 < n ? i + 1 : 0;
}

}  // namespace rc
