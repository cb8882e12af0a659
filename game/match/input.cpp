#include "game/match/input.h"

#include <cmath>

#include "physics/trig.h"

namespace game {
namespace {

constexpr float kTurn = 2.0f * rc::kPi;

std::int8_t quantiseAxis(float v) {
  const float clamped = std::fmax(-1.0f, std::fmin(1.0f, v));
  return static_cast<std::int8_t>(std::lround(clamped * 127.0f));
}

}  // namespace

PlayerInput makeInput(rc::Vec2 move, float aim, std::uint8_t buttons, std::uint8_t weapon) {
  PlayerInput in;
  const float len = rc::length(move);
  if (len > 1.0f) move = (1.0f / len) * move;
  if (rc::isFinite(move)) {
    in.moveX = quantiseAxis(move.x);
    in.moveY = quantiseAxis(move.y);
  }
  if (std::isfinite(aim)) {
    // Whole turns off first, in double, so that large angles keep their fraction.
    double turns = static_cast<double>(aim) / static_cast<double>(kTurn);
    turns -= std::floor(turns);
    in.aim = static_cast<std::uint16_t>(std::llround(turns * 65536.0) & 0xFFFF);
  }
  in.buttons = buttons;
  in.weapon = weapon;
  return in;
}

rc::Vec2 moveOf(const PlayerInput& input) {
  rc::Vec2 m{static_cast<float>(input.moveX) / 127.0f, static_cast<float>(input.moveY) / 127.0f};
  // (127, 127) is longer than 1: diagonals are no faster than straight lines.
  const float len2 = rc::lengthSquared(m);
  if (len2 > 1.0f) m = (1.0f / std::sqrt(len2)) * m;
  return m;
}

float aimOf(const PlayerInput& input) {
  return static_cast<float>(input.aim) * (kTurn / 65536.0f);
}

std::array<std::uint8_t, kInputBytes> toBytes(const PlayerInput& input) {
  return {static_cast<std::uint8_t>(input.moveX),
          static_cast<std::uint8_t>(input.moveY),
          static_cast<std::uint8_t>(input.aim & 0xFF),
          static_cast<std::uint8_t>(input.aim >> 8),
          input.buttons,
          input.weapon};
}

PlayerInput fromBytes(const std::array<std::uint8_t, kInputBytes>& b) {
  PlayerInput in;
  in.moveX = static_cast<std::int8_t>(b[0]);
  in.moveY = static_cast<std::int8_t>(b[1]);
  in.aim = static_cast<std::uint16_t>(b[2] | (b[3] << 8));
  in.buttons = b[4];
  in.weapon = b[5];
  return in;
}

}  // namespace game
