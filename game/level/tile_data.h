// The pieces of a tile layer's "data" field: base64 text, zlib or gzip compression, and the
// little-endian 32-bit gids inside. Each checks its input completely (a stray character, a
// truncated or oversized stream) and fails with a LevelError through `at`; decompression never
// produces more than the layer's expected size, so a small hostile file cannot expand to
// gigabytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "game/level/level_error.h"

namespace game {

enum class TileCompression : std::uint8_t { none, zlib, gzip };

// Standard base64 (RFC 4648, '+' and '/'), padding optional, whitespace skipped.
std::vector<std::uint8_t> decodeBase64(std::string_view text, const ErrorContext& at);

// Inflates a zlib or gzip stream that must hold exactly `size` bytes.
std::vector<std::uint8_t> inflateExactly(std::span<const std::uint8_t> compressed,
                                         TileCompression compression, std::size_t size,
                                         const ErrorContext& at);

// `count` gids from their little-endian bytes, which must be exactly 4 * count.
std::vector<std::uint32_t> gidsFromBytes(std::span<const std::uint8_t> bytes, std::size_t count,
                                         const ErrorContext& at);

}  // namespace game
