// Sprites: images loaded from PNG files, drawn turned, scaled and tinted, in draw order with the
// shapes of their list; the errors for a missing or corrupt file; the shipped font.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "render/png.h"
#include "render/renderer.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace sprite_test {

using render::Color;
using render::Frame;
using render::Image;
using render::SpriteId;
namespace colors = render::colors;

constexpr Color kBackground{20, 20, 20, 255};
constexpr Color kRed{255, 0, 0, 255};
constexpr Color kGreen{0, 255, 0, 255};
constexpr Color kBlue{0, 0, 255, 255};
constexpr Color kWhite{255, 255, 255, 255};

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// The quadrant sprite written to a PNG and loaded through loadSprite (the file path is the one
// callers use), once per run.
SpriteId quadrants() {
  static const SpriteId id = [] {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("ricochet_sprite_quadrants_" + std::to_string(::getpid()) + ".png");
    render::writePng(path, render_test::quadrantSprite());
    SpriteId loaded = render_test::sharedRenderer().loadSprite(path);
    std::filesystem::remove(path);
    return loaded;
  }();
  return id;
}

// 100x100 pixels, 10 per world unit, the world's origin at pixel (50, 50).
const render::Camera kCamera{100, 100, {0.0f, 0.0f}, 10.0f};

Frame blankFrame() {
  Frame frame;
  frame.background = kBackground;
  return frame;
}

TEST(Sprite, DrawnAtItsWorldPositionWithTheTintedTexelColour) {
  Frame frame = blankFrame();
  // x 0..4, y -1..3 in the world: pixels x 50..90, y 20..60.
  frame.world.sprite(quadrants(), {2.0f, 1.0f}, {4.0f, 4.0f}, 0.0f, Color{200, 100, 50, 255});
  const Image image = render_test::sharedRenderer().render(frame, kCamera);
  EXPECT_PIXEL(image, 60, 30, (Color{200, 0, 0, 255}), 1);     // red texel x tint, top-left
  EXPECT_PIXEL(image, 80, 30, (Color{0, 100, 0, 255}), 1);     // green, top-right
  EXPECT_PIXEL(image, 60, 50, (Color{0, 0, 50, 255}), 1);      // blue, bottom-left
  EXPECT_PIXEL(image, 80, 50, (Color{200, 100, 50, 255}), 1);  // white: the tint itself
  EXPECT_PIXEL(image, 51, 21, (Color{200, 0, 0, 255}), 1);     // just inside the corner
  EXPECT_PIXEL(image, 48, 30, kBackground, 0);                 // just outside the left edge
  EXPECT_PIXEL(image, 60, 62, kBackground, 0);                 // just below
  EXPECT_PIXEL(image, 30, 60, kBackground, 0);                 // the mirror image
}

TEST(Sprite, TintAlphaBlendsOverWhatIsBelow) {
  Frame frame = blankFrame();
  frame.world.sprite(quadrants(), {0.0f, 0.0f}, {4.0f, 4.0f}, 0.0f, Color{255, 255, 255, 128});
  const Image image = render_test::sharedRenderer().render(frame, kCamera);
  // White texel at half alpha over the background: 255 * 128/255 + 20 * (1 - 128/255).
  EXPECT_PIXEL(image, 60, 60, (Color{138, 138, 138, 255}), 2);
  EXPECT_PIXEL(image, 40, 40, (Color{138, 10, 10, 255}), 2);  // red
}

TEST(Sprite, QuarterTurnMovesTheMarkedCornerCounterClockwise) {
  Frame upright = blankFrame();
  upright.world.sprite(quadrants(), {2.0f, 1.0f}, {4.0f, 4.0f}, 0.0f);
  Frame turned = blankFrame();
  turned.world.sprite(quadrants(), {2.0f, 1.0f}, {4.0f, 4.0f}, std::numbers::pi_v<float> / 2);
  const Image a = render_test::sharedRenderer().render(upright, kCamera);
  const Image b = render_test::sharedRenderer().render(turned, kCamera);
  EXPECT_PIXEL(a, 60, 30, kRed, 1);
  // A quarter turn counter-clockwise: top-left -> bottom-left -> bottom-right -> top-right.
  EXPECT_PIXEL(b, 60, 50, kRed, 1);
  EXPECT_PIXEL(b, 80, 50, kBlue, 1);
  EXPECT_PIXEL(b, 80, 30, kWhite, 1);
  EXPECT_PIXEL(b, 60, 30, kGreen, 1);
}

TEST(Sprite, HudSpritesFaceUpAndTurnCounterClockwiseToo) {
  // The HUD's y points down; the image's top still faces the top of the picture and a positive
  // angle still turns counter-clockwise on screen.
  Frame upright = blankFrame();
  upright.hud.sprite(quadrants(), {50.0f, 50.0f}, {40.0f, 40.0f});
  Frame turned = blankFrame();
  turned.hud.sprite(quadrants(), {50.0f, 50.0f}, {40.0f, 40.0f}, std::numbers::pi_v<float> / 2);
  const Image a = render_test::sharedRenderer().render(upright, kCamera);
  const Image b = render_test::sharedRenderer().render(turned, kCamera);
  EXPECT_PIXEL(a, 40, 40, kRed, 1);
  EXPECT_PIXEL(a, 60, 60, kWhite, 1);
  EXPECT_PIXEL(b, 40, 60, kRed, 1);
  EXPECT_PIXEL(b, 40, 40, kGreen, 1);
}

TEST(Sprite, SourceRectangleDrawsPartOfTheImage) {
  Frame frame = blankFrame();
  frame.world.sprite(quadrants(), {0.0f, 0.0f}, {4.0f, 4.0f}, 0.0f, colors::kWhite,
                     {16.0f, 0.0f, 16.0f, 16.0f});  // the green quadrant
  const Image image = render_test::sharedRenderer().render(frame, kCamera);
  // x -2..2, y -2..2 in the world: pixels 30..70 both ways.
  for (int y = 32; y <= 68; y += 4) {
    for (int x = 32; x <= 68; x += 4) {
      EXPECT_PIXEL(image, x, y, kGreen, 0);
    }
  }
  EXPECT_PIXEL(image, 28, 50, kBackground, 0);
}

TEST(Sprite, DrawnInOrderWithTheShapesOfItsListUnderItsText) {
  Frame frame = blankFrame();
  frame.world.circle({-2.0f, 0.0f}, 1.0f, render::Style::filled(colors::kBlue));  // under
  frame.world.sprite(quadrants(), {0.0f, 0.0f}, {6.0f, 6.0f});
  frame.world.circle({2.0f, 0.0f}, 1.0f, render::Style::filled(colors::kOrange));  // on top
  frame.world.text({1.0f, -2.0f}, "#", 20.0f, colors::kCyan, render::HAlign::kCenter,
                   render::VAlign::kMiddle);
  render::Renderer& renderer = render_test::sharedRenderer();
  const Image image = renderer.render(frame, kCamera);
  EXPECT_PIXEL(image, 30, 55, kBlue, 1);  // the sprite's blue quadrant hides the blue circle
  EXPECT_PIXEL(image, 70, 50, colors::kOrange, 1);  // the second circle covers the sprite
  EXPECT_EQ(renderer.lastTiming().drawCalls, 4);    // shapes, sprites, shapes, text
  // The text is on top of the sprite somewhere in its box.
  int cyan = 0;
  for (int y = 60; y < 80; ++y) {
    for (int x = 50; x < 70; ++x)
      cyan += render_test::channelDistance(image.pixel(x, y), colors::kCyan) <= 2;
  }
  EXPECT_GT(cyan, 5);

  // Sprites of one image added together are one draw call however many there are.
  Frame many = blankFrame();
  for (int i = 0; i < 50; ++i)
    many.world.sprite(quadrants(), {-4.0f + 0.16f * static_cast<float>(i), 0.0f}, {1.0f, 1.0f});
  many.world.circle({0.0f, 3.0f}, 0.5f, render::Style::filled(colors::kRed));
  renderer.render(many, kCamera);
  EXPECT_EQ(renderer.lastTiming().drawCalls, 2);
}

TEST(Sprite, ThePathIsReadOnce) {
  render_test::ScratchDir dir;
  const std::filesystem::path path = dir.path() / "crate.png";
  render::writePng(path, render_test::crateSprite());
  render::Renderer& renderer = render_test::sharedRenderer();
  const SpriteId first = renderer.loadSprite(path);
  const SpriteId again = renderer.loadSprite(dir.path() / "." / "crate.png");
  EXPECT_TRUE(first.valid());
  EXPECT_EQ(first, again);
  EXPECT_EQ(renderer.spriteSize(first).width, 32);
  EXPECT_EQ(renderer.spriteSize(first).height, 32);
  EXPECT_NE(renderer.addSprite(render_test::crateSprite()), first);
}

TEST(Sprite, MissingPngIsNamed) {
  render_test::ScratchDir dir;
  const std::filesystem::path path = dir.path() / "none.png";
  EXPECT_EQ(errorOf([&] { render_test::sharedRenderer().loadSprite(path); }),
            "render: cannot read PNG '" + path.string() + "': No such file or directory");
}

TEST(Sprite, CorruptPngIsNamed) {
  render_test::ScratchDir dir;
  const std::filesystem::path garbage = dir.path() / "garbage.png";
  std::ofstream(garbage) << "not a png at all";
  EXPECT_EQ(errorOf([&] {
              render_test::sharedRenderer().loadSprite(garbage);
            }).rfind("render: cannot read PNG '" + garbage.string() + "': not a valid PNG file", 0),
            0u);
  // A real PNG cut short: the header is fine, the pixels are missing.
  std::vector<std::uint8_t> bytes = render::encodePng(render_test::crateSprite());
  bytes.resize(bytes.size() / 2);
  const std::filesystem::path truncated = dir.path() / "truncated.png";
  render::writeFileAtomically(truncated, bytes);
  EXPECT_EQ(
      errorOf([&] {
        render_test::sharedRenderer().loadSprite(truncated);
      }).rfind("render: cannot read PNG '" + truncated.string() + "': not a valid PNG file", 0),
      0u);
}

TEST(Sprite, BadInputIsRejected) {
  render::DrawList list;
  EXPECT_THROW(list.sprite(SpriteId{}, {0.0f, 0.0f}, {1.0f, 1.0f}), std::invalid_argument);
  EXPECT_THROW(list.sprite(quadrants(), {0.0f, 0.0f}, {0.0f, 1.0f}), std::invalid_argument);
  EXPECT_THROW(list.sprite(quadrants(), {0.0f, 0.0f}, {1.0f, 1.0f}, std::nanf("")),
               std::invalid_argument);
  EXPECT_THROW(list.sprite(quadrants(), {0.0f, 0.0f}, {1.0f, 1.0f}, 0.0f, colors::kWhite,
                           {0.0f, 0.0f, 4.0f, 0.0f}),
               std::invalid_argument);
  EXPECT_TRUE(list.sprites.empty());

  Frame unknown = blankFrame();
  unknown.world.sprite(SpriteId{100000}, {0.0f, 0.0f}, {1.0f, 1.0f});
  EXPECT_EQ(errorOf([&] { render_test::sharedRenderer().render(unknown, kCamera); }),
            "render: sprite id 100000 was not made by this Renderer");
  Frame outside = blankFrame();
  outside.world.sprite(quadrants(), {0.0f, 0.0f}, {1.0f, 1.0f}, 0.0f, colors::kWhite,
                       {20.0f, 0.0f, 16.0f, 16.0f});
  EXPECT_EQ(errorOf([&] { render_test::sharedRenderer().render(outside, kCamera); }),
            "render: sprite source rectangle (20, 0, 16 x 16) goes outside its 32x32 image");
}

TEST(Font, TheShippedFontIsTheDefault) {
  const std::filesystem::path shipped = render::shippedFontPath();
  EXPECT_TRUE(shipped.is_absolute());
  EXPECT_EQ(shipped.parent_path().filename(), "fonts");
  EXPECT_EQ(shipped.filename(), "DejaVuSans.ttf");
  EXPECT_TRUE(std::filesystem::exists(shipped.parent_path() / "LICENSE-DejaVu.txt"));

  ::unsetenv("RICOCHET_FONT");
  EXPECT_EQ(render::defaultFontPath(), shipped.string());
  render::Renderer renderer;  // default options: the shipped font, from any working directory
  EXPECT_EQ(renderer.font().path(), shipped.string());
  Frame frame = blankFrame();
  frame.hud.text({10.0f, 10.0f}, "Ricochet", 20.0f, colors::kWhite);
  const Image image = renderer.render(frame, kCamera);
  int lit = 0;
  for (int y = 10; y < 30; ++y) {
    for (int x = 10; x < 90; ++x)
      lit += image.pixel(x, y).r > 200;
  }
  EXPECT_GT(lit, 40);
}

TEST(Font, EnvironmentAndOptionsOverrideTheDefault) {
  ::setenv("RICOCHET_FONT", "/nonexistent/env-font.ttf", 1);
  EXPECT_EQ(render::defaultFontPath(), "/nonexistent/env-font.ttf");
  EXPECT_EQ(errorOf([] { render::Renderer renderer; }),
            "render: cannot read font '/nonexistent/env-font.ttf': No such file or directory");
  // An explicit path wins over the environment.
  render::Renderer renderer(render::RendererOptions{render::shippedFontPath()});
  EXPECT_EQ(renderer.font().path(), render::shippedFontPath());
  ::setenv("RICOCHET_FONT", "", 1);
  EXPECT_EQ(render::defaultFontPath(), render::shippedFontPath());
  ::unsetenv("RICOCHET_FONT");
}

}  // namespace sprite_test
