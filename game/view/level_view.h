// The parts of a level that never move, drawn once per view: the floor over the map's bounds with
// a faint tile grid (and what lies beyond the map darker), the regions of merged tiles filled and
// edged, static walls, trigger zones. Props, pickups and whatever else can move or change are drawn
// every frame by the match view.
#pragma once

#include <span>
#include <vector>

#include "game/level/level.h"
#include "game/level/level_builder.h"
#include "physics/world.h"
#include "render/draw_list.h"

namespace game {

// The frame is to be cleared to the floor's colour (palette::kFloor): what it shows beyond the
// map's bounds (`visible` is the world rectangle the frame shows) is covered instead, far fewer
// pixels to shade than a floor drawn over the whole map. `pixel` is a pixel's size in metres at
// the view's zoom: fills overlap by half of one, so that no seam shows between neighbouring
// rectangles.
render::DrawList drawLevelStatics(const Level& level, const BuiltLevel& built,
                                  const rc::World& world, const rc::AABB& visible, float pixel);

// The inside of closed loops of straight links (even-odd: a loop inside another is a hole) as
// rectangles, band by band between the links' distinct heights: exact for loops of horizontal
// and vertical links (merged tiles), an approximation of slanted ones.
std::vector<rc::AABB> fillLoops(std::span<const rc::Segment> links);

}  // namespace game
