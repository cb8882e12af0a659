// The camera: which part of the world a frame shows and at what size.
//
// World coordinates have y up (the physics convention); pixel coordinates have (0, 0) at the
// top-left corner of the top-left pixel, x right, y down, so the centre of pixel (i, j) is at
// (i + 0.5, j + 0.5). The world point `center` lands on the middle of the frame, and one world
// unit spans `zoom` pixels.
#pragma once

#include "physics/math.h"

namespace render {

struct Camera {
  int width = 640;   // frame size in pixels
  int height = 360;  //
  rc::Vec2 center{0.0f, 0.0f};
  float zoom = 10.0f;  // pixels per world unit

  rc::Vec2 worldToPixel(rc::Vec2 world) const {
    return {0.5f * static_cast<float>(width) + (world.x - center.x) * zoom,
            0.5f * static_cast<float>(height) - (world.y - center.y) * zoom};
  }
  rc::Vec2 pixelToWorld(rc::Vec2 pixel) const {
    return {center.x + (pixel.x - 0.5f * static_cast<float>(width)) / zoom,
            center.y - (pixel.y - 0.5f * static_cast<float>(height)) / zoom};
  }
  // The world rectangle the frame shows.
  rc::AABB visibleWorld() const {
    rc::Vec2 half{0.5f * static_cast<float>(width) / zoom,
                  0.5f * static_cast<float>(height) / zoom};
    return {center - half, center + half};
  }
  // Keeps the zoom and centres the frame on a point (a camera following a player).
  void follow(rc::Vec2 point) { center = point; }

  // The largest zoom that shows all of `rect` with `marginPixels` to spare on every side,
  // centred on it. Throws std::invalid_argument for a bad size or rectangle.
  static Camera fit(const rc::AABB& rect, int width, int height, float marginPixels = 0.0f);
};

}  // namespace render
