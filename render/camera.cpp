#include "render/camera.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace render {

Camera Camera::fit(const rc::AABB& rect, int width, int height, float marginPixels) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("render: Camera::fit: frame size must be positive, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
  if (!rect.isValid()) {
    throw std::invalid_argument(
        "render: Camera::fit: rectangle must be finite with lower <= upper");
  }
  float usableW = static_cast<float>(width) - 2.0f * marginPixels;
  float usableH = static_cast<float>(height) - 2.0f * marginPixels;
  if (!(usableW > 0.0f && usableH > 0.0f)) {
    throw std::invalid_argument("render: Camera::fit: margin leaves no room in the frame");
  }
  rc::Vec2 size = rect.upper - rect.lower;
  // A degenerate rectangle (a point or a line) is shown at one world unit across.
  float w = std::max(size.x, 1e-6f);
  float h = std::max(size.y, 1e-6f);
  float zoom = std::min(usableW / w, usableH / h);
  if (size.x <= 1e-6f && size.y <= 1e-6f) zoom = std::min(usableW, usableH);
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.center = rect.center();
  camera.zoom = zoom;
  return camera;
}

}  // namespace render
