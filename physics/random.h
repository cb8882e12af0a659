// Ricochet physics: a deterministic pseudo-random generator and distributions.
//
// std::uniform_*_distribution differ between standard libraries, so everything that must replay
// bit for bit (scene generators, the game, the tests' random cases) draws from this instead.
// The generator is SplitMix64 (Steele, Lea and Flood 2014): one 64-bit state, full period 2^64,
// passes BigCrush, and any seed (including 0) is fine.
#pragma once

#include <cstdint>

#include "physics/math.h"

namespace rc {

class Random {
 public:
  explicit constexpr Random(std::uint64_t seed) : state_(seed) {}

  constexpr std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1) with 24 random bits: every float of the form k / 2^24.
  constexpr float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
  // Uniform in [lo, hi).
  constexpr float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  // Uniform in [0, 1) with 53 random bits.
  constexpr double uniformDouble() {
    return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0);
  }
  // Uniform integer in [0, n) (Lemire's multiply-shift; the bias is below 2^-32 for n < 2^32).
  constexpr std::uint32_t below(std::uint32_t n) {
    return static_cast<std::uint32_t>(((next() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
  }
  constexpr Vec2 inBox(Vec2 lo, Vec2 hi) { return {uniform(lo.x, hi.x), uniform(lo.y, hi.y)}; }
  // The whole state: Random(state()) continues the same sequence (snapshots, hashes).
  constexpr std::uint64_t state() const { return state_; }

 private:
  std::uint64_t state_;
};

}  // namespace rc
