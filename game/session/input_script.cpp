#include "game/session/input_script.h"

#include <cmath>
#include <sstream>

#include "game/input_file.h"
#include "physics/trig.h"

namespace game {
namespace {

// Long lines are cut in messages; control characters are shown as '?'.
std::string shown(const std::string& text) {
  std::string out;
  for (const char c : text.substr(0, 40))
    out += static_cast<unsigned char>(c) < 0x20 || c == 0x7F ? '?' : c;
  return text.size() > 40 ? out + "..." : out;
}

}  // namespace

InputScript::InputScript(std::istream& in, std::string name, int players)
    : in_(in), name_(std::move(name)), current_(static_cast<std::size_t>(players)) {}

bool InputScript::readLine() {
  std::string text;
  bool tooLong = false;
  while (readBoundedLine(in_, text, 4096, tooLong)) {
    ++lineNumber_;
    if (tooLong)
      throw InputScriptError(name_ + ":" + std::to_string(lineNumber_) + ": the line is over " +
                             "4096 characters");
    const std::size_t hash = text.find('#');
    if (hash != std::string::npos) text.erase(hash);
    std::istringstream fields(text);
    std::vector<std::string> f;
    for (std::string word; fields >> word;)
      f.push_back(word);
    if (f.empty()) continue;
    const std::string at = name_ + ":" + std::to_string(lineNumber_) + ": ";
    if (f.size() != 7)
      throw InputScriptError(at + "expected 7 fields (tick player move_x move_y aim buttons " +
                             "weapon), got " + std::to_string(f.size()));
    auto number = [&](std::size_t k, const char* what) {
      try {
        std::size_t used = 0;
        const double v = std::stod(f[k], &used);
        if (used == f[k].size() && std::isfinite(v)) return v;
      } catch (const std::exception&) {
      }
      throw InputScriptError(at + what + " is not a number: '" + shown(f[k]) + "'");
    };
    auto integer = [&](std::size_t k, const char* what, double lo, double hi) {
      const double v = number(k, what);
      if (v != std::floor(v) || v < lo || v > hi)
        throw InputScriptError(at + what + " must be a whole number from " +
                               std::to_string(static_cast<long long>(lo)) + " to " +
                               std::to_string(static_cast<long long>(hi)) + ", got '" +
                               shown(f[k]) + "'");
      return static_cast<std::int64_t>(v);
    };
    if (current_.empty()) throw InputScriptError(at + "the match has no players to script");
    Line line;
    line.tick = integer(0, "the tick", 0, 1e15);
    line.player =
        static_cast<int>(integer(1, "the player", 0, static_cast<double>(current_.size()) - 1.0));
    if (line.tick < lastTick_)
      throw InputScriptError(at + "tick " + std::to_string(line.tick) + " comes after tick " +
                             std::to_string(lastTick_));
    lastTick_ = line.tick;
    const double mx = number(2, "move_x"), my = number(3, "move_y");
    if (std::fabs(mx) > 1.0 || std::fabs(my) > 1.0)
      throw InputScriptError(at + "move_x and move_y must be within -1 to 1");
    const double degrees = number(4, "aim");
    if (std::fabs(degrees) > 1e6) throw InputScriptError(at + "aim is beyond a million degrees");
    std::uint8_t buttons = 0;
    if (f[5] != "-") {
      for (const char c : f[5]) {
        if (c == 'f') {
          buttons |= kButtonFire;
        } else if (c == 't') {
          buttons |= kButtonThrow;
        } else if (c == 'r') {
          buttons |= kButtonReload;
        } else {
          throw InputScriptError(at + "buttons are f, t, r or -, got '" + shown(f[5]) + "'");
        }
      }
    }
    const auto weapon = static_cast<std::uint8_t>(integer(6, "the weapon", 0, 255));
    // Degrees to radians in double, then the input's own rounding (1/65536 of a turn).
    const double radians = degrees * (static_cast<double>(rc::kPi) / 180.0);
    line.input = makeInput({static_cast<float>(mx), static_cast<float>(my)},
                           static_cast<float>(radians), buttons, weapon);
    pending_ = line;
    return true;
  }
  if (in_.bad()) throw InputScriptError(name_ + ": cannot read it");
  return false;
}

const std::vector<PlayerInput>& InputScript::inputsFor(std::int64_t tick) {
  // Apply every line up to `tick`; to know none is left for it, read one line beyond (or the end).
  while (true) {
    if (!pending_) {
      if (ended_ || !readLine()) {
        ended_ = true;
        break;
      }
    }
    if (pending_->tick > tick) break;
    current_[static_cast<std::size_t>(pending_->player)] = pending_->input;
    pending_.reset();
  }
  return current_;
}

}  // namespace game
