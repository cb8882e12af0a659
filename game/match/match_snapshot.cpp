#include "game/match/match_snapshot.h"

#include <bit>
#include <cstdio>
#include <string>
#include <type_traits>
#include <utility>

#include "game/bots/bot_state.h"
#include "physics/bytes.h"

namespace game {
namespace {

constexpr std::uint32_t kMagic = 0x534D4352;  // "RCMS"
constexpr std::uint32_t kFormat = 1;

// Every field once, for both directions (as physics/snapshot.cpp does): io() writes through Out
// and reads through In, so the two cannot disagree on what is in a snapshot or in what order.
class Out {
 public:
  static constexpr bool reading = false;
  explicit Out(rc::ByteWriter& w) : w_(w) {}
  void operator()(const bool& v) { w_.boolean(v); }
  void operator()(const std::uint8_t& v) { w_.u8(v); }
  void operator()(const std::int8_t& v) { w_.u8(static_cast<std::uint8_t>(v)); }
  void operator()(const std::uint16_t& v) { w_.u16(v); }
  void operator()(const int& v) { w_.i32(v); }
  void operator()(const std::uint32_t& v) { w_.u32(v); }
  void operator()(const std::int64_t& v) { w_.u64(static_cast<std::uint64_t>(v)); }
  void operator()(const std::uint64_t& v) { w_.u64(v); }
  void operator()(const float& v) { w_.f32(v); }
  void operator()(const rc::Vec2& v) {
    w_.f32(v.x);
    w_.f32(v.y);
  }
  template <class E>
  requires std::is_enum_v<E>
  void operator()(const E& e) { w_.u8(static_cast<std::uint8_t>(e)); }
  // An index into a list of `size` items.
  void index(const std::size_t& v, std::size_t) { w_.u32(static_cast<std::uint32_t>(v)); }
  std::size_t count(std::size_t n, std::size_t) {
    w_.count(n);
    return n;
  }

 private:
  rc::ByteWriter& w_;
};

class In {
 public:
  static constexpr bool reading = true;
  explicit In(rc::ByteReader& r) : r_(r) {}
  void operator()(bool& v) { v = r_.boolean(); }
  void operator()(std::uint8_t& v) { v = r_.u8(); }
  void operator()(std::int8_t& v) { v = static_cast<std::int8_t>(r_.u8()); }
  void operator()(std::uint16_t& v) { v = r_.u16(); }
  void operator()(int& v) { v = r_.i32(); }
  void operator()(std::uint32_t& v) { v = r_.u32(); }
  void operator()(std::int64_t& v) { v = static_cast<std::int64_t>(r_.u64()); }
  void operator()(std::uint64_t& v) { v = r_.u64(); }
  void operator()(float& v) { v = r_.f32(); }
  void operator()(rc::Vec2& v) {
    v.x = r_.f32();
    v.y = r_.f32();
  }
  // An enumeration's byte as it is; its range is checked with the struct it is in (checkMind).
  template <class E>
  requires std::is_enum_v<E>
  void operator()(E& e) { e = static_cast<E>(r_.u8()); }
  void index(std::size_t& v, std::size_t size) {
    const std::uint32_t i = r_.u32();
    if (i >= size) fail("an index is " + std::to_string(i) + " of " + std::to_string(size));
    v = i;
  }
  std::size_t count(std::size_t, std::size_t minBytes) { return r_.count(minBytes); }
  [[noreturn]] void fail(const std::string& why) const { r_.fail(why); }

 private:
  rc::ByteReader& r_;
};

// A count that must equal what the match was made with (actors, props: fixed by the level and
// the configuration).
template <class A>
void fixedCount(A& a, std::size_t n, const char* what) {
  const std::size_t read = a.count(n, 0);
  if constexpr (A::reading)
    if (read != n)
      a.fail(std::string("the snapshot has ") + std::to_string(read) + " " + what +
             ", this match " + std::to_string(n));
}

template <class A>
void ioBody(A& a, auto& id) {
  a(id.index);
  a(id.generation);
}

template <class A>
void ioInput(A& a, auto& in) {
  a(in.moveX);
  a(in.moveY);
  a(in.aim);
  a(in.buttons);
  a(in.weapon);
}

// What a mind's fields may hold: a hostile snapshot must not make the brain index past an array.
template <class A>
void checkMind(A& a, const BotMind& m, std::size_t actors) {
  bool ok = m.behaviour <= Behaviour::fetch && m.focus >= -1 &&
            m.focus < static_cast<std::int32_t>(kMemorySlots) &&
            m.route.length <= kRouteWaypoints && m.route.next <= m.route.length &&
            m.route.partial <= 1;
  for (const MemoryEntry& e : m.memory)
    ok = ok && e.sense <= Sense::heard && e.actor >= -1 &&
         e.actor < static_cast<std::int32_t>(actors);
  if (!ok) a.fail("a bot's mind is out of range");
}

template <class A, class S>
void io(A& a, S& s, std::size_t weapons) {
  a(s.tick);
  if constexpr (A::reading) {
    std::uint64_t state = 0;
    a(state);
    s.rng = rc::Random(state);
  } else {
    const std::uint64_t state = s.rng.state();
    a(state);
  }
  fixedCount(a, s.actors.size(), "actors");
  for (auto& actor : s.actors) {
    a(actor.alive);
    a(actor.health);
    a(actor.aim);
    a(actor.respawnTick);
    a(actor.kills);
    a(actor.deaths);
    a(actor.suicides);
    a(actor.exits);
    a(actor.score);
    a(actor.blamed);
    a(actor.blamedTick);
    a(actor.cooldown);
    for (std::size_t w = 0; w < weapons; ++w)
      a(actor.ammo[w]);
    ioInput(a, actor.input);
  }
  // Bots' minds and the last tick's sounds: their fields as bots/bot_state.h lists them.
  auto field = [&](auto& v) { a(v); };
  for (auto& mind : s.minds) {
    forEachField(mind, field);
    if constexpr (A::reading) checkMind(a, mind, s.actors.size());
  }
  const std::size_t sounds = a.count(s.sounds.size(), 24);
  if constexpr (A::reading) s.sounds.resize(sounds);
  for (auto& sound : s.sounds) {
    forEachField(sound, field);
    if constexpr (A::reading)
      if (sound.kind > SoundKind::explosion || sound.maker < -1 ||
          sound.maker >= static_cast<std::int32_t>(s.actors.size()))
        a.fail("a sound is out of range");
  }
  fixedCount(a, s.props.size(), "props");
  for (auto& prop : s.props) {
    a(prop.health);
    a(prop.destroyed);
    a(prop.blamed);
    a(prop.blamedTick);
  }
  // Pickups' and teams' fixed parts (what, where, which team) come from the level and the actors.
  fixedCount(a, s.pickups.size(), "pickups");
  for (auto& p : s.pickups) {
    a(p.available);
    a(p.respawnTick);
    a(p.takenBy);
    a(p.timesTaken);
  }
  fixedCount(a, s.teams.size(), "teams");
  for (auto& t : s.teams) {
    a(t.kills);
    a(t.deaths);
    a(t.suicides);
    a(t.exits);
    a(t.score);
  }
  const std::size_t grenades = a.count(s.grenades.size(), 30);
  if constexpr (A::reading) s.grenades.resize(grenades);
  for (auto& g : s.grenades) {
    a.index(g.thrower, s.actors.size());
    a.index(g.weapon, weapons);
    ioBody(a, g.body);
    a(g.fuse);
    a(g.bounces);
    a(g.live);
  }
}

}  // namespace

MatchSnapshot saveMatch(const MatchState& s) {
  MatchSnapshot out;
  rc::ByteWriter w(out);
  w.u32(kMagic);
  w.u32(kFormat);
  Out a(w);
  io(a, s, s.weapons.weapons.size());
  const rc::WorldSnapshot world = s.world->snapshot();
  w.count(world.size());
  out.insert(out.end(), world.begin(), world.end());
  return out;
}

void restoreMatch(MatchState& s, std::span<const std::uint8_t> snapshot) {
  try {
    rc::ByteReader r(snapshot, "match snapshot");
    if (r.u32() != kMagic) r.fail("not a match snapshot");
    if (const std::uint32_t format = r.u32(); format != kFormat)
      r.fail("format " + std::to_string(format) + ", this build reads " + std::to_string(kFormat));
    // Decoded into copies of the parts it changes, so that a refusal leaves the match whole.
    struct Parts {
      std::int64_t tick;
      rc::Random rng;
      std::vector<Actor> actors;
      std::vector<BotMind> minds;
      std::vector<Sound> sounds;
      std::vector<PropState> props;
      std::vector<PickupState> pickups;
      std::vector<TeamScore> teams;
      std::vector<Grenade> grenades;
    } parts{s.tick, s.rng, s.actors, s.minds, s.sounds, s.props, s.pickups, s.teams, s.grenades};
    In a(r);
    io(a, parts, s.weapons.weapons.size());
    const std::size_t worldBytes = r.count(1);
    if (r.position() + worldBytes != snapshot.size())
      r.fail("the world's snapshot does not end where the snapshot does");
    s.world->restore(snapshot.subspan(r.position()));
    s.tick = parts.tick;
    s.rng = parts.rng;
    s.actors = std::move(parts.actors);
    s.minds = std::move(parts.minds);
    s.sounds = std::move(parts.sounds);
    s.props = std::move(parts.props);
    s.pickups = std::move(parts.pickups);
    s.teams = std::move(parts.teams);
    s.grenades = std::move(parts.grenades);
    s.shots.clear();
    s.explosions.clear();
    s.crashes.clear();
    s.sightRays.clear();
    s.heard.clear();
  } catch (const std::invalid_argument& e) {
    throw MatchSnapshotError(e.what());
  }
}

std::uint64_t Match::hash() const {
  return fnv1a(saveMatch(s_));
}

namespace {

std::string floatText(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", static_cast<double>(v));
  return text;
}

std::string bodyName(const MatchState& s, rc::BodyId body) {
  std::string name = "body " + std::to_string(body.index);
  const std::uint64_t data = s.world->userData(body);
  if (const std::optional<GameRef> ref = gameRefOf(data)) {
    if (ref->kind == GameKind::actor && ref->index < s.actors.size())
      return name + " (actor " + std::to_string(ref->index) + " '" + s.actors[ref->index].name +
             "')";
    return name + " (grenade " + std::to_string(ref->index) + ")";
  }
  if (const std::optional<LevelRef> ref = levelRefOf(data);
      ref && ref->index < s.level.objects.size()) {
    const LevelObject& o = s.level.objects[ref->index];
    return name + " (" + levelObjectKindName(o.kind) + " " + std::to_string(o.tiledId) +
           (o.name.empty() ? "" : " '" + o.name + "'") + ")";
  }
  return name;
}

}  // namespace

std::vector<MatchDifference> compareMatches(const MatchState& a, const MatchState& b,
                                            std::size_t limit) {
  std::vector<MatchDifference> out;
  auto add = [&](std::string what, std::string x, std::string y) {
    if (out.size() < limit && x != y) out.push_back({std::move(what), std::move(x), std::move(y)});
  };
  auto addFloat = [&](const std::string& what, float x, float y) {
    if (std::bit_cast<std::uint32_t>(x) != std::bit_cast<std::uint32_t>(y))
      add(what, floatText(x), floatText(y));
  };
  auto addInt = [&](const std::string& what, std::int64_t x, std::int64_t y) {
    add(what, std::to_string(x), std::to_string(y));
  };
  // A body's state, field by field, under the name of what it belongs to.
  auto addBody = [&](const std::string& who, rc::BodyId body) {
    const bool inA = a.world->isValid(body), inB = b.world->isValid(body);
    if (!inA || !inB) {
      add(who, inA ? "present" : "absent", inB ? "present" : "absent");
      return;
    }
    const rc::Vec2 px = a.world->position(body), py = b.world->position(body);
    const rc::Vec2 vx = a.world->linearVelocity(body), vy = b.world->linearVelocity(body);
    addFloat(who + " position x", px.x, py.x);
    addFloat(who + " position y", px.y, py.y);
    addFloat(who + " angle", a.world->angle(body), b.world->angle(body));
    addFloat(who + " velocity x", vx.x, vy.x);
    addFloat(who + " velocity y", vx.y, vy.y);
    addFloat(who + " angular velocity", a.world->angularVelocity(body),
             b.world->angularVelocity(body));
    addInt(who + " awake", a.world->isAwake(body), b.world->isAwake(body));
    addInt(who + " enabled", a.world->isEnabled(body), b.world->isEnabled(body));
  };
  addInt("tick", a.tick, b.tick);
  // Entities first, each with its body: what a person looks for is "which thing, which field".
  for (std::size_t i = 0; i < a.actors.size() && i < b.actors.size(); ++i) {
    const Actor &x = a.actors[i], &y = b.actors[i];
    const std::string who = "actor " + std::to_string(i) + " ('" + x.name + "')";
    addBody(who + " body " + std::to_string(x.body.index), x.body);
    addInt(who + " alive", x.alive, y.alive);
    addFloat(who + " health", x.health, y.health);
    addFloat(who + " aim", x.aim, y.aim);
    addInt(who + " kills", x.kills, y.kills);
    addInt(who + " deaths", x.deaths, y.deaths);
    addInt(who + " suicides", x.suicides, y.suicides);
    addInt(who + " exits", x.exits, y.exits);
    addInt(who + " score", x.score, y.score);
    addInt(who + " cooldown", x.cooldown, y.cooldown);
    for (std::size_t w = 0; w < a.weapons.weapons.size(); ++w)
      addInt(who + " ammo of " + a.weapons.weapons[w].name, x.ammo[w], y.ammo[w]);
    add(who + " input", std::to_string(fnv1a(toBytes(x.input))),
        std::to_string(fnv1a(toBytes(y.input))));
  }
  for (std::size_t i = 0; i < a.minds.size() && i < b.minds.size(); ++i) {
    const BotMind &x = a.minds[i], &y = b.minds[i];
    const std::string who = "actor " + std::to_string(i) + " ('" + a.actors[i].name + "') mind ";
    add(who + "behaviour", behaviourName(x.behaviour), behaviourName(y.behaviour));
    addInt(who + "focus", x.focus, y.focus);
    addFloat(who + "goal x", x.goal.x, y.goal.x);
    addFloat(who + "goal y", x.goal.y, y.goal.y);
    addInt(who + "route length", x.route.length, y.route.length);
  }
  addInt("sounds", static_cast<std::int64_t>(a.sounds.size()),
         static_cast<std::int64_t>(b.sounds.size()));
  for (std::size_t i = 0; i < a.props.size() && i < b.props.size(); ++i) {
    const PropState &x = a.props[i], &y = b.props[i];
    const std::string who = "prop " + bodyName(a, x.body);
    addFloat(who + " health", x.health, y.health);
    addInt(who + " destroyed", x.destroyed, y.destroyed);
    if (!x.destroyed && !y.destroyed) addBody(who, x.body);
  }
  for (std::size_t i = 0; i < a.pickups.size() && i < b.pickups.size(); ++i) {
    const PickupState &x = a.pickups[i], &y = b.pickups[i];
    const std::string who = "pickup " + std::to_string(i);
    addInt(who + " available", x.available, y.available);
    addInt(who + " back at tick", x.respawnTick, y.respawnTick);
    addInt(who + " taken by", x.takenBy, y.takenBy);
  }
  for (std::size_t i = 0; i < a.teams.size() && i < b.teams.size(); ++i)
    addInt("team " + std::to_string(a.teams[i].team) + " score", a.teams[i].score,
           b.teams[i].score);
  addInt("grenades", static_cast<std::int64_t>(a.grenades.size()),
         static_cast<std::int64_t>(b.grenades.size()));
  for (std::size_t i = 0; i < a.grenades.size() && i < b.grenades.size(); ++i) {
    const Grenade &x = a.grenades[i], &y = b.grenades[i];
    const std::string who = "grenade " + std::to_string(i);
    addInt(who + " live", x.live, y.live);
    addInt(who + " fuse", x.fuse, y.fuse);
    if (x.live && y.live) addBody(who, x.body);
  }
  // The world's other bodies (the level's walls and triggers, should they move), by slot.
  const std::vector<rc::BodyId> bodiesA = a.world->bodies(), bodiesB = b.world->bodies();
  for (std::size_t i = 0, j = 0; i < bodiesA.size() || j < bodiesB.size();) {
    if (j == bodiesB.size() || (i < bodiesA.size() && bodiesA[i].index < bodiesB[j].index)) {
      add(bodyName(a, bodiesA[i]), "present", "absent");
      ++i;
    } else if (i == bodiesA.size() || bodiesB[j].index < bodiesA[i].index) {
      add(bodyName(b, bodiesB[j]), "absent", "present");
      ++j;
    } else {
      const rc::BodyId body = bodiesA[i++];
      ++j;
      const std::optional<GameRef> game = gameRefOf(a.world->userData(body));
      const std::optional<LevelRef> level = levelRefOf(a.world->userData(body));
      if (game || (level && level->kind == LevelObjectKind::prop)) continue;  // named above
      addBody(bodyName(a, body), body);
    }
  }
  add("the match's generator", std::to_string(a.rng.state()), std::to_string(b.rng.state()));
  // Whatever else differs (contacts, warm starts, sleep timers, the broadphase) shows in the
  // world's hash alone.
  if (out.empty() && a.world->stateHash() != b.world->stateHash())
    add("the world's contacts, timers or broadphase (bodies agree)", "equal", "differ");
  return out;
}

}  // namespace game
