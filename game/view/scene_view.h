// A world drawn as a render::Frame: every shape in the world layer (static bodies grey,
// dynamic ones in a colour of their own, darker while asleep, kinematic ones blue, sensors as
// outlines), and the debug overlay (AABBs, the quadtree's occupied cells, body ids, contact
// points with their normals, velocities).
// The renderer knows no physics types; this is where the two meet (game -> render, game ->
// physics).
#pragma once

#include <string>

#include "physics/world.h"
#include "render/camera.h"
#include "render/draw_list.h"

namespace game {

struct ViewOptions {
  bool overlay = true;
  std::string caption;  // first HUD line (the scene's name)
};

// The frame of the world as it is now; `step` is shown in the HUD.
render::Frame drawWorld(const rc::World& world, long step, const ViewOptions& options);

// The camera that shows every shape of the world as it is now, with a margin.
render::Camera cameraForWorld(const rc::World& world, int width, int height);

}  // namespace game
