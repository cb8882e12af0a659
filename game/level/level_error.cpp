#include "game/level/level_error.h"

namespace game {

void ErrorContext::fail(const std::string& what) const {
  std::string message = file_ + ": " + (where_.empty() ? "" : where_ + ": ") + what;
  // One line whatever a file's names hold: the commands print exactly one line per error.
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  throw LevelError(message);
}

}  // namespace game
