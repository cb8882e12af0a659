// The ricochet command line: one executable, one subcommand per job.
#pragma once

#include <span>
#include <string_view>

namespace game {

// `ricochet demo`: builds a few shapes, runs queries on them and prints each result beside the
// value worked out by hand, so a person can check the engine at a glance.
int runDemo(std::span<const std::string_view> args);

// `ricochet sim SCENE.json --steps N ...`: steps a scene file, writes the final state.
int runSim(std::span<const std::string_view> args);

// `ricochet level LEVEL.tmj [--json]`: reads a Tiled level, builds it, prints what it holds.
int runLevel(std::span<const std::string_view> args);

// `ricochet play LEVEL.tmj [--bots K] [--seed S] [--ticks N] [--json] [--frames DIR ...]`: a
// headless match, rendered with --frames.
int runPlay(std::span<const std::string_view> args);

// `ricochet replay FILE [--verify] ...` and `ricochet replay --batch ...`: recorded sessions
// played back (game/commands/replay.cpp).
int runReplay(std::span<const std::string_view> args);

// `ricochet info FILE [--json]`: what a recording holds and whether it is whole.
int runInfo(std::span<const std::string_view> args);

// `ricochet render FILE --tick T -o out.png`: one tick of a recording as a picture.
int runRender(std::span<const std::string_view> args);

}  // namespace game
