// A level's content hash: what a recorded session checks before it replays on a level, so a
// level edited since the recording was made is refused instead of diverging at its first hash.
//
// It covers what decides a match on the level: the world the level builds (its state hash:
// bodies, shapes, materials' friction and restitution, the broadphase's square) and what is not
// physics (materials' thickness, health and hardness, spawns, pickups, triggers, paths,
// markers, the map's settings, and every custom property). Not the file's bytes: a map saved
// again by Tiled with its keys in another order is the same level.
#pragma once

#include <cstdint>

#include "game/level/level.h"

namespace game {

// `builtWorldHash`: rc::World::stateHash() of a world holding nothing but the built level.
std::uint64_t levelContentHash(const Level& level, std::uint64_t builtWorldHash);

}  // namespace game
