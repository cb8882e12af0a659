// Draw list: what the adders record, and one-line errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "render/draw_list.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace draw_list_test {

using render::DrawList;
using render::ShapeKind;
using render::Style;

std::string errorOf(void (*build)(DrawList&)) {
  DrawList list;
  try {
    build(list);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(DrawList, PolygonsAreStoredCounterClockwiseWithBounds) {
  DrawList list;
  const rc::Vec2 clockwise[] = {{0, 0}, {0, 2}, {3, 2}, {3, 0}};
  list.polygon(clockwise, Style::filled(render::colors::kRed));
  ASSERT_EQ(list.shapes.size(), 1u);
  const render::Shape& s = list.shapes[0];
  EXPECT_EQ(s.kind, ShapeKind::kPolygon);
  EXPECT_EQ(s.pointCount, 4u);
  EXPECT_EQ(s.a, (rc::Vec2{0, 0}));
  EXPECT_EQ(s.b, (rc::Vec2{3, 2}));
  float area2 = 0;
  for (std::uint32_t i = 0; i < 4; ++i) {
    area2 += rc::cross(list.points[i], list.points[(i + 1) % 4]);
  }
  EXPECT_GT(area2, 0.0f);
}

TEST(DrawList, LinesAndArrowsUsePixelWidths) {
  DrawList list;
  list.segment({0, 0}, {1, 0}, 3.0f, render::colors::kWhite);
  list.arrow({0, 0}, {0, 5}, 2.0f, render::colors::kWhite, 12.0f);
  const rc::Vec2 line[] = {{0, 0}, {1, 0}, {1, 1}};
  list.polyline(line, 1.0f, render::colors::kWhite, true);
  ASSERT_EQ(list.shapes.size(), 5u);
  EXPECT_EQ(list.shapes[0].kind, ShapeKind::kCapsule);
  EXPECT_FLOAT_EQ(list.shapes[0].radius, 0.0f);
  EXPECT_FLOAT_EQ(list.shapes[0].radiusPixels, 1.5f);
  EXPECT_EQ(list.shapes[1].kind, ShapeKind::kArrow);
  EXPECT_FLOAT_EQ(list.shapes[1].headPixels, 12.0f);
  // A closed polyline of three points is three segments.
  EXPECT_EQ(list.shapes[4].a, (rc::Vec2{1, 1}));
  EXPECT_EQ(list.shapes[4].b, (rc::Vec2{0, 0}));
}

TEST(DrawList, BadInputGivesOneLineNamingTheValue) {
  EXPECT_EQ(errorOf([](DrawList& l) {
              l.circle({0, 0}, -1.0f, Style{});
            }),
            "render: DrawList::circle: radius must be finite and >= 0, got -1");
  EXPECT_EQ(errorOf([](DrawList& l) {
              l.circle({std::numeric_limits<float>::quiet_NaN(), 0}, 1.0f, Style{});
            }),
            "render: DrawList::circle: centre must be finite, got (nan, 0)");
  EXPECT_EQ(errorOf([](DrawList& l) {
              const rc::Vec2 two[] = {{0, 0}, {1, 0}};
              l.polygon(two, Style{});
            }),
            "render: DrawList::polygon: needs at least 3 vertices, got 2");
  EXPECT_EQ(errorOf([](DrawList& l) {
              const rc::Vec2 dart[] = {{0, 0}, {2, 1}, {4, 0}, {2, 4}};
              l.polygon(dart, Style{});
            }),
            "render: DrawList::polygon: vertices must form a convex polygon (vertex 1 turns the "
            "other way)");
  EXPECT_EQ(errorOf([](DrawList& l) {
              l.text({0, 0}, "x", 0.0f, render::colors::kWhite);
            }),
            "render: DrawList::text: size must be finite and > 0, got 0");
  EXPECT_EQ(errorOf([](DrawList& l) {
              l.segment({0, 0}, {1, 1}, -2.0f, render::colors::kWhite);
            }),
            "render: DrawList::segment: width must be finite and >= 0, got -2");
}

}  // namespace draw_list_test
