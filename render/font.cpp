#include "render/font.h"

#include <stb_truetype.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace render {

namespace {

constexpr int kAtlasWidth = 1024;
constexpr std::uint32_t kReplacement = '?';

bool baked(std::uint32_t cp) {
  return (cp >= 32 && cp <= 126) || (cp >= 160 && cp <= 255);
}

// Decodes one UTF-8 sequence at text[i], advancing i; malformed input gives U+FFFD.
std::uint32_t nextCodePoint(std::string_view text, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return static_cast<std::uint8_t>(text[k]); };
  std::uint8_t b0 = byte(i++);
  if (b0 < 0x80) return b0;
  int extra = b0 >= 0xF0 ? 3 : b0 >= 0xE0 ? 2 : b0 >= 0xC0 ? 1 : -1;
  if (extra < 0) return 0xFFFD;
  std::uint32_t cp = b0 & (0x3Fu >> extra);
  for (int k = 0; k < extra; ++k) {
    if (i >= text.size() || (byte(i) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (byte(i++) & 0x3Fu);
  }
  return cp;
}

std::vector<unsigned char> readFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    throw std::runtime_error("render: cannot read font '" + path + "': " + std::strerror(errno));
  }
  std::vector<unsigned char> data;
  unsigned char buffer[65536];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0)
    data.insert(data.end(), buffer, buffer + n);
  bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw std::runtime_error("render: cannot read font '" + path + "': read error");
  return data;
}

}  // namespace

const char* shippedFontPath() {
  return RICOCHET_SHIPPED_FONT;
}

std::string defaultFontPath() {
  const char* fromEnvironment = std::getenv("RICOCHET_FONT");
  if (fromEnvironment != nullptr && fromEnvironment[0] != '\0') return fromEnvironment;
  return shippedFontPath();
}

struct Font::Impl {
  struct Glyph {
    bool present = false;
    bool hasBitmap = false;
    int advance = 0;                 // font units
    int x = 0, y = 0, w = 0, h = 0;  // atlas rectangle
    float xoff = 0, yoff = 0;        // bitmap's top-left from the pen on the baseline, bake px
  };
  std::vector<unsigned char> ttf;
  stbtt_fontinfo info{};
  int ascent = 0, descent = 0, lineGap = 0;  // font units
  std::array<Glyph, 256> glyphs{};

  float scaleFor(float sizePixels) const {
    return sizePixels / static_cast<float>(ascent - descent);
  }
  const Glyph& glyph(std::uint32_t cp) const {
    if (cp < glyphs.size() && glyphs[cp].present) return glyphs[cp];
    return glyphs[kReplacement];
  }
  std::uint32_t shown(std::uint32_t cp) const {
    return cp < glyphs.size() && glyphs[cp].present ? cp : kReplacement;
  }
};

Font::Font(const std::string& path, float bakePixels)
    : impl_(std::make_unique<Impl>()), path_(path), bakePixels_(bakePixels) {
  Impl& im = *impl_;
  im.ttf = readFile(path);
  int offset = stbtt_GetFontOffsetForIndex(im.ttf.data(), 0);
  if (offset < 0 || !stbtt_InitFont(&im.info, im.ttf.data(), offset)) {
    throw std::runtime_error("render: '" + path + "' is not a TrueType font");
  }
  stbtt_GetFontVMetrics(&im.info, &im.ascent, &im.descent, &im.lineGap);
  if (im.ascent - im.descent <= 0) {
    throw std::runtime_error("render: font '" + path + "' has no vertical extent");
  }
  const float scale = im.scaleFor(bakePixels);

  // Bake every glyph's distance field, then pack them on shelves of a fixed-width atlas.
  struct Bitmap {
    std::uint32_t cp;
    unsigned char* pixels;
    int w, h;
  };
  std::vector<Bitmap> bitmaps;
  for (std::uint32_t cp = 0; cp < 256; ++cp) {
    if (!baked(cp)) continue;
    int index = stbtt_FindGlyphIndex(&im.info, static_cast<int>(cp));
    if (index == 0 && cp != ' ') continue;  // not in this font
    Impl::Glyph& g = im.glyphs[cp];
    g.present = true;
    int lsb = 0;
    stbtt_GetGlyphHMetrics(&im.info, index, &g.advance, &lsb);
    int w = 0, h = 0, xoff = 0, yoff = 0;
    unsigned char* sdf =
        stbtt_GetGlyphSDF(&im.info, scale, index, kPadding, static_cast<unsigned char>(kOnEdge),
                          kDistanceScale, &w, &h, &xoff, &yoff);
    if (sdf == nullptr) continue;  // blank glyph (space)
    g.hasBitmap = true;
    g.w = w;
    g.h = h;
    g.xoff = static_cast<float>(xoff);
    g.yoff = static_cast<float>(yoff);
    bitmaps.push_back({cp, sdf, w, h});
  }
  if (!im.glyphs[kReplacement].present) {
    throw std::runtime_error("render: font '" + path + "' has no '?' glyph");
  }
  // Tallest first packs shelves tightly; ties by code point keep the atlas deterministic.
  std::vector<Bitmap> order = bitmaps;
  std::sort(order.begin(), order.end(),
            [](const Bitmap& a, const Bitmap& b) { return a.h != b.h ? a.h > b.h : a.cp < b.cp; });
  int x = 1, y = 1, shelf = 0;
  for (const Bitmap& b : order) {
    if (x + b.w + 1 > kAtlasWidth) {
      x = 1;
      y += shelf + 1;
      shelf = 0;
    }
    Impl::Glyph& g = im.glyphs[b.cp];
    g.x = x;
    g.y = y;
    x += b.w + 1;
    shelf = std::max(shelf, b.h);
  }
  int height = 1;
  while (height < y + shelf + 1)
    height *= 2;
  atlasWidth_ = kAtlasWidth;
  atlasHeight_ = height;
  atlas_.assign(static_cast<std::size_t>(atlasWidth_) * atlasHeight_, 0);
  for (const Bitmap& b : bitmaps) {
    const Impl::Glyph& g = im.glyphs[b.cp];
    for (int row = 0; row < b.h; ++row) {
      std::memcpy(&atlas_[static_cast<std::size_t>(g.y + row) * atlasWidth_ + g.x],
                  b.pixels + static_cast<std::size_t>(row) * b.w, static_cast<std::size_t>(b.w));
    }
    stbtt_FreeSDF(b.pixels, nullptr);
  }
}

Font::~Font() = default;

float Font::ascent(float sizePixels) const {
  return static_cast<float>(impl_->ascent) * impl_->scaleFor(sizePixels);
}

Font::Extent Font::measure(std::string_view text, float sizePixels) const {
  const Impl& im = *impl_;
  const float scale = im.scaleFor(sizePixels);
  Extent extent;
  float line = 0.0f;
  int lines = 1;
  std::uint32_t previous = 0;
  for (std::size_t i = 0; i < text.size();) {
    std::uint32_t cp = nextCodePoint(text, i);
    if (cp == '\n') {
      extent.width = std::max(extent.width, line);
      line = 0.0f;
      previous = 0;
      ++lines;
      continue;
    }
    cp = im.shown(cp);
    if (previous != 0) {
      line += scale * static_cast<float>(stbtt_GetCodepointKernAdvance(
                          &im.info, static_cast<int>(previous), static_cast<int>(cp)));
    }
    line += scale * static_cast<float>(im.glyph(cp).advance);
    previous = cp;
  }
  extent.width = std::max(extent.width, line);
  const float lineHeight = scale * static_cast<float>(im.ascent - im.descent + im.lineGap);
  extent.height = sizePixels + static_cast<float>(lines - 1) * lineHeight;
  return extent;
}

void Font::layout(std::string_view text, float sizePixels, HAlign halign, VAlign valign,
                  std::vector<Quad>& out) const {
  const Impl& im = *impl_;
  const float scale = im.scaleFor(sizePixels);
  const float k = sizePixels / bakePixels_;  // screen pixels per atlas pixel
  const float lineHeight = scale * static_cast<float>(im.ascent - im.descent + im.lineGap);
  const float blockHeight = measure(text, sizePixels).height;
  float baseline = 0.0f;
  switch (valign) {
    case VAlign::kTop:
      baseline = ascent(sizePixels);
      break;
    case VAlign::kMiddle:
      baseline = ascent(sizePixels) - 0.5f * blockHeight;
      break;
    case VAlign::kBaseline:
      baseline = 0.0f;
      break;
    case VAlign::kBottom:
      baseline = ascent(sizePixels) - blockHeight;
      break;
  }
  const float invW = 1.0f / static_cast<float>(atlasWidth_);
  const float invH = 1.0f / static_cast<float>(atlasHeight_);
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    float pen = 0.0f;
    if (halign != HAlign::kLeft) {
      float width = measure(line, sizePixels).width;
      pen = halign == HAlign::kCenter ? -0.5f * width : -width;
    }
    std::uint32_t previous = 0;
    for (std::size_t i = 0; i < line.size();) {
      std::uint32_t cp = im.shown(nextCodePoint(line, i));
      if (previous != 0) {
        pen += scale * static_cast<float>(stbtt_GetCodepointKernAdvance(
                           &im.info, static_cast<int>(previous), static_cast<int>(cp)));
      }
      const Impl::Glyph& g = im.glyph(cp);
      if (g.hasBitmap) {
        Quad q;
        q.x0 = pen + k * g.xoff;
        q.y0 = baseline + k * g.yoff;
        q.x1 = q.x0 + k * static_cast<float>(g.w);
        q.y1 = q.y0 + k * static_cast<float>(g.h);
        q.u0 = static_cast<float>(g.x) * invW;
        q.v0 = static_cast<float>(g.y) * invH;
        q.u1 = static_cast<float>(g.x + g.w) * invW;
        q.v1 = static_cast<float>(g.y + g.h) * invH;
        out.push_back(q);
      }
      pen += scale * static_cast<float>(g.advance);
      previous = cp;
    }
    baseline += lineHeight;
    start = end + 1;
  }
}

}  // namespace render
