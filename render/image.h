// An RGBA8 image in memory, rows top to bottom, 4 bytes per pixel, no padding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/color.h"

namespace render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes; row 0 is the top of the picture

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4) {}

  std::size_t stride() const { return static_cast<std::size_t>(width) * 4; }
  // Pixel (x, y) with y = 0 the top row; no bounds check beyond the vector's.
  Color pixel(int x, int y) const {
    const std::uint8_t* p = rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
    return {p[0], p[1], p[2], p[3]};
  }
  void setPixel(int x, int y, Color c) {
    std::uint8_t* p = rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
    p[3] = c.a;
  }
  friend bool operator==(const Image&, const Image&) = default;
};

}  // namespace render
