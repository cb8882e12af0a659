// Score: per actor and per team, kills of enemies, deaths, suicides (deaths no enemy scored
// for), exits reached, and the points they make (RuleTuning::killScore, exitScore). A team's
// numbers are always the sums of its actors'.
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"

namespace game {

// One TeamScore per team of the actors, in the order the teams first appear.
void makeTeams(MatchState& s);
// The team's score (added if the team is new).
TeamScore& teamScore(MatchState& s, int team);

// A death: the victim's deaths count; an enemy attacker scores a kill, otherwise (no attacker,
// itself, a team-mate) it is the victim's suicide.
void scoreDeath(MatchState& s, std::size_t victim, std::optional<std::size_t> attacker);
// An exit reached: the actor's and its team's exits and points.
void scoreExit(MatchState& s, std::size_t actor);

}  // namespace game
