#include "game/level/json_fields.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace game::json_fields {

namespace {

std::string field(const char* key) {
  return std::string("'") + key + "'";
}

}  // namespace

Json parseText(std::string_view text, const ErrorContext& at) {
  if (text.size() > kMaxFileBytes)
    at.fail("the file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  // The callback sees every value as it opens: refusing depth here bounds the parser's own
  // stack and every recursive walk of the tree after it.
  const Json::parser_callback_t limitDepth = [&at](int depth, Json::parse_event_t event, Json&) {
    if ((event == Json::parse_event_t::object_start || event == Json::parse_event_t::array_start) &&
        depth >= kMaxDepth)
      at.fail("not a Tiled file: JSON nested deeper than " + std::to_string(kMaxDepth) + " levels");
    return true;
  };
  try {
    return Json::parse(text.begin(), text.end(), limitDepth);
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
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) at.fail("cannot open the file: it does not exist");
  if (std::filesystem::is_directory(status)) at.fail("cannot open the file: it is a directory");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxFileBytes)
    at.fail("the file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) at.fail("cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) at.fail("cannot read the file");
  return parseText(text.str(), at);
}

std::string describe(const Json& value) {
  std::string s = value.dump(-1, ' ', false, Json::error_handler_t::replace);
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
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
