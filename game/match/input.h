// A player's controls for one tick: the record a recording stores, one per player per tick.
//
// Quantised to small integers so that it is stored and replayed exactly: the move direction as
// two signed bytes, the aim as a 16-bit fraction of a turn (0.0055 degrees), the buttons as bits,
// the weapon wanted as an index. The game only ever reads it through moveOf() and aimOf(), so a
// human's, a script's and the autopilot's inputs go through the same rounding.
#pragma once

#include <array>
#include <cstdint>

#include "physics/math.h"

namespace game {

inline constexpr int kTicksPerSecond = 60;
inline constexpr float kTickSeconds = 1.0f / 60.0f;

// Button bits.
inline constexpr std::uint8_t kButtonFire = 1u << 0;   // the weapon in hand
inline constexpr std::uint8_t kButtonThrow = 1u << 1;  // a grenade
inline constexpr std::uint8_t kButtonReload = 1u << 2;

struct PlayerInput {
  std::int8_t moveX = 0, moveY = 0;  // -127..127 on each axis (127: full speed that way)
  std::uint16_t aim = 0;             // counter-clockwise from +x, in 1/65536 of a turn
  std::uint8_t buttons = 0;
  std::uint8_t weapon = 0;  // index in the weapon table
  friend constexpr bool operator==(const PlayerInput&, const PlayerInput&) = default;
};

inline constexpr std::size_t kInputBytes = 6;

// From continuous controls: the move direction (its length is capped at 1) and the aim angle
// in radians (any value; taken modulo a turn).
PlayerInput makeInput(rc::Vec2 move, float aim, std::uint8_t buttons, std::uint8_t weapon);
// The move direction, length at most 1, and the aim in radians in [0, 2 pi).
rc::Vec2 moveOf(const PlayerInput& input);
float aimOf(const PlayerInput& input);

// The record as bytes (little-endian) and back.
std::array<std::uint8_t, kInputBytes> toBytes(const PlayerInput& input);
PlayerInput fromBytes(const std::array<std::uint8_t, kInputBytes>& bytes);

}  // namespace game
