// The renderer end to end: pixel probes at known world positions, orientation, anti-aliased
// edges, draw order, each primitive kind, text placement, and byte-identical repeats.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render/context.h"
#include "render/renderer.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace render_test {

using render::Camera;
using render::Color;
using render::Frame;
using render::Image;
using render::Style;
namespace colors = render::colors;

constexpr Color kBackground = colors::kBlack;
constexpr int kTolerance = 2;  // 8-bit rounding of blended colours

// 160x90 pixels, world origin in the middle, 10 pixels per unit: world (x, y) is pixel
// (80 + 10x, 45 - 10y).
Camera smallCamera() {
  return Camera{160, 90, {0.0f, 0.0f}, 10.0f};
}

Frame blankFrame() {
  Frame frame;
  frame.background = kBackground;
  return frame;
}

// Pixels of the whole image whose colour differs from the background by more than `threshold`.
int countInk(const Image& image, int x0, int y0, int x1, int y1, int threshold = 40) {
  int n = 0;
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
      if (render_test::channelDistance(image.pixel(x, y), kBackground) > threshold) ++n;
    }
  }
  return n;
}

TEST(Renderer, ContextIsGl45CoreOnLlvmpipe) {
  const render::GlContext& context = render_test::sharedRenderer().context();
  EXPECT_EQ(context.version().rfind("4.5 (Core Profile)", 0), 0u) << context.version();
  std::printf("GL_VERSION %s, GL_RENDERER %s\n", context.version().c_str(),
              context.rendererName().c_str());
}

TEST(Renderer, RedDiscColoursTheExpectedPixelAndNotAFarOne) {
  Frame frame = blankFrame();
  frame.world.circle({3.0f, 2.0f}, 1.0f, Style::filled(colors::kRed));
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  ASSERT_EQ(image.width, 160);
  ASSERT_EQ(image.height, 90);
  // World (3, 2) is pixel (110, 25); the disc reaches 10 pixels around it.
  EXPECT_PIXEL(image, 110, 25, colors::kRed, kTolerance);
  EXPECT_PIXEL(image, 116, 25, colors::kRed, kTolerance);
  EXPECT_PIXEL(image, 110, 19, colors::kRed, kTolerance);
  EXPECT_PIXEL(image, 122, 25, kBackground, 0);
  EXPECT_PIXEL(image, 110, 37, kBackground, 0);
  EXPECT_PIXEL(image, 20, 70, kBackground, 0);
  // Its mirror image below the x axis is empty: y is not flipped.
  EXPECT_PIXEL(image, 110, 64, kBackground, 0);
  // About pi r^2 = 314 pixels of ink, counting partly covered edge pixels as half.
  EXPECT_NEAR(countInk(image, 0, 0, 160, 90, 115), 314, 12);
}

TEST(Renderer, TopOfTheWorldIsTheTopOfTheImage) {
  Frame frame = blankFrame();
  frame.world.rect({{-100.0f, 0.0f}, {100.0f, 100.0f}}, Style::filled(colors::kGreen));
  frame.world.rect({{-100.0f, -100.0f}, {100.0f, 0.0f}}, Style::filled(colors::kBlue));
  frame.world.circle({-7.0f, 3.5f}, 0.5f, Style::filled(colors::kRed));  // near the top-left
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_PIXEL(image, 80, 0, colors::kGreen, 0);
  EXPECT_PIXEL(image, 80, 44, colors::kGreen, 0);
  EXPECT_PIXEL(image, 80, 45, colors::kBlue, 0);
  EXPECT_PIXEL(image, 80, 89, colors::kBlue, 0);
  EXPECT_PIXEL(image, 10, 10, colors::kRed, kTolerance);  // world (-7, 3.5) is pixel (10, 10)
}

TEST(Renderer, EdgesAreAntiAliased) {
  // Radius 30.5 pixels about the pixel corner (80, 45): the edge crosses the middle of pixel
  // column 110 on the rows next to the centre.
  Frame frame = blankFrame();
  frame.world.circle({0.0f, 0.0f}, 3.05f, Style::filled(colors::kWhite));
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  // Along the row through the centre, brightness falls from full to nothing through one
  // in-between value and never goes back up.
  int previous = 255;
  int partial = 0;
  for (int x = 80; x < 120; ++x) {
    int v = image.pixel(x, 44).r;
    EXPECT_LE(v, previous) << "at x = " << x;
    if (v > 10 && v < 245) ++partial;
    previous = v;
  }
  EXPECT_EQ(partial, 1);
  // Coverage is 0.5 minus the signed distance from the pixel's centre to the edge, in pixels:
  // pixel (110, 44) has its centre (30.5, 0.5) from the disc's, 0.004 px outside the edge.
  const float distance = std::hypot(30.5f, 0.5f) - 30.5f;
  EXPECT_NEAR(image.pixel(110, 44).r, 255.0f * (0.5f - distance), 1.5f);
  EXPECT_PIXEL(image, 109, 44, colors::kWhite, 0);
  EXPECT_PIXEL(image, 111, 44, kBackground, 0);
  // An edge on a pixel boundary leaves no partial pixel: a box filter of one pixel.
  frame.world.clear();
  frame.world.circle({0.0f, 0.0f}, 3.0f, Style::filled(colors::kWhite));
  image = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_GE(image.pixel(109, 44).r, 253);
  EXPECT_EQ(image.pixel(110, 44).r, 0);
}

TEST(Renderer, LaterShapesDrawOnTopAcrossKinds) {
  Frame frame = blankFrame();
  frame.world.circle({0.0f, 0.0f}, 2.0f, Style::filled(colors::kRed));
  const rc::Vec2 square[] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  frame.world.polygon(square, Style::filled(colors::kBlue));
  frame.world.capsule({-0.5f, 0.0f}, {0.5f, 0.0f}, 0.3f, Style::filled(colors::kGreen));
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_PIXEL(image, 80, 45, colors::kGreen, 0);
  EXPECT_PIXEL(image, 80, 38, colors::kBlue, 0);
  EXPECT_PIXEL(image, 80, 28, colors::kRed, 0);
}

TEST(Renderer, TranslucentColoursBlend) {
  Frame frame = blankFrame();
  frame.world.rect({{-8, -5}, {8, 5}}, Style::filled(colors::kWhite));
  frame.world.circle({0.0f, 0.0f}, 2.0f, Style::filled(Color{0, 0, 255, 128}));
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_PIXEL(image, 80, 45, (Color{127, 127, 255, 255}), kTolerance);
}

TEST(Renderer, OutlinesLieInsideTheEdge) {
  Frame frame = blankFrame();
  frame.world.circle({0.0f, 0.0f}, 3.0f, Style::outlined(colors::kYellow, 4.0f));
  frame.world.circle({-5.0f, 0.0f}, 1.5f, Style::both(colors::kBlue, colors::kWhite, 2.0f));
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_PIXEL(image, 80, 45, kBackground, 0);           // hollow middle
  EXPECT_PIXEL(image, 80 + 28, 45, colors::kYellow, 0);  // inside the 4 px band
  EXPECT_PIXEL(image, 80 + 24, 45, kBackground, kTolerance);
  EXPECT_PIXEL(image, 80 + 31, 45, kBackground, 0);              // nothing outside the radius
  EXPECT_PIXEL(image, 30, 45, colors::kBlue, 0);                 // the second circle's fill...
  EXPECT_PIXEL(image, 30 + 14, 45, colors::kWhite, kTolerance);  // ...and its rim
}

TEST(Renderer, PolygonsArrowsAndLinesCoverTheirPixels) {
  Frame frame = blankFrame();
  // A triangle with its right angle at world (-6, -3).
  const rc::Vec2 triangle[] = {{-6, -3}, {-2, -3}, {-6, 1}};
  frame.world.polygon(triangle, Style::filled(colors::kCyan));
  // A horizontal 3-pixel line from x = 0 to 6 at y = 3; an arrow up at x = 4.
  frame.world.segment({0.0f, 3.0f}, {6.0f, 3.0f}, 3.0f, colors::kWhite);
  frame.world.arrow({4.0f, -4.0f}, {4.0f, 0.0f}, 2.0f, colors::kOrange, 12.0f);
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_PIXEL(image, 22, 70, colors::kCyan, 0);  // inside, near the right angle
  EXPECT_PIXEL(image, 55, 50, kBackground, 0);    // beyond the hypotenuse
  // The line's middle is the boundary between pixel rows 14 and 15 (y = 3): rows 14 and 15
  // are covered, 13 and 16 half covered.
  EXPECT_PIXEL(image, 100, 14, colors::kWhite, 0);
  EXPECT_PIXEL(image, 100, 15, colors::kWhite, 0);
  EXPECT_PIXEL(image, 100, 16, (Color{127, 127, 127, 255}), kTolerance);
  EXPECT_PIXEL(image, 100, 13, (Color{127, 127, 127, 255}), kTolerance);
  EXPECT_PIXEL(image, 100, 17, kBackground, 0);
  EXPECT_PIXEL(image, 100, 12, kBackground, 0);
  // Arrow: thin shaft, head 12 px long ending at pixel row 45, 12 px wide at its base.
  EXPECT_PIXEL(image, 119, 70, colors::kOrange, 0);  // shaft
  EXPECT_PIXEL(image, 116, 70, kBackground, 0);      // beside the shaft
  EXPECT_PIXEL(image, 116, 56, colors::kOrange, 0);  // beside the shaft, in the head
  EXPECT_PIXEL(image, 119, 47, colors::kOrange, kTolerance);
  EXPECT_PIXEL(image, 119, 43, kBackground, 0);  // past the tip
}

TEST(Renderer, DotsKeepTheirPixelSizeAtAnyZoom) {
  for (float zoom : {1.0f, 10.0f, 100.0f}) {
    Frame frame = blankFrame();
    frame.world.dot({0.0f, 0.0f}, 3.0f, colors::kRed);
    Image image = render_test::sharedRenderer().render(frame, Camera{160, 90, {0, 0}, zoom});
    EXPECT_NEAR(countInk(image, 0, 0, 160, 90, 115), 28, 4) << "zoom " << zoom;  // pi 3^2
  }
}

TEST(Renderer, OverlayCanBeSwitchedOff) {
  Frame frame = blankFrame();
  frame.overlay.rect({{-1, -1}, {1, 1}}, Style::outlined(colors::kGreen, 2.0f));
  frame.showOverlay = true;
  Image on = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_PIXEL(on, 71, 45, colors::kGreen, 0);
  frame.showOverlay = false;
  Image off = render_test::sharedRenderer().render(frame, smallCamera());
  EXPECT_EQ(countInk(off, 0, 0, 160, 90, 0), 0);
}

TEST(Renderer, HudTextAppearsWherePlaced) {
  render::Renderer& renderer = render_test::sharedRenderer();
  Frame frame = blankFrame();
  frame.hud.text({20.0f, 30.0f}, "HELLO", 20.0f, colors::kWhite);
  Image image = renderer.render(frame, smallCamera());
  const render::Font::Extent extent = renderer.font().measure("HELLO", 20.0f);
  const int right = 20 + static_cast<int>(std::ceil(extent.width));
  // Capitals fill most of the box from the top of the line to the baseline.
  const int baseline = 30 + static_cast<int>(std::lround(renderer.font().ascent(20.0f)));
  EXPECT_GT(countInk(image, 20, 30, right, baseline), 120);
  // ...and nothing lies outside the text's box.
  const int total = countInk(image, 0, 0, 160, 90, 0);
  EXPECT_EQ(countInk(image, 19, 29, right + 2, 30 + 21, 0), total);
  EXPECT_GT(extent.width, 50.0f);
  EXPECT_LT(extent.width, 80.0f);
}

TEST(Renderer, WorldTextFollowsItsAnchorAndAlignment) {
  Frame frame = blankFrame();
  // Centred on world (-4, 2), which is pixel (40, 25).
  frame.world.text({-4.0f, 2.0f}, "Ab", 16.0f, colors::kYellow, render::HAlign::kCenter,
                   render::VAlign::kMiddle);
  Image image = render_test::sharedRenderer().render(frame, smallCamera());
  const int left = countInk(image, 20, 10, 40, 40, 0);
  const int rightSide = countInk(image, 40, 10, 60, 40, 0);
  EXPECT_GT(left, 20);
  EXPECT_GT(rightSide, 20);
  EXPECT_EQ(left + rightSide, countInk(image, 0, 0, 160, 90, 0));
  const int above = countInk(image, 0, 0, 160, 25, 0);
  const int below = countInk(image, 0, 25, 160, 90, 0);
  EXPECT_GT(above, 20);
  EXPECT_GT(below, 10);
}

Frame busyFrame() {
  Frame frame = blankFrame();
  for (int i = 0; i < 60; ++i) {
    float x = -7.5f + 0.25f * static_cast<float>(i);
    float y = 3.0f * std::sin(0.37f * static_cast<float>(i));
    Color c{std::uint8_t(40 + i * 3), std::uint8_t(200 - i * 2), std::uint8_t(90 + i), 200};
    switch (i % 4) {
      case 0:
        frame.world.circle({x, y}, 0.4f, Style::both(c, colors::kWhite, 1.0f));
        break;
      case 1:
        frame.world.capsule({x, y}, {x + 0.5f, y + 0.3f}, 0.2f, Style::filled(c));
        break;
      case 2: {
        const rc::Vec2 tri[] = {{x, y}, {x + 0.6f, y}, {x + 0.3f, y + 0.5f}};
        frame.world.polygon(tri, Style::filled(c), 0.05f);
        break;
      }
      default:
        frame.world.arrow({x, y}, {x + 0.3f, y + 1.0f}, 1.5f, c, 6.0f);
        break;
    }
  }
  frame.overlay.rect({{-2, -2}, {2, 2}}, Style::outlined(colors::kGreen, 1.0f));
  frame.hud.text({4.0f, 4.0f}, "tick 123\nbodies 60", 12.0f, colors::kWhite);
  frame.hud.rect({{100, 80}, {150, 86}}, Style::both(colors::kRed, colors::kWhite, 1.0f));
  return frame;
}

TEST(Renderer, SameDrawListGivesIdenticalBytes) {
  const Frame frame = busyFrame();
  render::Renderer& renderer = render_test::sharedRenderer();
  Image first = renderer.render(frame, smallCamera());
  // Something else in between must not leave state behind.
  Frame other = blankFrame();
  other.world.circle({1, 1}, 5, Style::filled(colors::kRed));
  renderer.render(other, Camera{64, 64, {0, 0}, 3.0f});
  Image second;
  renderer.render(frame, smallCamera(), second);
  EXPECT_TRUE(first == second);
  EXPECT_GT(countInk(first, 0, 0, 160, 90, 0), 1000);
  EXPECT_GE(renderer.lastTiming().drawCalls, 4);  // shapes + text of the world and HUD
  EXPECT_LE(renderer.lastTiming().drawCalls, 6);  // never one per shape
}

TEST(Renderer, RejectsBadCameras) {
  render::Renderer& renderer = render_test::sharedRenderer();
  Frame frame = blankFrame();
  EXPECT_THROW(renderer.render(frame, Camera{0, 90, {0, 0}, 1.0f}), std::invalid_argument);
  EXPECT_THROW(renderer.render(frame, Camera{160, 90, {0, 0}, 0.0f}), std::invalid_argument);
  EXPECT_THROW(renderer.render(frame, Camera{160, 90, {NAN, 0}, 1.0f}), std::invalid_argument);
}

TEST(Renderer, MissingFontIsNamed) {
  try {
    render::Font font("/nonexistent/font.ttf");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "render: cannot read font '/nonexistent/font.ttf': No such file or directory");
  }
}

}  // namespace render_test
