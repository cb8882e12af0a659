#include "game/level/level_properties.h"

#include <cmath>

namespace game {

namespace {

std::string typeOf(const TiledProperty& p) {
  return std::string("a ") + propertyTypeName(p.type);
}

std::string number(double v) {
  std::string s = std::to_string(v);
  while (s.size() > 1 && s.back() == '0')
    s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

float floatProperty(const TiledProperties& properties, const std::string& name, float fallback,
                    float min, float max, const ErrorContext& at) {
  const TiledProperty* p = properties.find(name);
  if (p == nullptr) return fallback;
  const ErrorContext here = at.in("property " + quoteName(name));
  if (p->type != TiledProperty::Type::floating && p->type != TiledProperty::Type::integer)
    here.fail("must be a float, got " + typeOf(*p));
  if (!(p->number >= min && p->number <= max))
    here.fail("must be from " + number(min) + " to " + number(max) + ", got " + number(p->number));
  return static_cast<float>(p->number);
}

int intProperty(const TiledProperties& properties, const std::string& name, int fallback, int min,
                int max, const ErrorContext& at) {
  const TiledProperty* p = properties.find(name);
  if (p == nullptr) return fallback;
  const ErrorContext here = at.in("property " + quoteName(name));
  if (p->type != TiledProperty::Type::integer) here.fail("must be an int, got " + typeOf(*p));
  if (!(p->number >= min && p->number <= max))
    here.fail("must be from " + std::to_string(min) + " to " + std::to_string(max) + ", got " +
              number(p->number));
  return static_cast<int>(p->number);
}

bool boolProperty(const TiledProperties& properties, const std::string& name, bool fallback,
                  const ErrorContext& at) {
  const TiledProperty* p = properties.find(name);
  if (p == nullptr) return fallback;
  if (p->type != TiledProperty::Type::boolean)
    at.in("property " + quoteName(name)).fail("must be a bool, got " + typeOf(*p));
  return p->flag;
}

std::string stringProperty(const TiledProperties& properties, const std::string& name,
                           const std::string& fallback, const ErrorContext& at) {
  const TiledProperty* p = properties.find(name);
  if (p == nullptr) return fallback;
  if (p->type != TiledProperty::Type::string)
    at.in("property " + quoteName(name)).fail("must be a string, got " + typeOf(*p));
  return p->text;
}

LevelMaterial readMaterial(const TiledProperties& properties, const LevelMaterial& defaults,
                           const ErrorContext& at) {
  // Bounds generous for any game, tight enough that the engine's own checks and the solver's
  // float arithmetic never see an absurd value.
  LevelMaterial m = defaults;
  m.density = floatProperty(properties, "density", m.density, 1e-6f, 1e6f, at);
  m.friction = floatProperty(properties, "friction", m.friction, 0.0f, 100.0f, at);
  m.restitution = floatProperty(properties, "restitution", m.restitution, 0.0f, 10.0f, at);
  m.thickness = floatProperty(properties, "thickness", m.thickness, 0.0f, kImpenetrable, at);
  m.health = floatProperty(properties, "health", m.health, 0.0f, 1e9f, at);
  m.hard = boolProperty(properties, "hard", m.hard, at);
  return m;
}

}  // namespace game
