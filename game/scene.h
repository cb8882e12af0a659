// Scene files: a JSON description of a world (settings, integrator, gravity, bodies, shapes,
// materials, initial velocities), read into plain definitions that our World and the Box2D
// adapter in tests/ both build from, and the state format both write. The format is
// documented in game/README.md ("Scene files").
//
// Every error names the file, the body (index and name) or setting, and the field, on one line:
// "scenes/pile.json: body 3 ("crate"), shapes[0]: circle: radius must be positive, got -1".
// Unknown fields are errors too (a typo must not silently fall back to a default).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "physics/world.h"

namespace game {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ShapeDesc {
  rc::Shape shape = rc::Circle{};
  rc::ShapeDef def;
};

struct BodyDesc {
  std::string name;  // optional in the file; "" if absent
  rc::BodyDef def;
  std::vector<ShapeDesc> shapes;  // a chain is expanded into its links
  // A constant force (N, world axes) and torque (N m) acting at every instant of the run, for
  // scenes with an answer in closed form (a box spun by a torque, a sled pushed along).
  // forcePoint is where the force acts, in the body's frame; absent, the centre of mass.
  rc::Vec2 force{};
  float torque = 0.0f;
  std::optional<rc::Vec2> forcePoint;
  bool pushed() const { return force.x != 0.0f || force.y != 0.0f || torque != 0.0f; }
};

struct SceneDesc {
  std::string source;  // the file it came from, for messages
  rc::WorldDef world;
  float dt = 1.0f / 60.0f;
  std::vector<BodyDesc> bodies;
};

// Reads and validates a scene; throws SceneError.
// Scene files larger than this are refused before they are read (the parsed tree takes about
// ten times the file); deeper nesting is refused while parsing (a scene needs five levels).
inline constexpr std::uintmax_t kMaxSceneBytes = std::uintmax_t{32} << 20;
inline constexpr int kMaxSceneDepth = 32;

SceneDesc loadScene(const std::string& path);
// The same from text; `name` stands for the file in messages.
SceneDesc parseScene(std::string_view text, const std::string& name);

// Our world built from a scene; ids[i] is body i of the scene. The bodies' constant forces are
// one force field, evaluated at every stage of the integrator.
struct BuiltWorld {
  std::unique_ptr<rc::World> world;
  std::vector<rc::BodyId> ids;
};
BuiltWorld buildWorld(const SceneDesc& scene);

// The state both engines write after a run.
struct BodyState {
  std::string name;
  rc::Vec2 position{};  // body origin
  float angle = 0;
  rc::Vec2 linearVelocity{};
  float angularVelocity = 0;
};
struct SceneState {
  std::string engine;  // "ricochet" or "box2d 2.4.1"
  int steps = 0;
  double time = 0;
  std::string hash;  // engine-specific; empty when the engine has none
  std::vector<BodyState> bodies;
};
SceneState captureState(const SceneDesc& scene, const BuiltWorld& built, int steps);
std::string stateToJson(const SceneState& state);
// Writes `text` to `path` through a temporary file and a rename: a killed run never leaves a
// half-written file under the final name. Throws SceneError naming the path.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace game
