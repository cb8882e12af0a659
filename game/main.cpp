#include <cstdio>
#include <exception>
#include <string_view>
#include <vector>

#include "game/cli.h"

namespace {

constexpr const char* kUsage =
    "usage: ricochet <command> [options]\n"
    "\n"
    "commands:\n"
    "  demo      run the geometry demo and print results beside hand-worked values\n"
    "  sim       step a scene file and write the final state (and a trajectory)\n"
    "  level     read a Tiled level, build its world and say what it holds\n"
    "  play      play a headless match on a level, bots against the autopilot (--record)\n"
    "  replay    play a recorded session back, verify it, or verify many (--batch)\n"
    "  info      say what a recording holds and whether it is whole\n"
    "  render    draw one tick of a recording as a PNG\n"
    "\n"
    "ricochet <command> --help (or ricochet help <command>) shows a command's options.\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string_view> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::puts("ricochet 0.1.0");
    return 0;
  }
  // `ricochet help` and `ricochet help COMMAND`, as git and cargo take them.
  static constexpr std::string_view kHelp[] = {"--help"};
  std::vector<std::string_view> helpArgs;
  if (args[0] == "help") {
    if (args.size() == 1) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    helpArgs = {args[1], kHelp[0]};
    args = helpArgs;
  }
  std::string_view command = args[0];
  std::span<const std::string_view> rest(args.data() + 1, args.size() - 1);
  // Each command words its own errors; this is the last line of defence, so that nothing a
  // command did not foresee (a renderer that cannot load, memory refused) ends in
  // std::terminate: one line naming the command, exit 1.
  try {
    if (command == "demo") return game::runDemo(rest);
    if (command == "sim") return game::runSim(rest);
    if (command == "level") return game::runLevel(rest);
    if (command == "play") return game::runPlay(rest);
    if (command == "replay") return game::runReplay(rest);
    if (command == "info") return game::runInfo(rest);
    if (command == "render") return game::runRender(rest);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ricochet %.*s: %s\n", static_cast<int>(command.size()), command.data(),
                 e.what());
    return 1;
  }
  std::fprintf(stderr, "ricochet: unknown command '%.*s' (try ricochet --help)\n",
               static_cast<int>(command.size()), command.data());
  return 2;
}
