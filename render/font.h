// A TrueType font baked once into a signed-distance atlas with stb_truetype, and text layout.
//
// Glyphs are baked at one size as distance fields (not coverage), so the shader draws any text
// size with an anti-aliased edge from the same atlas: a texel holds 128 on the outline and
// changes by kDistanceScale per atlas pixel (larger inside). The atlas covers printable ASCII
// and Latin-1; other code points show as '?'. CPU only: no GL here, the Renderer uploads the
// atlas.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "render/draw_list.h"

namespace render {

// The font shipped with the project, assets/fonts/DejaVuSans.ttf (its licence beside it), as the
// absolute path of the source tree the library was built from (a compile definition), so a
// binary finds it from any working directory without a system font package.
const char* shippedFontPath();

// The font a Renderer uses when RendererOptions::fontPath is empty: the environment variable
// RICOCHET_FONT when it is set and not empty, else shippedFontPath().
std::string defaultFontPath();

class Font {
 public:
  static constexpr int kPadding = 6;  // atlas pixels of distance field around each glyph
  static constexpr int kOnEdge = 128;
  static constexpr float kDistanceScale = 128.0f / kPadding;  // texel value per atlas pixel

  // Reads and bakes the font; throws std::runtime_error naming the path when the file cannot be
  // read or is not a TrueType font. `bakePixels` is the line height glyphs are baked at.
  explicit Font(const std::string& path, float bakePixels = 40.0f);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  // A glyph placed by layout(): pixel offsets from the text's anchor (y down) and atlas
  // coordinates in [0, 1].
  struct Quad {
    float x0, y0, x1, y1;
    float u0, v0, u1, v1;
  };
  struct Extent {
    float width = 0;   // widest line, pixels
    float height = 0;  // first ascender to last descender, pixels
  };
  // Appends one quad per visible glyph of `text` at `sizePixels`, aligned on the anchor (0, 0).
  void layout(std::string_view text, float sizePixels, HAlign halign, VAlign valign,
              std::vector<Quad>& out) const;
  Extent measure(std::string_view text, float sizePixels) const;
  // Distance from the top of a line to its baseline, at `sizePixels`.
  float ascent(float sizePixels) const;

  float bakePixels() const { return bakePixels_; }
  int atlasWidth() const { return atlasWidth_; }
  int atlasHeight() const { return atlasHeight_; }
  const std::vector<std::uint8_t>& atlas() const { return atlas_; }  // one byte per texel
  const std::string& path() const { return path_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  float bakePixels_;
  int atlasWidth_ = 0;
  int atlasHeight_ = 0;
  std::vector<std::uint8_t> atlas_;
};

}  // namespace render
