// Colours: 8-bit RGBA, straight (not premultiplied) alpha, sRGB values as written to the PNG.
#pragma once

#include <cstdint>

namespace render {

struct Color {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  std::uint8_t a = 255;

  // 0xRRGGBBAA, the way colours are usually written down.
  static constexpr Color hex(std::uint32_t rgba) {
    return {static_cast<std::uint8_t>(rgba >> 24), static_cast<std::uint8_t>(rgba >> 16),
            static_cast<std::uint8_t>(rgba >> 8), static_cast<std::uint8_t>(rgba)};
  }
  constexpr Color withAlpha(std::uint8_t alpha) const { return {r, g, b, alpha}; }
  friend constexpr bool operator==(Color, Color) = default;
};

namespace colors {
inline constexpr Color kTransparent{0, 0, 0, 0};
inline constexpr Color kBlack{0, 0, 0, 255};
inline constexpr Color kWhite{255, 255, 255, 255};
inline constexpr Color kRed{230, 40, 40, 255};
inline constexpr Color kGreen{60, 200, 80, 255};
inline constexpr Color kBlue{50, 110, 230, 255};
inline constexpr Color kYellow{240, 210, 40, 255};
inline constexpr Color kOrange{245, 140, 30, 255};
inline constexpr Color kCyan{40, 200, 220, 255};
inline constexpr Color kMagenta{210, 60, 200, 255};
inline constexpr Color kGray{128, 128, 128, 255};
inline constexpr Color kDarkGray{40, 42, 48, 255};
}  // namespace colors

}  // namespace render
