// Camera: world y up maps to pixel y down, zoom and centre, fitting a rectangle.
#include <gtest/gtest.h>

#include <stdexcept>

#include "render/camera.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace camera_test {

using render::Camera;

TEST(Camera, CentreLandsOnTheMiddleAndYPointsUp) {
  Camera camera{160, 90, {10.0f, 5.0f}, 4.0f};
  rc::Vec2 middle = camera.worldToPixel({10.0f, 5.0f});
  EXPECT_FLOAT_EQ(middle.x, 80.0f);
  EXPECT_FLOAT_EQ(middle.y, 45.0f);
  // One unit up in the world is `zoom` pixels up in the picture (smaller pixel y).
  rc::Vec2 up = camera.worldToPixel({10.0f, 6.0f});
  EXPECT_FLOAT_EQ(up.x, 80.0f);
  EXPECT_FLOAT_EQ(up.y, 41.0f);
  rc::Vec2 right = camera.worldToPixel({11.0f, 5.0f});
  EXPECT_FLOAT_EQ(right.x, 84.0f);
}

TEST(Camera, PixelToWorldInvertsWorldToPixel) {
  Camera camera{640, 360, {-3.25f, 7.5f}, 12.5f};
  for (rc::Vec2 p : {rc::Vec2{0, 0}, rc::Vec2{-10, 3}, rc::Vec2{100, -50}}) {
    rc::Vec2 back = camera.pixelToWorld(camera.worldToPixel(p));
    EXPECT_NEAR(back.x, p.x, 1e-4f);
    EXPECT_NEAR(back.y, p.y, 1e-4f);
  }
}

TEST(Camera, VisibleWorldMatchesTheFrameCorners) {
  Camera camera{200, 100, {1.0f, 2.0f}, 10.0f};
  rc::AABB box = camera.visibleWorld();
  EXPECT_FLOAT_EQ(box.lower.x, -9.0f);
  EXPECT_FLOAT_EQ(box.upper.x, 11.0f);
  EXPECT_FLOAT_EQ(box.lower.y, -3.0f);
  EXPECT_FLOAT_EQ(box.upper.y, 7.0f);
}

TEST(Camera, FitShowsTheWholeRectangleWithItsMargin) {
  // A wide rectangle in a 16:9 frame: width decides the zoom.
  rc::AABB wide{{-20.0f, -1.0f}, {20.0f, 1.0f}};
  Camera a = Camera::fit(wide, 160, 90, 10.0f);
  EXPECT_FLOAT_EQ(a.zoom, 140.0f / 40.0f);
  EXPECT_FLOAT_EQ(a.worldToPixel(wide.lower).x, 10.0f);
  EXPECT_FLOAT_EQ(a.worldToPixel(wide.upper).x, 150.0f);
  // A tall one: height decides.
  rc::AABB tall{{0.0f, 0.0f}, {1.0f, 10.0f}};
  Camera b = Camera::fit(tall, 160, 90);
  EXPECT_FLOAT_EQ(b.zoom, 9.0f);
  EXPECT_FLOAT_EQ(b.worldToPixel(tall.upper).y, 0.0f);
  EXPECT_FLOAT_EQ(b.worldToPixel(tall.lower).y, 90.0f);
  // A point: centred, with some zoom.
  Camera c = Camera::fit({{3.0f, 4.0f}, {3.0f, 4.0f}}, 160, 90);
  EXPECT_FLOAT_EQ(c.center.x, 3.0f);
  EXPECT_GT(c.zoom, 0.0f);
}

TEST(Camera, FitRejectsBadInput) {
  EXPECT_THROW(Camera::fit({{0, 0}, {1, 1}}, 0, 90), std::invalid_argument);
  EXPECT_THROW(Camera::fit({{1, 1}, {0, 0}}, 160, 90), std::invalid_argument);
  EXPECT_THROW(Camera::fit({{0, 0}, {1, 1}}, 160, 90, 50.0f), std::invalid_argument);
}

}  // namespace camera_test
