#include "game/level/level.h"

namespace game {

const char* levelObjectKindName(LevelObjectKind kind) {
  switch (kind) {
    case LevelObjectKind::wall:
      return "wall";
    case LevelObjectKind::tiles:
      return "tiles";
    case LevelObjectKind::prop:
      return "prop";
    case LevelObjectKind::trigger:
      return "trigger";
  }
  return "?";
}

std::optional<LevelRef> levelRefOf(std::uint64_t userData) {
  if ((userData & (std::uint64_t{0xFF} << 56)) != kLevelUserDataTag) return std::nullopt;
  const auto kind = static_cast<std::uint8_t>(userData >> 48);
  if (kind > static_cast<std::uint8_t>(LevelObjectKind::trigger)) return std::nullopt;
  if (((userData >> 32) & 0xFFFF) != 0) return std::nullopt;
  return LevelRef{static_cast<LevelObjectKind>(kind),
                  static_cast<std::size_t>(userData & 0xFFFFFFFFu)};
}

}  // namespace game
