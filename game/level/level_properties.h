// The custom properties a level designer sets in Tiled, read with their types checked: a
// friction typed as a string, a negative density or a health of 1e40 fails with the property's
// name and the object it is on. The names and their meanings are listed in
// game/level/README.md.
#pragma once

#include <string>

#include "game/level/level.h"
#include "game/level/level_error.h"
#include "game/level/tiled_map.h"

namespace game {

// A number (Tiled's float or int) in [min, max], or the fallback when absent.
float floatProperty(const TiledProperties& properties, const std::string& name, float fallback,
                    float min, float max, const ErrorContext& at);
int intProperty(const TiledProperties& properties, const std::string& name, int fallback, int min,
                int max, const ErrorContext& at);
bool boolProperty(const TiledProperties& properties, const std::string& name, bool fallback,
                  const ErrorContext& at);
std::string stringProperty(const TiledProperties& properties, const std::string& name,
                           const std::string& fallback, const ErrorContext& at);

// density, friction, restitution, thickness, health and hard over the given defaults.
LevelMaterial readMaterial(const TiledProperties& properties, const LevelMaterial& defaults,
                           const ErrorContext& at);

}  // namespace game
