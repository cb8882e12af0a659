#include "game/level/json_fields.h"

#include <cmath>
#include <string>

#include "game/input_file.h"
#include "game/json_guard.h"

namespace game::json_fields {

namespace {

std::string field(const char* key) {
  return std::string("'") + key + "'";
}

}  // namespace

Json parseText(std::string_view text, const ErrorContext& at) {
  if (text.size() > kMaxFileBytes)
    at.fail("the file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  // The callback sees every value as it opens and every key (game/json_guard.h): refusing depth
  // here bounds the parser's own stack and every recursive walk of the tree after it; a key twice
  // in one object is refused, not silently the last one's.
  JsonGuard limits(kMaxDepth);
  const Json::parser_callback_t guard = [&](int depth, Json::parse_event_t event, Json& value) {
    switch (limits.check(depth, event, value)) {
      case JsonGuard::Problem::tooDeep:
        at.fail("not a Tiled file: JSON nested deeper than " + std::to_string(kMaxDepth) +
                " levels");
      case JsonGuard::Problem::duplicateKey:
        at.fail("the key " + quoteName(value.get<std::string>()) + " appears twice in one object");
      case JsonGuard::Problem::none:
        break;
    }
    return true;
  };
  try {
    return Json::parse(text.begin(), text.end(), guard);
  } catch (const Json::exception& e) {
    // nlohmann's messages: "[json.exception.parse_error.101] parse error at line L, column C:
    // what", or "[json.exception.out_of_range.406] number overflow parsing '1e999'". Keep what
    // follows its tag.
    const std::string what = e.what();
    const auto line = what.find("line "), tag = what.find("] ");
    if (line != std::string::npos) at.fail("not valid JSON at " + what.substr(line));
    at.fail("not valid JSON: " + (tag == std::string::npos ? what : what.substr(tag + 2)));
  }
}

Json parseFile(const std::string& path, const ErrorContext& at) {
  std::string text;
  if (const auto why = readInputFile(path, kMaxFileBytes, text)) at.fail(*why);
  return parseText(text, at);
}

std::string describe(const Json& value) {
  return describeJson(value);
}

const Json* find(const Json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

double number(const Json& object, const char* key, const ErrorContext& at,
              std::optional<double> fallback, double limit) {
  const Json* v = find(object, key);
  if (v == nullptr) {
    if (!fallback) at.fail(field(key) + " is missing");
    return *fallback;
  }
  if (!v->is_number()) at.fail(field(key) + " must be a number, got " + describe(*v));
  const double d = v->get<double>();
  if (!std::isfinite(d) || std::fabs(d) > limit)
    at.fail(field(key) + " must be a number from -" + describe(Json(limit)) + " to " +
            describe(Json(limit)) + ", got " + describe(*v));
  return d;
}

std::int64_t integer(const Json& object, const char* key, const ErrorContext& at, std::int64_t min,
                     std::int64_t max, std::optional<std::int64_t> fallback) {
  const Json* v = find(object, key);
  if (v == nullptr) {
    if (!fallback) at.fail(field(key) + " is missing");
    return *fallback;
  }
  const std::string range = "an integer from " + std::to_string(min) + " to " + std::to_string(max);
  bool ok = false;
  std::int64_t result = 0;
  if (v->is_number_unsigned()) {
    const std::uint64_t u = v->get<std::uint64_t>();
    ok = u <= static_cast<std::uint64_t>(max);
    result = ok ? static_cast<std::int64_t>(u) : 0;
  } else if (v->is_number_integer()) {
    result = v->get<std::int64_t>();
    ok = true;
  } else if (v->is_number_float()) {
    // Other tools write 32.0 where Tiled writes 32: accepted when exactly an integer.
    const double d = v->get<double>();
    ok = std::isfinite(d) && d == std::floor(d) && d >= static_cast<double>(min) &&
         d <= static_cast<double>(max);
    result = ok ? static_cast<std::int64_t>(d) : 0;
  }
  if (!ok || result < min || result > max)
    at.fail(field(key) + " must be " + range + ", got " + describe(*v));
  return result;
}

std::string text(const Json& object, const char* key, const ErrorContext& at,
                 std::optional<std::string> fallback) {
  const Json* v = find(object, key);
  if (v == nullptr) {
    if (!fallback) at.fail(field(key) + " is missing");
    return *fallback;
  }
  if (!v->is_string()) at.fail(field(key) + " must be a string, got " + describe(*v));
  return v->get<std::string>();
}

bool boolean(const Json& object, const char* key, const ErrorContext& at,
             std::optional<bool> fallback) {
  const Json* v = find(object, key);
  if (v == nullptr) {
    if (!fallback) at.fail(field(key) + " is missing");
    return *fallback;
  }
  if (!v->is_boolean()) at.fail(field(key) + " must be true or false, got " + describe(*v));
  return v->get<bool>();
}

const Json* array(const Json& object, const char* key, const ErrorContext& at, bool required) {
  const Json* v = find(object, key);
  if (v == nullptr) {
    if (required) at.fail(field(key) + " is missing");
    return nullptr;
  }
  if (!v->is_array()) at.fail(field(key) + " must be an array, got " + describe(*v));
  return v;
}

void requireObject(const Json& value, const ErrorContext& at, const std::string& what) {
  if (!value.is_object()) at.fail(what + " must be a JSON object, got " + describe(value));
}

}  // namespace game::json_fields
