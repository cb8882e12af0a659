// What every JSON reader of the game (scene, level and tileset, weapon table) checks through
// nlohmann's parser callback, which sees every value as it opens and every key: nesting deeper
// than the reader's limit, refused as it opens (bounding the parser's stack and every recursive
// walk of the tree after it, an error message's rendering of a value included), and a key seen
// twice in one object, which nlohmann would otherwise keep the last of silently. The keys of the
// open objects are kept in sets, so an object of a million keys costs n log n, not n^2. The
// reader words the errors. Header-only, for the .cpp files that parse (nlohmann stays out of
// the libraries' public headers).
#pragma once

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace game {

class JsonGuard {
 public:
  enum class Problem { none, tooDeep, duplicateKey };

  explicit JsonGuard(int maxDepth) : maxDepth_(maxDepth) {}

  // For the parser callback's arguments; on duplicateKey, `value` is the key (a string).
  Problem check(int depth, nlohmann::json::parse_event_t event, const nlohmann::json& value) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start || event == Event::array_start) {
      if (depth >= maxDepth_) return Problem::tooDeep;
      if (event == Event::object_start) keys_.emplace_back();
    } else if (event == Event::object_end) {
      if (!keys_.empty()) keys_.pop_back();
    } else if (event == Event::key && !keys_.empty()) {
      if (!keys_.back().insert(value.get<std::string>()).second) return Problem::duplicateKey;
    }
    return Problem::none;
  }

 private:
  int maxDepth_;
  std::vector<std::set<std::string>> keys_;  // per open object, its keys so far
};

// At most 40 characters of a value, for the readers' messages: the JSON as written, with every
// character past ASCII as \uXXXX (so a cut never splits a character and no C1 control or 8-bit
// CSI reaches a terminal), invalid UTF-8 replaced rather than thrown.
inline std::string describeJson(const nlohmann::json& value) {
  std::string s = value.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

}  // namespace game
