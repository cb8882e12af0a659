// Text taken from a file (a name, a path, a key) as an error or a summary shows it: quoted,
// control characters (C0 and C1) and bytes that are not UTF-8 written as \xNN so that a message
// stays one line and cannot drive the terminal (a newline, an ANSI escape, an 8-bit CSI), and
// cut at 60 bytes (never inside a UTF-8 character), so that a 1 MiB name makes a short line. One
// helper for every reader and command: the scene, the level, the recording's header.
// Header-only: the scene and level libraries both use it.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace game {

inline constexpr std::size_t kMaxQuotedBytes = 60;

// 'walls', "crate", 'two\x0alines', 'xxxx...' (the quote given: the scene's messages use ").
inline std::string quoteName(std::string_view text, char quote = '\'') {
  std::size_t shown = text.size();
  if (shown > kMaxQuotedBytes) {
    shown = kMaxQuotedBytes;
    // Back to the start of a UTF-8 character (continuation bytes are 10xxxxxx), at most three.
    for (int k = 0; k < 3 && shown > 0 && (static_cast<unsigned char>(text[shown]) & 0xC0) == 0x80;
         ++k)
      --shown;
  }
  static constexpr char kHex[] = "0123456789abcdef";
  auto escaped = [](std::string& out, unsigned char c) {
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 15];
  };
  // The length of the well-formed UTF-8 character at i (RFC 3629: no overlong forms, no
  // surrogates, nothing past U+10FFFF), 0 when the bytes there are not one.
  auto characterAt = [&](std::size_t i) -> std::size_t {
    const auto b = [&](std::size_t k) {
      return static_cast<unsigned char>(i + k < shown ? text[i + k] : '\0');
    };
    const unsigned char c = b(0);
    auto tail = [&](std::size_t k) { return (b(k) & 0xC0) == 0x80; };
    if (c >= 0xC2 && c <= 0xDF) return tail(1) ? 2 : 0;
    if (c >= 0xE0 && c <= 0xEF) {
      const unsigned char lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
      return b(1) >= lo && b(1) <= hi && tail(2) ? 3 : 0;
    }
    if (c >= 0xF0 && c <= 0xF4) {
      const unsigned char lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
      return b(1) >= lo && b(1) <= hi && tail(2) && tail(3) ? 4 : 0;
    }
    return 0;
  };
  std::string out(1, quote);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7F) {
      escaped(out, c);
    } else if (c < 0x80) {
      if (c == static_cast<unsigned char>(quote) || c == '\\') out += '\\';
      out += static_cast<char>(c);
    } else if (const std::size_t n = characterAt(i);
               n == 0 || (c == 0xC2 && static_cast<unsigned char>(text[i + 1]) <= 0x9F)) {
      // Not UTF-8 (a lone 0x9B is a terminal's CSI, as ESC [ is), or U+0080 to U+009F, the C1
      // controls: the byte as \xNN, and the next byte looked at on its own.
      escaped(out, c);
    } else {
      out.append(text.substr(i, n));
      i += n - 1;
    }
  }
  if (shown < text.size()) out += "...";
  out += quote;
  return out;
}

// Whether quoteName(text, quote) only adds the quotes: nothing to escape, nothing cut. A message
// may then show the text as it is (a typo'd key, a level's path).
inline bool isPlainText(std::string_view text, char quote = '\'') {
  // Compared as text, not by length: a cut text plus "..." can have the length of the whole.
  return text.size() <= kMaxQuotedBytes &&
         quoteName(text, quote) == std::string(1, quote) + std::string(text) + quote;
}

}  // namespace game
