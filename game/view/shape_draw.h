// A physics shape drawn into a render::DrawList at a body's transform: the one place that knows
// how each rc::ShapeType looks (circles, boxes, polygons, capsules as themselves; segments and
// chain links as lines), shared by the scene view and the match view.
#pragma once

#include "physics/shapes.h"
#include "render/draw_list.h"

namespace game {

// Segments and chain links are lines `lineWidthPixels` wide in the style's fill colour (its
// stroke colour when the fill is transparent).
void drawShape(render::DrawList& list, const rc::Shape& shape, const rc::Transform& xf,
               const render::Style& style, float lineWidthPixels = 2.0f);

}  // namespace game
