// Typed reads of Tiled's JSON, with the reader's guards against hostile files: a size and a
// nesting limit on the parse, every number finite and within what a level can use, integers
// exact. A missing or mistyped field fails with its name and what was found instead:
// "layer 'walls': 'width' must be an integer from 1 to 4096, got \"40\"". Internal to the
// level library (nlohmann-json stays out of its public headers).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "game/level/level_error.h"

namespace game::json_fields {

using Json = nlohmann::json;

// Files larger than this are refused before parsing (the bundled levels are a few kB; the
// largest map allowed, 2^22 tiles, is about 22 MiB of base64). The parsed tree takes several
// times the file's size, so this bounds the reader's memory too.
inline constexpr std::uintmax_t kMaxFileBytes = 32u << 20;
// Deeper nesting than this is refused while parsing: a Tiled map needs about ten levels
// (map, layers, groups, objects, points), and a deep file must not exhaust the stack later.
inline constexpr int kMaxDepth = 64;
// The largest coordinate, size or offset a level may use, in pixels: 10 km at 1000 px/m.
inline constexpr double kMaxCoordinate = 1e7;

// The file read and parsed; a missing file, a directory, an oversize file or invalid JSON fail
// with `at` (which names the file).
Json parseFile(const std::string& path, const ErrorContext& at);
Json parseText(std::string_view text, const ErrorContext& at);

// At most 40 characters of the value as JSON, for messages.
std::string describe(const Json& value);

const Json* find(const Json& object, const char* key);
// The field must be there (no fallback) or may be absent (fallback given).
double number(const Json& object, const char* key, const ErrorContext& at,
              std::optional<double> fallback = std::nullopt, double limit = kMaxCoordinate);
std::int64_t integer(const Json& object, const char* key, const ErrorContext& at, std::int64_t min,
                     std::int64_t max, std::optional<std::int64_t> fallback = std::nullopt);
std::string text(const Json& object, const char* key, const ErrorContext& at,
                 std::optional<std::string> fallback = std::nullopt);
bool boolean(const Json& object, const char* key, const ErrorContext& at,
             std::optional<bool> fallback = std::nullopt);
// An array field; absent gives nullptr when optional, fails when required.
const Json* array(const Json& object, const char* key, const ErrorContext& at,
                  bool required = true);
// The value itself must be a JSON object (an element of an array, the file's root).
void requireObject(const Json& value, const ErrorContext& at, const std::string& what);

}  // namespace game::json_fields
