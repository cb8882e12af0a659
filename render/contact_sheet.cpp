#include "render/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace render {

Image resizeArea(const Image& image, int width, int height) {
  if (width <= 0 || height <= 0 || image.width <= 0 || image.height <= 0) {
    throw std::invalid_argument("render: resizeArea: sizes must be positive");
  }
  Image out(width, height);
  const double sx = static_cast<double>(image.width) / width;
  const double sy = static_cast<double>(image.height) / height;
  for (int y = 0; y < height; ++y) {
    const double y0 = y * sy, y1 = (y + 1) * sy;
    for (int x = 0; x < width; ++x) {
      const double x0 = x * sx, x1 = (x + 1) * sx;
      double sum[4] = {0, 0, 0, 0};
      double area = 0;
      // Each source pixel weighs by how much of it the target pixel covers.
      for (int j = static_cast<int>(y0);
           j < std::min(image.height, static_cast<int>(std::ceil(y1))); ++j) {
        const double wy = std::min(y1, j + 1.0) - std::max(y0, static_cast<double>(j));
        for (int i = static_cast<int>(x0);
             i < std::min(image.width, static_cast<int>(std::ceil(x1))); ++i) {
          const double w = wy * (std::min(x1, i + 1.0) - std::max(x0, static_cast<double>(i)));
          const Color c = image.pixel(i, j);
          sum[0] += w * c.r;
          sum[1] += w * c.g;
          sum[2] += w * c.b;
          sum[3] += w * c.a;
          area += w;
        }
      }
      auto channel = [&](int k) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(sum[k] / area, 0.0, 255.0)));
      };
      out.setPixel(x, y, {channel(0), channel(1), channel(2), channel(3)});
    }
  }
  return out;
}

Image contactSheet(std::span<const Image> frames, const ContactSheetOptions& options) {
  if (frames.empty()) throw std::invalid_argument("render: contactSheet: no frames");
  if (options.columns <= 0 || options.thumbWidth <= 0 || options.gap < 0) {
    throw std::invalid_argument(
        "render: contactSheet: columns and thumbnail width must be "
        "positive and the gap not negative");
  }
  const Image& first = frames.front();
  if (first.width <= 0 || first.height <= 0) {
    throw std::invalid_argument("render: contactSheet: the first frame is empty");
  }
  const int thumbW = options.thumbWidth;
  const int thumbH = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(thumbW) * first.height / first.width)));
  const int count = static_cast<int>(frames.size());
  const int columns = std::min(options.columns, count);
  const int rows = (count + columns - 1) / columns;
  const int gap = options.gap;
  Image sheet(gap + columns * (thumbW + gap), gap + rows * (thumbH + gap));
  for (int y = 0; y < sheet.height; ++y) {
    for (int x = 0; x < sheet.width; ++x)
      sheet.setPixel(x, y, options.background);
  }
  for (int k = 0; k < count; ++k) {
    const Image thumb = resizeArea(frames[k], thumbW, thumbH);
    const int ox = gap + (k % columns) * (thumbW + gap);
    const int oy = gap + (k / columns) * (thumbH + gap);
    for (int y = 0; y < thumbH; ++y) {
      std::copy_n(
          thumb.rgba.begin() + static_cast<std::ptrdiff_t>(y * thumb.stride()), thumb.stride(),
          sheet.rgba.begin() + static_cast<std::ptrdiff_t>((oy + y) * sheet.stride() + ox * 4));
    }
  }
  return sheet;
}

}  // namespace render
