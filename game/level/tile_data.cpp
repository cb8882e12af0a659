#include "game/level/tile_data.h"

#include <zlib.h>

#include <string>

namespace game {

namespace {

int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

std::vector<std::uint8_t> decodeBase64(std::string_view text, const ErrorContext& at) {
  std::vector<std::uint8_t> out;
  out.reserve(text.size() / 4 * 3);
  std::uint32_t bits = 0;
  int held = 0;  // 6-bit groups in `bits`
  std::size_t padding = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    if (c == '=') {
      ++padding;
      continue;
    }
    const int v = base64Value(c);
    if (v < 0 || padding > 0)
      at.fail("base64 data: " + std::string(v < 0 ? "invalid character" : "data after padding") +
              " at offset " + std::to_string(i));
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    if (++held == 4) {
      out.push_back(static_cast<std::uint8_t>(bits >> 16));
      out.push_back(static_cast<std::uint8_t>(bits >> 8));
      out.push_back(static_cast<std::uint8_t>(bits));
      bits = 0;
      held = 0;
    }
  }
  // A final group of 2 or 3 characters carries 1 or 2 bytes; 1 character carries none.
  if (held == 1 || padding > 2 || (padding > 0 && held + padding != 4))
    at.fail("base64 data: truncated (its length is not a whole number of bytes)");
  if (held == 2) out.push_back(static_cast<std::uint8_t>(bits >> 4));
  if (held == 3) {
    out.push_back(static_cast<std::uint8_t>(bits >> 10));
    out.push_back(static_cast<std::uint8_t>(bits >> 2));
  }
  return out;
}

std::vector<std::uint8_t> inflateExactly(std::span<const std::uint8_t> compressed,
                                         TileCompression compression, std::size_t size,
                                         const ErrorContext& at) {
  const char* name = compression == TileCompression::gzip ? "gzip" : "zlib";
  if (compression == TileCompression::none) return {compressed.begin(), compressed.end()};
  // Both lengths fit zlib's 32-bit counters: the file is at most 32 MiB and a layer at most
  // 2^22 tiles (16 MiB of gids).
  std::vector<std::uint8_t> out(size + 1);  // one byte more shows data beyond the expected size
  z_stream zs{};
  const int windowBits = compression == TileCompression::gzip ? 15 + 16 : 15;
  if (inflateInit2(&zs, windowBits) != Z_OK) at.fail(std::string(name) + " data: out of memory");
  zs.next_in = const_cast<Bytef*>(compressed.data());  // zlib's API is not const-correct
  zs.avail_in = static_cast<uInt>(compressed.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = inflate(&zs, Z_FINISH);
  const std::size_t produced = zs.total_out;
  const std::string message = zs.msg != nullptr ? zs.msg : "";
  inflateEnd(&zs);
  if (produced > size)
    at.fail(std::string(name) + " data decompresses to more than the layer's " +
            std::to_string(size) + " bytes");
  if (rc != Z_STREAM_END)
    at.fail(std::string(name) + " data is " +
            (rc == Z_DATA_ERROR ? "corrupt" + (message.empty() ? "" : " (" + message + ")")
                                : std::string("truncated")));
  if (produced != size)
    at.fail(std::string(name) + " data decompresses to " + std::to_string(produced) +
            " bytes, the layer needs " + std::to_string(size));
  out.resize(size);
  return out;
}

std::vector<std::uint32_t> gidsFromBytes(std::span<const std::uint8_t> bytes, std::size_t count,
                                         const ErrorContext& at) {
  if (bytes.size() != 4 * count)
    at.fail("tile data holds " + std::to_string(bytes.size()) + " bytes, the layer needs " +
            std::to_string(4 * count) + " (4 per tile, " + std::to_string(count) + " tiles)");
  std::vector<std::uint32_t> gids(count);
  for (std::size_t i = 0; i < count; ++i)
    gids[i] = static_cast<std::uint32_t>(bytes[4 * i]) |
              static_cast<std::uint32_t>(bytes[4 * i + 1]) << 8 |
              static_cast<std::uint32_t>(bytes[4 * i + 2]) << 16 |
              static_cast<std::uint32_t>(bytes[4 * i + 3]) << 24;
  return gids;
}

}  // namespace game
