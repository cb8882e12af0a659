// Golden images: one small frame (160x90) per primitive kind, the overlay and the HUD, compared
// with PNGs under tests/render/golden/ at a stated tolerance.
//
// Tolerance: every channel of every pixel within kGoldenTolerance of the golden image. llvmpipe
// is deterministic on one machine (see SameDrawListGivesIdenticalBytes); the slack is for other
// Mesa/LLVM versions rounding an anti-aliased edge differently, not for anything a person could
// see. On a mismatch the test writes <name>.actual.png and <name>.diff.png into
// golden_failures/ in the test's working directory (the build's tests/render) and names them.
//
// To create or update the images after a deliberate change, run the test with
// RICOCHET_UPDATE_GOLDEN=1 and look at every changed PNG before committing it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "render/png.h"
#include "render/renderer.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace golden_test {

using render::Color;
using render::Frame;
using render::Image;
using render::Style;
namespace colors = render::colors;

constexpr int kGoldenTolerance = 3;

struct Comparison {
  int worst = 0;      // largest channel difference
  int different = 0;  // pixels beyond the tolerance
};

Comparison compare(const Image& actual, const Image& expected, int tolerance) {
  Comparison c;
  for (int y = 0; y < actual.height; ++y) {
    for (int x = 0; x < actual.width; ++x) {
      int d = render_test::channelDistance(actual.pixel(x, y), expected.pixel(x, y));
      c.worst = std::max(c.worst, d);
      if (d > tolerance) ++c.different;
    }
  }
  return c;
}

// The expected image dimmed to grey, with pixels beyond the tolerance in red (brighter = larger).
Image diffImage(const Image& actual, const Image& expected, int tolerance) {
  Image diff(actual.width, actual.height);
  for (int y = 0; y < actual.height; ++y) {
    for (int x = 0; x < actual.width; ++x) {
      Color e = expected.pixel(x, y);
      int d = render_test::channelDistance(actual.pixel(x, y), e);
      if (d > tolerance) {
        diff.setPixel(x, y, {static_cast<std::uint8_t>(std::min(255, 128 + d)), 0, 0, 255});
      } else {
        auto grey = static_cast<std::uint8_t>((e.r + e.g + e.b) / 12);
        diff.setPixel(x, y, {grey, grey, grey, 255});
      }
    }
  }
  return diff;
}

// Empty when `actual` matches the golden image `name`; otherwise what is wrong and where the
// actual and diff images went.
std::string checkGolden(const std::string& name, const Image& actual,
                        const std::filesystem::path& goldenDir,
                        const std::filesystem::path& failureDir) {
  const std::filesystem::path golden = goldenDir / (name + ".png");
  const char* update = std::getenv("RICOCHET_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") {
    render::writePng(golden, actual, {9});
    return "";
  }
  if (!std::filesystem::exists(golden)) {
    return "no golden image " + golden.string() +
           " (run with RICOCHET_UPDATE_GOLDEN=1 to create it, then look at it)";
  }
  const Image expected = render::readPng(golden);
  std::string problem;
  if (expected.width != actual.width || expected.height != actual.height) {
    problem = "size " + std::to_string(actual.width) + "x" + std::to_string(actual.height) +
              ", golden " + std::to_string(expected.width) + "x" + std::to_string(expected.height);
  } else {
    Comparison c = compare(actual, expected, kGoldenTolerance);
    if (c.different == 0) return "";
    problem = std::to_string(c.different) + " pixels differ by more than " +
              std::to_string(kGoldenTolerance) + " (worst " + std::to_string(c.worst) + ")";
  }
  std::filesystem::create_directories(failureDir);
  const std::filesystem::path actualPath = failureDir / (name + ".actual.png");
  render::writePng(actualPath, actual);
  std::string message = name + ": " + problem + "; actual image in " + actualPath.string();
  if (expected.width == actual.width && expected.height == actual.height) {
    const std::filesystem::path diffPath = failureDir / (name + ".diff.png");
    render::writePng(diffPath, diffImage(actual, expected, kGoldenTolerance));
    message += ", diff in " + diffPath.string();
  }
  return message;
}

std::filesystem::path failureDir() {
  return std::filesystem::current_path() / "golden_failures";
}

void expectGolden(const std::string& name, const Frame& frame) {
  const render::Camera camera{160, 90, {0.0f, 0.0f}, 10.0f};
  const Image actual = render_test::sharedRenderer().render(frame, camera);
  std::string failure = checkGolden(name, actual, RICOCHET_GOLDEN_DIR, failureDir());
  EXPECT_TRUE(failure.empty()) << failure;
}

Frame baseFrame() {
  Frame frame;
  frame.background = Color{24, 26, 32, 255};
  return frame;
}

TEST(Golden, Circles) {
  Frame frame = baseFrame();
  frame.world.circle({-5.0f, 1.5f}, 2.2f, Style::filled(colors::kRed));
  frame.world.circle({0.0f, 1.5f}, 2.2f, Style::outlined(colors::kYellow, 2.0f));
  frame.world.circle({5.0f, 1.5f}, 2.2f, Style::both(colors::kBlue, colors::kWhite, 3.0f));
  frame.world.circle({-5.0f, -2.8f}, 0.35f, Style::filled(colors::kGreen));
  frame.world.circle({0.0f, -2.8f}, 1.0f, Style::filled(Color{255, 255, 255, 128}));
  frame.world.circle({0.6f, -2.8f}, 1.0f, Style::filled(Color{255, 0, 0, 128}));
  frame.world.dot({5.0f, -2.8f}, 2.0f, colors::kOrange);
  expectGolden("circles", frame);
}

TEST(Golden, Capsules) {
  Frame frame = baseFrame();
  frame.world.capsule({-6.0f, 2.0f}, {-1.0f, 3.0f}, 0.8f, Style::filled(colors::kGreen));
  frame.world.capsule({1.0f, 2.5f}, {6.0f, 2.5f}, 1.0f, Style::outlined(colors::kCyan, 1.5f));
  frame.world.capsule({-4.0f, -2.0f}, {-4.0f, -3.5f}, 0.6f,
                      Style::both(colors::kMagenta, colors::kBlack, 2.0f));
  frame.world.capsule({2.0f, -3.0f}, {2.0f, -3.0f}, 0.9f, Style::filled(colors::kYellow));
  expectGolden("capsules", frame);
}

TEST(Golden, Polygons) {
  Frame frame = baseFrame();
  const rc::Vec2 triangle[] = {{-7.0f, -3.5f}, {-3.0f, -3.5f}, {-5.0f, 3.0f}};
  frame.world.polygon(triangle, Style::filled(colors::kCyan));
  rc::Vec2 hexagon[6];
  for (int i = 0; i < 6; ++i) {
    float a = 1.0471976f * static_cast<float>(i) + 0.2f;
    hexagon[i] = {0.0f + 2.5f * std::cos(a), 0.0f + 2.5f * std::sin(a)};
  }
  frame.world.polygon(hexagon, Style::both(colors::kMagenta, colors::kWhite, 1.5f));
  const rc::Vec2 box[] = {{4.0f, -2.0f}, {6.5f, -2.0f}, {6.5f, 2.0f}, {4.0f, 2.0f}};
  frame.world.polygon(box, Style::filled(colors::kOrange), 0.5f);  // rounded
  frame.world.rect({{-7.5f, -4.2f}, {7.5f, -3.8f}}, Style::filled(colors::kGray));
  expectGolden("polygons", frame);
}

TEST(Golden, LinesAndArrows) {
  Frame frame = baseFrame();
  const rc::Vec2 zigzag[] = {{-7.0f, -3.0f}, {-5.5f, 2.0f}, {-4.0f, -3.0f}, {-2.5f, 2.0f}};
  frame.world.polyline(zigzag, 3.0f, colors::kOrange);
  frame.world.segment({-1.0f, -3.0f}, {2.0f, 3.0f}, 1.0f, colors::kWhite);
  frame.world.segment({-1.0f, 3.5f}, {3.0f, 3.5f}, 0.5f, colors::kWhite);
  const rc::Vec2 square[] = {{0.5f, -3.5f}, {2.5f, -3.5f}, {2.5f, -1.5f}, {0.5f, -1.5f}};
  frame.world.polyline(square, 2.0f, colors::kCyan, true);
  frame.world.arrow({4.0f, -3.0f}, {7.0f, 3.0f}, 2.0f, colors::kYellow, 12.0f);
  frame.world.arrow({4.0f, -3.0f}, {7.5f, -3.0f}, 1.0f, colors::kRed, 8.0f);
  frame.world.arrow({4.0f, 0.0f}, {4.3f, 0.0f}, 1.0f, colors::kGreen, 8.0f);  // all head
  expectGolden("lines_arrows", frame);
}

TEST(Golden, Text) {
  Frame frame = baseFrame();
  frame.world.text({-7.5f, 4.0f}, "Ricochet 0123", 16.0f, colors::kWhite);
  frame.world.text({0.0f, 1.0f}, "centred", 12.0f, colors::kYellow, render::HAlign::kCenter,
                   render::VAlign::kMiddle);
  frame.world.text({7.5f, -4.0f}, "right\nbottom", 10.0f, colors::kCyan, render::HAlign::kRight,
                   render::VAlign::kBottom);
  frame.world.text({-7.5f, -3.0f}, "AVAWAY", 24.0f, colors::kGreen, render::HAlign::kLeft,
                   render::VAlign::kBaseline);
  expectGolden("text", frame);
}

TEST(Golden, OverlayAndHud) {
  Frame frame = baseFrame();
  frame.world.circle({-3.0f, 0.0f}, 1.5f, Style::filled(colors::kBlue));
  const rc::Vec2 box[] = {{0.0f, -1.0f}, {2.0f, -1.0f}, {2.0f, 1.0f}, {0.0f, 1.0f}};
  frame.world.polygon(box, Style::filled(colors::kRed));
  // Debug overlay: AABBs, a contact point with its normal, a ray and its hit, a sight cone.
  const Color aabb{60, 220, 90, 255};
  frame.overlay.rect({{-4.5f, -1.5f}, {-1.5f, 1.5f}}, Style::outlined(aabb, 1.0f));
  frame.overlay.rect({{0.0f, -1.0f}, {2.0f, 1.0f}}, Style::outlined(aabb, 1.0f));
  frame.overlay.dot({-1.5f, 0.0f}, 2.5f, colors::kYellow);
  frame.overlay.arrow({-1.5f, 0.0f}, {-0.3f, 0.0f}, 1.0f, colors::kYellow, 6.0f);
  frame.overlay.segment({-7.0f, -3.0f}, {0.0f, -0.6f}, 1.0f, colors::kWhite);
  frame.overlay.dot({0.0f, -0.6f}, 2.0f, colors::kRed);
  rc::Vec2 cone[9];
  cone[0] = {5.0f, -3.0f};
  for (int i = 0; i < 8; ++i) {
    float a = 1.3f + 0.12f * static_cast<float>(i);
    cone[i + 1] = {5.0f + 5.0f * std::cos(a), -3.0f + 5.0f * std::sin(a)};
  }
  frame.overlay.polygon(cone, Style::both(Color{255, 255, 0, 40}, Color{255, 255, 0, 160}, 1.0f));
  frame.overlay.text({-3.0f, 0.0f}, "7", 10.0f, colors::kWhite, render::HAlign::kCenter,
                     render::VAlign::kMiddle);
  // HUD: a health bar and a tick counter, in pixels from the top-left.
  frame.hud.rect({{4.0f, 4.0f}, {54.0f, 10.0f}}, Style::outlined(colors::kWhite, 1.0f));
  frame.hud.rect({{5.0f, 5.0f}, {40.0f, 9.0f}}, Style::filled(colors::kGreen));
  frame.hud.text({156.0f, 4.0f}, "tick 42", 10.0f, colors::kWhite, render::HAlign::kRight);
  expectGolden("overlay_hud", frame);
}

TEST(Golden, Sprites) {
  render_test::ScratchDir dir;
  render::writePng(dir.path() / "crate.png", render_test::crateSprite());
  render::writePng(dir.path() / "quadrants.png", render_test::quadrantSprite());
  render::Renderer& renderer = render_test::sharedRenderer();
  const render::SpriteId crate = renderer.loadSprite(dir.path() / "crate.png");
  const render::SpriteId quadrants = renderer.loadSprite(dir.path() / "quadrants.png");
  Frame frame = baseFrame();
  // A disc under a crate, a crate turned half a radian, the quadrants turned a quarter (red
  // top-left goes to the bottom-left), a translucent tinted crate with text on top.
  frame.world.circle({-5.5f, 0.5f}, 1.6f, Style::filled(colors::kBlue));
  frame.world.sprite(crate, {-5.5f, 1.0f}, {2.4f, 2.4f});
  frame.world.sprite(crate, {-1.5f, 1.5f}, {3.0f, 3.0f}, 0.5f);
  frame.world.sprite(quadrants, {2.5f, 1.5f}, {3.0f, 3.0f}, 1.5707964f);
  frame.world.sprite(crate, {6.0f, 1.5f}, {2.5f, 2.5f}, -0.3f, Color{120, 200, 255, 160});
  frame.world.text({6.0f, 1.5f}, "x2", 12.0f, colors::kWhite, render::HAlign::kCenter,
                   render::VAlign::kMiddle);
  // Bottom row: one quadrant of the image (its source rectangle), crates drawn small (mipmaps),
  // a stretched crate, and a disc added after a crate, so on top of it.
  frame.world.sprite(quadrants, {-6.0f, -2.8f}, {1.5f, 1.5f}, 0.0f, colors::kWhite,
                     {16.0f, 0.0f, 16.0f, 16.0f});
  frame.world.sprite(crate, {-3.8f, -2.8f}, {0.8f, 0.8f}, 0.3f);
  frame.world.sprite(crate, {-2.8f, -2.8f}, {0.8f, 0.8f}, 0.8f);
  frame.world.sprite(crate, {0.5f, -2.8f}, {3.5f, 1.2f}, 0.0f, Color{255, 220, 220, 255});
  frame.world.sprite(crate, {4.5f, -2.8f}, {2.0f, 2.0f});
  frame.world.circle({5.2f, -3.3f}, 0.6f, Style::filled(colors::kOrange));
  // A HUD sprite, pixels from the top-left: the red mark at its top-left.
  frame.hud.sprite(crate, {148.0f, 10.0f}, {14.0f, 14.0f});
  expectGolden("sprites", frame);
}

TEST(Golden, MismatchWritesActualAndDiffImages) {
  render_test::ScratchDir dir;
  Image golden(8, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x)
      golden.setPixel(x, y, colors::kBlue);
  }
  render::writePng(dir.path() / "case.png", golden);
  Image close = golden;
  close.setPixel(1, 1,
                 {static_cast<std::uint8_t>(colors::kBlue.r + kGoldenTolerance), colors::kBlue.g,
                  colors::kBlue.b, 255});
  if (std::getenv("RICOCHET_UPDATE_GOLDEN") != nullptr) GTEST_SKIP() << "updating goldens";
  EXPECT_EQ(checkGolden("case", close, dir.path(), dir.path() / "fail"), "");
  Image off = golden;
  off.setPixel(2, 3, colors::kRed);
  std::string message = checkGolden("case", off, dir.path(), dir.path() / "fail");
  EXPECT_EQ(message, "case: 1 pixels differ by more than 3 (worst " +
                         std::to_string(render_test::channelDistance(colors::kRed, colors::kBlue)) +
                         "); actual image in " +
                         (dir.path() / "fail" / "case.actual.png").string() + ", diff in " +
                         (dir.path() / "fail" / "case.diff.png").string());
  EXPECT_TRUE(render::readPng(dir.path() / "fail" / "case.actual.png") == off);
  Image diff = render::readPng(dir.path() / "fail" / "case.diff.png");
  EXPECT_GT(diff.pixel(2, 3).r, 128);
  EXPECT_EQ(diff.pixel(0, 0).r, diff.pixel(0, 0).b);
}

}  // namespace golden_test
