// A match: a level, the physics world it is built into, the actors (players and bots) and what
// they do, advanced one fixed tick at a time.
//
// The tick reads top to bottom (Quake III's G_RunFrame is the model; Match::tick):
//   decide      every bot (and every player on autopilot) perceives: hears the sounds the last
//               tick made, looks (sight cone and line-of-sight rays) every few ticks, staggered
//               across bots; then fills its input from what it remembers (bots/brain.cpp: patrol,
//               investigate, chase, attack, take cover, flee; paths on the navigation grid);
//               then the last tick's sounds are forgotten
//   move        actors accelerate towards what their input asks; running makes footsteps
//   weapons     grenades whose fuse ran out explode; shots are ray casts through the world,
//               now, before the bodies move (penetration, ricochets); grenades are thrown; shots
//               and blasts are heard
//   physics     the world steps once (World::step)
//   rules       the step's events: impacts, triggers (kill zones, exits), grenades' bounces;
//               pickups taken and back; respawns due
// Entities refer to bodies by handle and are created and removed between steps only. Randomness
// comes from the match's own generator, seeded by the config; order is creation order.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "game/bots/bot_state.h"
#include "game/bots/navigation.h"
#include "game/level/level.h"
#include "game/level/level_builder.h"
#include "game/match/input.h"
#include "game/weapons/weapon_table.h"
#include "physics/random.h"
#include "physics/world.h"

namespace game {

enum class ActorKind : std::uint8_t { player, bot };

// Tuning shared by every actor (one table, so a level or a test can change it in one place).
struct ActorTuning {
  float radius = 0.35f;        // m
  float density = 8.0f;        // kg/m^2 (a 3 kg disc: crates push back)
  float maxSpeed = 5.0f;       // m/s
  float acceleration = 40.0f;  // m/s^2
  float health = 100.0f;
  float respawnSeconds = 3.0f;
  // The penetration budget a shot spends crossing an actor (crates: 0.3, from the levels): a
  // body stops most of a round. The rifle (budget 1) goes through one actor with 40% of its
  // damage left and is stopped by a second; a shotgun pellet (0.1) is stopped by the first.
  float thickness = 0.6f;
};

// The rules' numbers (game/rules/), in one place like ActorTuning.
struct RuleTuning {
  // Impacts (rules/impacts.h): a contact that begins closing faster than impactSpeed hurts what
  // it joins by impactDamage per N s of the impulse the speed above it carries,
  // D = impactDamage * mu * (v - impactSpeed), mu the pair's reduced mass. 6 m/s is above what
  // walking (5 m/s) gives against anything at rest. With the bundled weapons: a 1 kg crate a
  // blast throws at 7 m/s deals 3 to an actor standing, 18 to one running at it; a grenade
  // (0.094 kg) thrown at a standing actor 4; an actor a blast throws against a wall at 7.6 m/s
  // (2.6 from the blast, 5 its own) takes 20.
  float impactSpeed = 6.0f;   // m/s
  float impactDamage = 4.0f;  // per N s
  // A blast's thrower is credited with what the bodies it pushed do for this long (ticks).
  std::int64_t blameTicks = 2 * kTicksPerSecond;
  // Score: points per kill of an enemy and per exit reached.
  int killScore = 1;
  int exitScore = 5;
};

struct Actor {
  ActorKind kind = ActorKind::bot;
  int team = 0;  // its spawn's (a level's `team`; players 0 and bots 1 where it has none)
  std::string name;
  rc::BodyId body;
  bool alive = true;
  float health = 0.0f;
  float aim = 0.0f;               // radians: where it faces (from its last input)
  std::int64_t respawnTick = -1;  // while dead: the tick it comes back
  // Score (rules/score.h): kills of enemies, deaths, the deaths no enemy scored for (its own
  // grenade, a kill zone, a team-mate, a crate no enemy threw), exits reached, and the points.
  int kills = 0, deaths = 0, suicides = 0, exits = 0, score = 0;
  // The thrower of the last blast that pushed it, and when (-1: none): credited with an impact
  // it suffers within RuleTuning::blameTicks (thrown against a wall).
  std::int32_t blamed = -1;
  std::int64_t blamedTick = -1;
  int cooldown = 0;                     // ticks until it can fire or throw again
  std::array<int, kMaxWeapons> ammo{};  // per weapon of the table
  PlayerInput input;                    // this tick's
};

// A level object the match follows: every dynamic one (crates, barrels: pushed, thrown by
// blasts) and every one with health (its material's health above zero), in the level's order.
struct PropState {
  std::size_t object = 0;  // index in Level::objects
  rc::BodyId body;
  float health = 0.0f;        // what is left (0 for an indestructible prop)
  bool destructible = false;  // its material has health: it can be destroyed
  bool destroyed = false;     // its body has left the world
  // The thrower of the last blast that pushed it, and when (-1: none): credited with the
  // impacts it deals within RuleTuning::blameTicks.
  std::int32_t blamed = -1;
  std::int64_t blamedTick = -1;
};

// Team scores: the sums of its actors' (rules/score.h), one per team in the order the teams
// first appear among the actors.
struct TeamScore {
  std::int32_t team = 0;
  std::int32_t kills = 0, deaths = 0, suicides = 0, exits = 0, score = 0;
};

// What a pickup is to the game (LevelPickup::item): an item it does not know is never taken.
enum class PickupItem : std::uint8_t { unknown, health, ammo };

// A level pickup (rules/pickups.h): what it gives, where, and whether it is there now. Taken by a
// living actor whose disc touches its circle and who can use it; back respawnTicks later.
struct PickupState {
  std::uint32_t pickup = 0;  // index in BuiltLevel::pickups
  PickupItem item = PickupItem::unknown;
  std::uint8_t weapon = 0;        // ammo: the weapon whose rounds it gives (index in the table)
  float amount = 0.0f;            // health points, or rounds (whole: rounded down)
  rc::Vec2 position{};            // its centre (m)
  float radius = 0.5f;            // m
  std::int32_t respawnTicks = 0;  // 0: taken once, never back
  bool available = true;          // there to be taken
  std::int64_t respawnTick = -1;  // while taken: the tick it is back (-1: never)
  std::int32_t takenBy = -1;      // the actor that took it last
  std::int32_t timesTaken = 0;
};

// What a shot did this tick, for the view and the tests: its path as straight segments (more
// than one when it ricochets or passes through), and who it hit.
struct Shot {
  std::size_t shooter = 0;
  std::size_t weapon = 0;      // index in the weapon table
  int pellet = 0;              // which of the weapon's pellets (a shotgun fires several at once)
  std::vector<rc::Vec2> path;  // from the muzzle through every bounce to where it ended
  std::vector<std::size_t> actorsHit;  // in the order it met them
};

// A thrown grenade: a dynamic circle body (a bullet for continuous collision) until its fuse runs
// out. Slots are reused in order once a grenade has exploded (its body user data names the slot).
struct Grenade {
  std::size_t thrower = 0;
  std::size_t weapon = 0;  // its spec in the weapon table
  rc::BodyId body;
  int fuse = 0;     // ticks left
  int bounces = 0;  // contacts it hit faster than the world's hit-event threshold
  bool live = false;
};

// A contact this tick that began faster than RuleTuning::impactSpeed and hurt (rules/impacts.h),
// for the view and the tests. Sides are actors or props (-1: neither, a wall, a grenade).
struct Crash {
  rc::Vec2 point{};
  float speed = 0.0f;   // approach speed, m/s
  float damage = 0.0f;  // dealt to each side that can be hurt
  std::array<std::int32_t, 2> actor{-1, -1};
  std::array<std::int32_t, 2> object{-1, -1};  // level objects (props)
  std::int32_t credited = -1;                  // the actor credited with a kill
};

// An explosion this tick, for the view and the tests.
struct Explosion {
  std::size_t thrower = 0;
  rc::Vec2 center{};
  float radius = 0.0f;
  std::vector<std::size_t> actorsHit;  // actors it reached (in line of sight, within the radius)
  int bodiesPushed = 0;                // dynamic bodies it reached, actors included
};

struct MatchState;

struct MatchConfig {
  int bots = -1;           // bots to field: -1 every bot spawn of the level; more reuse them
  int players = 1;         // players, driven by the autopilot unless inputs are given
  std::uint64_t seed = 1;  // the match's randomness (aim error, spawn choices)
  // The weapons; none: the bundled table (bundledWeaponTablePath()), and an error if it is bad.
  std::optional<WeaponTable> weapons;
  // The contact solver's batch width, 4 or 8 (WorldDef::maxSolverLanes): the same match at
  // either; a test checks it.
  int solverLanes = 8;
  // Time each phase of the tick into MatchState::profile (a clock read around each phase, about
  // 1% of a tick; off by default).
  bool profile = false;
  // Called at the end of every tick, for tests only: state kept here is hidden from snapshots
  // and hashes, which is what `replay --synctest` exists to catch.
  std::function<void(MatchState&)> testHook;
};

// Where a tick's time goes (MatchConfig::profile), summed over the ticks played: decide split
// into the bots' senses (perception: sight rays, hearing) and what they do with them (decisions:
// memory, behaviours, paths), then the tick's other phases. Not state: never saved or hashed.
struct MatchProfile {
  double perception = 0, decisions = 0, movement = 0, weapons = 0, physics = 0, rules = 0;  // s
  std::int64_t ticks = 0;
  double total() const { return perception + decisions + movement + weapons + physics + rules; }
};

// The whole match, open to the phase functions of game/ (each phase is a file of its own).
struct MatchState {
  Level level;
  MatchConfig config;
  std::uint64_t levelHash = 0;  // levelContentHash of the level (what a recording checks)
  ActorTuning tuning;
  RuleTuning rules;
  WeaponTable weapons;
  std::unique_ptr<rc::World> world;
  BuiltLevel built;
  std::vector<Actor> actors;
  // What bots keep between ticks (bots/bot_state.h lists every field): one mind per actor, and
  // the sounds made during the last tick (the next decide phase hears them, then they are gone).
  std::vector<BotMind> minds;
  std::vector<Sound> sounds;
  std::vector<PropState> props;
  std::vector<PickupState> pickups;  // one per BuiltLevel::pickups, in order
  std::vector<TeamScore> teams;
  rc::Random rng{1};
  std::int64_t tick = 0;
  std::vector<Grenade> grenades;
  std::vector<Shot> shots;            // this tick's
  std::vector<Explosion> explosions;  // this tick's
  std::vector<Crash> crashes;         // this tick's
  // For the view, this tick's perception (never read back by the simulation, so not state):
  // the line-of-sight rays bots cast and the sounds they heard.
  std::vector<SightRay> sightRays;
  std::vector<HeardSound> heard;
  MatchProfile profile;
  // Derived from the level, the same for every match on it (not hashed, not saved): where actors
  // can walk. And scratch, rebuilt before each use: the path search's arrays, and the actors'
  // centres as the decide phase began.
  NavGrid nav;
  PathSearch navSearch;
  std::vector<rc::Vec2> centers;
};

// User data of the bodies and shapes a match creates (a level's carry levelUserData): a tag in
// the top byte, the kind, and the index in its list.
enum class GameKind : std::uint8_t { actor, projectile };
inline constexpr std::uint64_t kGameUserDataTag = std::uint64_t{0x47} << 56;  // 'G'
constexpr std::uint64_t gameUserData(GameKind kind, std::size_t index) {
  return kGameUserDataTag | std::uint64_t{static_cast<std::uint8_t>(kind)} << 48 |
         static_cast<std::uint32_t>(index);
}
struct GameRef {
  GameKind kind;
  std::size_t index;
};
std::optional<GameRef> gameRefOf(std::uint64_t userData);

class Match {
 public:
  Match(Level level, const MatchConfig& config);

  // One tick. `inputs` has one record per player (MatchState::actors' players, in order);
  // players without one are driven by the autopilot.
  void tick(std::span<const PlayerInput> inputs = {});

  const MatchState& state() const { return s_; }
  MatchState& state() { return s_; }
  // FNV-1a over the match's snapshot (match_snapshot.h: the world's and the match's own state,
  // in creation order): equal hashes, equal futures.
  std::uint64_t hash() const;

 private:
  MatchState s_;
};

// The phases of the tick, in its order (each in its own file).
void decideBots(MatchState& s, std::span<const PlayerInput> inputs);  // bots/brain.cpp
void moveActors(MatchState& s);                                       // match/movement.cpp
void fireWeapons(MatchState& s);  // weapons/weapons.cpp: fuses, then shots and throws
void applyRules(MatchState& s);   // rules/rules.cpp

}  // namespace game
