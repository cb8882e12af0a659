#include "game/rules/pickups.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "game/level/level_error.h"
#include "game/level/level_properties.h"

namespace game {

std::vector<PickupState> makePickups(const Level& level, const BuiltLevel& built,
                                     const WeaponTable& weapons) {
  std::vector<PickupState> out;
  for (std::size_t i = 0; i < built.pickups.size(); ++i) {
    const LevelPickup& p = built.pickups[i];
    const ErrorContext at = ErrorContext(level.source)
                                .in("pickup " + std::to_string(p.tiledId) +
                                    (p.name.empty() ? "" : " (" + quoteName(p.name) + ")"));
    PickupState state;
    state.pickup = static_cast<std::uint32_t>(i);
    state.position = p.position;
    state.radius = p.radius;
    state.amount = p.amount;
    if (p.respawn > 0.0f)
      state.respawnTicks = std::max<std::int32_t>(
          1, static_cast<std::int32_t>(std::lround(p.respawn * kTicksPerSecond)));
    if (p.item == "health") {
      state.item = PickupItem::health;
    } else if (p.item == "ammo") {
      state.item = PickupItem::ammo;
      const std::string name = stringProperty(p.properties, "weapon", "", at);
      if (!name.empty()) {
        const auto found = std::find_if(weapons.weapons.begin(), weapons.weapons.end(),
                                        [&](const WeaponSpec& w) { return w.name == name; });
        if (found == weapons.weapons.end()) {
          std::string known;
          for (const WeaponSpec& w : weapons.weapons)
            known += (known.empty() ? "" : ", ") + quoteName(w.name);
          at.fail("property 'weapon': no weapon " + quoteName(name) + " in the weapon table " +
                  weapons.source + " (" + known + ")");
        }
        state.weapon = static_cast<std::uint8_t>(found - weapons.weapons.begin());
      }
    }
    out.push_back(state);
  }
  return out;
}

float pickupGift(const MatchState& s, const Actor& actor, const PickupState& pickup) {
  if (!actor.alive) return 0.0f;
  switch (pickup.item) {
    case PickupItem::health:
      return std::clamp(s.tuning.health - actor.health, 0.0f, pickup.amount);
    case PickupItem::ammo: {
      if (pickup.weapon >= s.weapons.weapons.size()) return 0.0f;
      const int room = s.weapons.weapons[pickup.weapon].ammo - actor.ammo[pickup.weapon];
      const float rounds = std::floor(pickup.amount);
      return room > 0 ? std::min(static_cast<float>(room), rounds) : 0.0f;
    }
    case PickupItem::unknown:
      break;
  }
  return 0.0f;
}

void updatePickups(MatchState& s) {
  bool any = false;
  for (PickupState& p : s.pickups) {
    if (!p.available && p.respawnTick >= 0 && p.respawnTick <= s.tick + 1) {
      p.available = true;
      p.respawnTick = -1;
    }
    any = any || (p.available && p.item != PickupItem::unknown);
  }
  if (!any) return;
  // The living actors' centres, read from the world once (not once per pickup).
  constexpr rc::Vec2 kNowhere{std::numeric_limits<float>::max(), 0.0f};
  std::vector<rc::Vec2> centres(s.actors.size(), kNowhere);
  for (std::size_t i = 0; i < s.actors.size(); ++i)
    if (s.actors[i].alive) centres[i] = s.world->worldCenter(s.actors[i].body);
  for (PickupState& p : s.pickups) {
    if (!p.available || p.item == PickupItem::unknown) continue;
    const float reach = p.radius + s.tuning.radius;
    std::int32_t taker = -1;
    float nearest = reach * reach;
    for (std::size_t i = 0; i < centres.size(); ++i) {
      const rc::Vec2 d = centres[i] - p.position;
      const float d2 = d.x * d.x + d.y * d.y;
      if (d2 > nearest || (taker >= 0 && d2 == nearest) || !(pickupGift(s, s.actors[i], p) > 0.0f))
        continue;
      nearest = d2;
      taker = static_cast<std::int32_t>(i);
    }
    if (taker < 0) continue;
    Actor& a = s.actors[static_cast<std::size_t>(taker)];
    const float gift = pickupGift(s, a, p);
    if (p.item == PickupItem::health) {
      a.health = std::min(s.tuning.health, a.health + gift);
    } else {
      a.ammo[p.weapon] += static_cast<int>(gift);
    }
    p.available = false;
    p.takenBy = taker;
    ++p.timesTaken;
    // Gone for respawnTicks ticks from the state this tick ends in.
    p.respawnTick = p.respawnTicks > 0 ? s.tick + 1 + p.respawnTicks : -1;
  }
}

}  // namespace game
