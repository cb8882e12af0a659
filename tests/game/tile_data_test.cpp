// The pieces of a tile layer's data: base64 against RFC 4648's test vectors, zlib and gzip
// streams inflated to exactly the expected size, gids read little-endian with their flags.
#include "game/level/tile_data.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include "game/level/tiled_map.h"
#include "level_test_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace tile_data_test {

const game::ErrorContext kAt("data.tmj");

std::string text(const std::vector<std::uint8_t>& bytes) {
  return {bytes.begin(), bytes.end()};
}

TEST(TileData, Base64Vectors) {
  // RFC 4648, section 10.
  EXPECT_EQ(text(game::decodeBase64("", kAt)), "");
  EXPECT_EQ(text(game::decodeBase64("Zg==", kAt)), "f");
  EXPECT_EQ(text(game::decodeBase64("Zm8=", kAt)), "fo");
  EXPECT_EQ(text(game::decodeBase64("Zm9v", kAt)), "foo");
  EXPECT_EQ(text(game::decodeBase64("Zm9vYg==", kAt)), "foob");
  EXPECT_EQ(text(game::decodeBase64("Zm9vYmE=", kAt)), "fooba");
  EXPECT_EQ(text(game::decodeBase64("Zm9vYmFy", kAt)), "foobar");
  EXPECT_EQ(text(game::decodeBase64(" Zm9v\nYmFy ", kAt)), "foobar");  // whitespace skipped
  EXPECT_EQ(text(game::decodeBase64("Zm8", kAt)), "fo");               // padding optional
  const auto error = [](const char* s) {
    return level_test::levelErrorOf([&] { game::decodeBase64(s, kAt); });
  };
  EXPECT_EQ(error("Zm9vY"),
            "data.tmj: base64 data: truncated (its length is not a whole number of bytes)");
  EXPECT_EQ(error("Zm=v"), "data.tmj: base64 data: data after padding at offset 3");
  EXPECT_EQ(error("Zm9v-"), "data.tmj: base64 data: invalid character at offset 4");
  EXPECT_EQ(error("Zg==="),
            "data.tmj: base64 data: truncated (its length is not a whole number of bytes)");
}

std::vector<std::uint8_t> deflated(const std::string& s, bool gzip) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::vector<std::uint8_t> out(s.size() + 64);
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(s.data()));
  zs.avail_in = static_cast<uInt>(s.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

TEST(TileData, ZlibAndGzipInflateToExactlyTheLayer) {
  const std::string gids(48, 'x');
  for (const bool gzip : {false, true}) {
    const auto how = gzip ? game::TileCompression::gzip : game::TileCompression::zlib;
    EXPECT_EQ(text(game::inflateExactly(deflated(gids, gzip), how, 48, kAt)), gids);
    // A zlib stream is not a gzip one and back.
    EXPECT_NE(level_test::levelErrorOf([&] {
                game::inflateExactly(deflated(gids, !gzip), how, 48, kAt);
              }).find("data is corrupt"),
              std::string::npos);
    EXPECT_NE(level_test::levelErrorOf([&] {
                game::inflateExactly(deflated(gids, gzip), how, 40, kAt);
              }).find("decompresses to more than the layer's 40 bytes"),
              std::string::npos);
  }
}

TEST(TileData, GidsAreLittleEndianWithTheirFlags) {
  const std::vector<std::uint8_t> bytes = {1, 0, 0, 0, 0x05, 0x01, 0, 0x80, 0xFF, 0xFF, 0xFF, 0xFF};
  const auto gids = game::gidsFromBytes(bytes, 3, kAt);
  ASSERT_EQ(gids.size(), 3u);
  EXPECT_EQ(gids[0], 1u);
  EXPECT_EQ(gids[1], 0x80000105u);
  EXPECT_EQ(gids[1] & ~game::kGidFlags, 0x105u);
  EXPECT_EQ(gids[1] & game::kFlipHorizontal, game::kFlipHorizontal);
  EXPECT_EQ(gids[2] & ~game::kGidFlags, 0x0FFFFFFFu);
}

}  // namespace tile_data_test
