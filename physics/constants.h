// Ricochet physics: tolerances shared by the geometry and dynamics layers.
#pragma once

namespace rc {

// Collision and constraint tolerance in metres. The same value as Box2D's b2_linearSlop, so our
// results and the oracle's can be compared with one tolerance.
inline constexpr float kLinearSlop = 0.005f;
// Contacts are created this far before shapes touch, so the solver can stop them in one step.
inline constexpr float kSpeculativeDistance = 4.0f * kLinearSlop;
// The most vertices a convex polygon may have (as in Box2D, so every polygon maps onto the oracle).
inline constexpr int kMaxPolygonVertices = 8;

}  // namespace rc
