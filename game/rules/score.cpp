#include "game/rules/score.h"

namespace game {

void makeTeams(MatchState& s) {
  s.teams.clear();
  for (const Actor& a : s.actors)
    teamScore(s, a.team);
}

TeamScore& teamScore(MatchState& s, int team) {
  for (TeamScore& t : s.teams)
    if (t.team == team) return t;
  TeamScore t;
  t.team = team;
  s.teams.push_back(t);
  return s.teams.back();
}

void scoreDeath(MatchState& s, std::size_t victim, std::optional<std::size_t> attacker) {
  Actor& v = s.actors[victim];
  TeamScore& vt = teamScore(s, v.team);
  ++v.deaths;
  ++vt.deaths;
  if (attacker && *attacker != victim && s.actors[*attacker].team != v.team) {
    Actor& a = s.actors[*attacker];
    TeamScore& at = teamScore(s, a.team);
    ++a.kills;
    ++at.kills;
    a.score += s.rules.killScore;
    at.score += s.rules.killScore;
  } else {
    ++v.suicides;
    ++vt.suicides;
  }
}

void scoreExit(MatchState& s, std::size_t actor) {
  Actor& a = s.actors[actor];
  TeamScore& t = teamScore(s, a.team);
  ++a.exits;
  ++t.exits;
  a.score += s.rules.exitScore;
  t.score += s.rules.exitScore;
}

}  // namespace game
