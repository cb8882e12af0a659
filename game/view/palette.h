// The match view's colours, in one place so that a frame reads the same everywhere: the level in
// greys, props in wood and rust, teams in colours far apart (blue, red, green, gold), shots and
// blasts in light and fire.
#pragma once

#include <cstddef>
#include <iterator>

#include "render/color.h"

namespace game::palette {

using render::Color;

inline constexpr Color kOutside{16, 18, 22, 255};  // around the level
inline constexpr Color kFloor{40, 44, 52, 255};
inline constexpr Color kGrid{255, 255, 255, 12};
inline constexpr Color kWall{92, 100, 116, 255};
inline constexpr Color kWallEdge{160, 170, 190, 255};
inline constexpr Color kCrate{178, 122, 62, 255};
inline constexpr Color kCrateEdge{92, 58, 26, 255};
inline constexpr Color kBarrel{168, 64, 46, 255};
inline constexpr Color kBarrelEdge{70, 26, 18, 255};
inline constexpr Color kSturdyProp{126, 116, 100, 255};  // a prop nothing can destroy
inline constexpr Color kHazard{230, 60, 60, 255};        // trigger zones that hurt or kill
inline constexpr Color kZone{230, 200, 60, 255};         // any other trigger
inline constexpr Color kHealthPickup{80, 220, 110, 255};
inline constexpr Color kAmmoPickup{240, 200, 60, 255};
inline constexpr Color kOtherPickup{170, 170, 255, 255};
inline constexpr Color kShot{255, 240, 170, 255};
inline constexpr Color kSpark{255, 255, 255, 255};
inline constexpr Color kBlast{255, 150, 40, 255};
inline constexpr Color kGrenade{70, 90, 40, 255};
inline constexpr Color kHealthFull{90, 220, 90, 255};
inline constexpr Color kHealthLow{235, 60, 50, 255};
inline constexpr Color kHealthBack{20, 20, 20, 220};
inline constexpr Color kHudBand{10, 11, 14, 230};
inline constexpr Color kHudText{235, 235, 240, 255};
inline constexpr Color kHudDim{160, 165, 175, 255};

inline constexpr Color kTeams[] = {
    {70, 160, 245, 255}, {240, 90, 70, 255}, {120, 210, 90, 255}, {230, 190, 60, 255}};
inline Color team(int index) {
  const std::size_t n = std::size(kTeams);
  return kTeams[static_cast<std::size_t>(index < 0 ? -index : index) % n];
}

// `c` moved towards `to` by t in [0, 1].
constexpr Color mix(Color c, Color to, float t) {
  auto lerp = [t](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(static_cast<float>(a) +
                                     t * (static_cast<float>(b) - static_cast<float>(a)) + 0.5f);
  };
  return {lerp(c.r, to.r), lerp(c.g, to.g), lerp(c.b, to.b), lerp(c.a, to.a)};
}

// `c` with its alpha scaled by t in [0, 1].
constexpr Color fade(Color c, float t) {
  return c.withAlpha(static_cast<std::uint8_t>(static_cast<float>(c.a) * t + 0.5f));
}

}  // namespace game::palette
