// A match's whole state as bytes and back: the world's snapshot and the match's own state (the
// tick, the generator, actors, bots' minds, props, grenades). What recorded sessions store as
// keyframes, what `replay --synctest` saves and restores every tick, and what Match::hash()
// hashes: one description of the state, so a field the snapshot misses is a field the hash
// misses too, and the synctest finds it.
//
// What is derived from the level and the configuration (the level itself, the weapon table,
// bodies' handles made at the start, actors' names and teams) is not written: a snapshot is
// restored into a match made from the same level and configuration, and is refused otherwise.
// This tick's shots and explosions are outputs for the view, not state, and are not written.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "game/match/match.h"
#include "physics/bytes.h"

namespace game {

using MatchSnapshot = std::vector<std::uint8_t>;

// Why a snapshot was refused (truncated, corrupt, or of another match), in one line.
class MatchSnapshotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

MatchSnapshot saveMatch(const MatchState& s);

// Restores a snapshot made by saveMatch of a match with the same level and configuration. A
// refused snapshot (MatchSnapshotError) leaves the match as it was.
void restoreMatch(MatchState& s, std::span<const std::uint8_t> snapshot);

using rc::fnv1a;  // (physics/bytes.h)

// What differs between two matches of the same level and configuration, in the order the state
// is described (the tick, the generator, actors, minds, props, grenades, then the world's
// bodies), each as "what: a vs b"; at most `limit` of them. For naming a divergence.
struct MatchDifference {
  std::string
      what;  // "actor 3 ('bot 2') body 17 position x", "prop body 9 (prop 31 'crate') angle"
  std::string recorded, replayed;
};
std::vector<MatchDifference> compareMatches(const MatchState& recorded, const MatchState& replayed,
                                            std::size_t limit = 16);

}  // namespace game
