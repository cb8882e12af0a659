#include "game/weapons/weapon_table.h"

#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "game/input_file.h"
#include "game/json_guard.h"
#include "game/quote.h"
#include "physics/trig.h"

#ifndef RICOCHET_WEAPONS_FILE
#define RICOCHET_WEAPONS_FILE "assets/weapons.json"
#endif

namespace game {
namespace {

using Json = nlohmann::json;

// A weapon file is a few kB; anything this large is not one (and must not exhaust memory).
constexpr std::uintmax_t kMaxFileBytes = 1u << 20;
// A weapon table nests four levels (the file, its list, a weapon, its falloff); deeper files are
// refused while parsing, before anything walks the tree (an error message renders a value, and
// rendering 100,000 nested arrays recurses as deep).
constexpr int kMaxDepth = 16;
constexpr float kDegree = rc::kPi / 180.0f;

// Where a value sits: the file, then "weapons[1] ("shotgun")", then the field.
class At {
 public:
  explicit At(std::string where) : where_(std::move(where)) {}
  At in(const std::string& part) const { return At(where_ + ": " + part); }
  [[noreturn]] void fail(const std::string& what) const {
    std::string line = where_ + ": " + what;
    for (char& c : line)
      if (c == '\n' || c == '\r') c = ' ';
    throw WeaponTableError(line);
  }

 private:
  std::string where_;
};

std::string describe(const Json& value) {
  return describeJson(value);
}

std::string quoted(const std::string& key) {
  return quoteName(key);
}

// Every key of the object must be one the reader knows: a misspelt field must not leave its
// weapon with a default the designer never chose.
void onlyKeys(const Json& object, std::initializer_list<const char*> known, const At& at) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool ok = false;
    for (const char* k : known)
      ok = ok || it.key() == k;
    if (!ok) at.fail("unknown field " + quoted(it.key()));
  }
}

const Json& field(const Json& object, const char* key, const At& at) {
  const auto it = object.find(key);
  if (it == object.end()) at.fail(quoted(key) + " is missing");
  return *it;
}

const Json& objectField(const Json& object, const char* key, const At& at) {
  const Json& v = field(object, key, at);
  if (!v.is_object()) at.fail(quoted(key) + " must be an object, got " + describe(v));
  return v;
}

float number(const Json& object, const char* key, double min, double max, const At& at) {
  const Json& v = field(object, key, at);
  const auto range = [&] {
    std::ostringstream s;
    s << min << " to " << max;
    return s.str();
  };
  if (!v.is_number())
    at.fail(quoted(key) + " must be a number from " + range() + ", got " + describe(v));
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < min || d > max)
    at.fail(quoted(key) + " must be a number from " + range() + ", got " + describe(v));
  return static_cast<float>(d);
}

int integer(const Json& object, const char* key, int min, int max, const At& at) {
  const Json& v = field(object, key, at);
  const std::string want = " must be an integer from " + std::to_string(min) + " to " +
                           std::to_string(max) + ", got " + describe(v);
  if (!v.is_number_integer()) at.fail(quoted(key) + want);
  const std::int64_t i = v.get<std::int64_t>();
  if (i < min || i > max) at.fail(quoted(key) + want);
  return static_cast<int>(i);
}

std::string text(const Json& object, const char* key, const At& at) {
  const Json& v = field(object, key, at);
  if (!v.is_string()) at.fail(quoted(key) + " must be a string, got " + describe(v));
  return v.get<std::string>();
}

HitscanSpec readHitscan(const Json& w, const At& at) {
  HitscanSpec h;
  h.damage = number(w, "damage", 0, 1e4, at);
  h.range = number(w, "range", 0.1, 1000, at);
  const At fat = at.in("'falloff'");
  const Json& falloff = objectField(w, "falloff", at);
  onlyKeys(falloff, {"start", "end", "min"}, fat);
  h.falloffStart = number(falloff, "start", 0, 1000, fat);
  h.falloffEnd = number(falloff, "end", h.falloffStart, 1000, fat);
  h.minDamage = number(falloff, "min", 0, 1, fat);
  h.pellets = integer(w, "pellets", 1, 64, at);
  h.spread = number(w, "spreadDegrees", 0, 45, at) * kDegree;
  h.penetration = number(w, "penetration", 0, 1000, at);
  const At rat = at.in("'ricochet'");
  const Json& ricochet = objectField(w, "ricochet", at);
  onlyKeys(ricochet, {"bounces", "maxAngleDegrees", "damageLoss"}, rat);
  h.ricochets = integer(ricochet, "bounces", 0, 16, rat);
  h.ricochetAngle = number(ricochet, "maxAngleDegrees", 0, 89, rat) * kDegree;
  h.ricochetSin = rc::sincos(h.ricochetAngle).sine;
  h.ricochetLoss = number(ricochet, "damageLoss", 0, 1, rat);
  h.impulse = number(w, "impulse", 0, 1e4, at);
  return h;
}

GrenadeSpec readGrenade(const Json& w, const At& at) {
  GrenadeSpec g;
  g.muzzleVelocity = number(w, "muzzleVelocity", 0, 200, at);
  g.radius = number(w, "radius", 0.01, 2, at);
  g.density = number(w, "density", 0.01, 1e4, at);
  g.restitution = number(w, "restitution", 0, 1, at);
  g.friction = number(w, "friction", 0, 10, at);
  g.linearDamping = number(w, "linearDamping", 0, 100, at);
  g.fuseTicks = integer(w, "fuseTicks", 1, 36000, at);
  const At eat = at.in("'explosion'");
  const Json& blast = objectField(w, "explosion", at);
  onlyKeys(blast, {"radius", "damage", "impulse"}, eat);
  g.blastRadius = number(blast, "radius", 0.1, 100, eat);
  g.blastDamage = number(blast, "damage", 0, 1e5, eat);
  g.blastImpulse = number(blast, "impulse", 0, 1e5, eat);
  return g;
}

WeaponSpec readWeapon(const Json& w, const At& at, const std::vector<WeaponSpec>& before) {
  if (!w.is_object()) at.fail("must be an object, got " + describe(w));
  WeaponSpec spec;
  spec.name = text(w, "name", at);
  if (spec.name.empty() || spec.name.size() > 32)
    at.fail("'name' must have 1 to 32 characters, got " + describe(w.at("name")));
  for (const WeaponSpec& other : before)
    if (other.name == spec.name) at.fail("'name' " + describe(w.at("name")) + " is taken");
  const std::string kind = text(w, "kind", at);
  if (kind == "hitscan") {
    spec.kind = WeaponKind::hitscan;
    onlyKeys(w,
             {"name", "kind", "cooldownTicks", "ammo", "damage", "range", "falloff", "pellets",
              "spreadDegrees", "penetration", "ricochet", "impulse"},
             at);
  } else if (kind == "grenade") {
    spec.kind = WeaponKind::grenade;
    onlyKeys(w,
             {"name", "kind", "cooldownTicks", "ammo", "muzzleVelocity", "radius", "density",
              "restitution", "friction", "linearDamping", "fuseTicks", "explosion"},
             at);
  } else {
    at.fail("'kind' must be \"hitscan\" or \"grenade\", got " + describe(w.at("kind")));
  }
  spec.cooldownTicks = integer(w, "cooldownTicks", 1, 3600, at);
  spec.ammo = integer(w, "ammo", 0, 100000, at);
  if (spec.kind == WeaponKind::hitscan) spec.hitscan = readHitscan(w, at);
  if (spec.kind == WeaponKind::grenade) spec.grenade = readGrenade(w, at);
  return spec;
}

}  // namespace

const char* weaponKindName(WeaponKind kind) {
  return kind == WeaponKind::grenade ? "grenade" : "hitscan";
}

std::optional<std::size_t> WeaponTable::grenade() const {
  for (std::size_t i = 0; i < weapons.size(); ++i)
    if (weapons[i].kind == WeaponKind::grenade) return i;
  return std::nullopt;
}

WeaponTable parseWeaponTable(std::string_view text, const std::string& source) {
  const At at(source);
  if (text.size() > kMaxFileBytes)
    at.fail("the file is larger than " + byteSizeText(kMaxFileBytes));
  // Too deep is refused as it opens, and so is a key twice in one object (game/json_guard.h).
  JsonGuard limits(kMaxDepth);
  const Json::parser_callback_t guard = [&](int depth, Json::parse_event_t event, Json& value) {
    switch (limits.check(depth, event, value)) {
      case JsonGuard::Problem::tooDeep:
        at.fail("not a weapon table: JSON nested deeper than " + std::to_string(kMaxDepth) +
                " levels");
      case JsonGuard::Problem::duplicateKey:
        at.fail("the key " + describe(value) + " appears twice in one object");
      case JsonGuard::Problem::none:
        break;
    }
    return true;
  };
  Json root;
  try {
    root = Json::parse(text.begin(), text.end(), guard);
  } catch (const Json::exception& e) {
    // nlohmann's "[json.exception.parse_error.101] parse error at line L, column C: what".
    const std::string what = e.what();
    const auto tag = what.find("] ");
    at.fail("not valid JSON: " + (tag == std::string::npos ? what : what.substr(tag + 2)));
  }
  if (!root.is_object()) at.fail("must hold a JSON object, got " + describe(root));
  onlyKeys(root, {"weapons"}, at);
  const Json& list = field(root, "weapons", at);
  if (!list.is_array() || list.empty() || list.size() > kMaxWeapons)
    at.fail("'weapons' must be an array of 1 to " + std::to_string(kMaxWeapons) + " weapons, got " +
            describe(list));
  WeaponTable table;
  table.source = source;
  table.text = std::string(text);
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::string where = "weapons[" + std::to_string(i) + "]";
    if (list[i].is_object() && list[i].contains("name") && list[i].at("name").is_string())
      where += " (" + describe(list[i].at("name")) + ")";
    table.weapons.push_back(readWeapon(list[i], at.in(where), table.weapons));
  }
  return table;
}

WeaponTable loadWeaponTable(const std::string& path) {
  std::string text;
  if (const auto why = readInputFile(path, kMaxFileBytes, text)) At(path).fail(*why);
  return parseWeaponTable(text, path);
}

std::string bundledWeaponTablePath() {
  if (const char* env = std::getenv("RICOCHET_WEAPONS"); env != nullptr && *env != '\0') return env;
  return RICOCHET_WEAPONS_FILE;
}

}  // namespace game
