#include "game/level/level_error.h"

namespace game {

std::string quoteName(std::string_view text) {
  constexpr std::size_t kMaxShown = 60;
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7F) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else if (c == '\'' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > kMaxShown) out += "...";
  return out + "'";
}

void ErrorContext::fail(const std::string& what) const {
  std::string message = file_ + ": " + (where_.empty() ? "" : where_ + ": ") + what;
  // One line whatever a file's names hold: the commands print exactly one line per error.
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  throw LevelError(message);
}

}  // namespace game
