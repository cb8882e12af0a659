// Scene files (game/scene.h): every kind of bad input gets one line naming the file, the body
// and the field; a complete scene reads into the definitions it spells out; a scene-built
// world steps exactly like the same world built by hand; outputs are written atomically.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "game/scene.h"

namespace scene_test {

std::string errorOf(const std::string& text) {
  try {
    game::SceneDesc scene = game::parseScene(text, "s.json");
    game::buildWorld(scene);
  } catch (const game::SceneError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Scene, BadInputNamesFileBodyAndField) {
  struct Case {
    const char* text;
    const char* message;
  };
  const Case cases[] = {
      {"",
       "s.json: not valid JSON at line 1, column 1: syntax error while parsing value - "
       "unexpected end of input; expected '[', '{', or a literal"},
      {R"({"bodies": [)",
       "s.json: not valid JSON at line 1, column 13: syntax error while "
       "parsing value - unexpected end of input; expected '[', '{', or a "
       "literal"},
      {"[]", "s.json: the top level must be an object with \"bodies\""},
      {R"({"bodys": []})", "s.json: bodys: unknown field"},
      {R"({"settings": {}})", "s.json: bodies: must be an array"},
      {R"({"settings": {"gravity": [0]}, "bodies": []})",
       "s.json: settings, gravity: must be [x, y], got [0]"},
      {R"({"settings": {"integrator": "leapfrog"}, "bodies": []})",
       "s.json: settings, integrator: must be one of explicit-euler, semi-implicit-euler, "
       "verlet, rk4; got \"leapfrog\""},
      {R"({"settings": {"substeps": 0}, "bodies": []})",
       "s.json: settings, substeps: must be an integer from 1 to 64, got 0"},
      {R"({"settings": {"stackSolveDepth": -1}, "bodies": []})",
       "s.json: settings, stackSolveDepth: must be an integer from 0 to 1000000, got -1"},
      {R"({"settings": {"stackSolveDepth": 2.5}, "bodies": []})",
       "s.json: settings, stackSolveDepth: must be an integer from 0 to 1000000, got 2.5"},
      {R"({"settings": {"dt": 1e999}, "bodies": []})",
       "s.json: not valid JSON: number overflow parsing '1e999'"},
      {R"({"bodies": [{"name": "crate", "type": "dynamik"}]})",
       "s.json: body 0 (\"crate\"), type: must be \"static\", \"kinematic\" or \"dynamic\", got "
       "\"dynamik\""},
      {R"({"bodies": [{}, {"position": [1, "x"]}]})",
       "s.json: body 1, position: must be [x, y], got [1,\"x\"]"},
      {R"({"bodies": [{"angle": true}]})", "s.json: body 0, angle: must be a number, got true"},
      {R"({"bodies": [{"shapes": [{"type": "circle"}]}]})",
       "s.json: body 0, shapes[0].radius: is missing"},
      {R"({"bodies": [{"shapes": [{"type": "circle", "radius": -1}]}]})",
       "s.json: body 0, shapes[0]: circle: radius must be positive, got -1"},
      {R"({"bodies": [{"shapes": [{"type": "circle", "radius": 1, "radiuss": 2}]}]})",
       "s.json: body 0, shapes[0].radiuss: unknown field for a circle"},
      {R"({"bodies": [{"shapes": [{"type": "blob"}]}]})",
       "s.json: body 0, shapes[0].type: must be one of circle, box, polygon, capsule, segment, "
       "chain; got \"blob\""},
      {R"({"bodies": [{"shapes": [{"type": "polygon", "points": [[0, 0], [1, 0], [2, 0]]}]}]})",
       "s.json: body 0, shapes[0]: polygon: the 3 points have a degenerate hull (all coincident "
       "or collinear)"},
      {R"({"bodies": [{"shapes": [{"type": "box", "halfExtents": [1, 1], "mask": -1}]}]})",
       "s.json: body 0, shapes[0].mask: must be an integer from 0 to 4294967295, got -1"},
      {R"({"bodies": [{"type": "dynamic", "linearDamping": -1}]})",
       "s.json: body 0: linearDamping is -1 (must be >= 0)"},
      {R"({"bodies": [{"type": "dynamic", "shapes": [{"type": "segment", "point1": [0, 0],
           "point2": [1, 0]}]}]})",
       "s.json: body 0: shape: type is a segment, which has no area: only static and kinematic "
       "bodies may carry it"},
      {R"({"bodies": [{"type": "dynamic", "forcePoint": [1, 0]}]})",
       "s.json: body 0, forcePoint: is given without a force"},
      {R"({"bodies": [{"name": "wall", "force": [1, 0]}]})",
       "s.json: body 0 (\"wall\"), force: acts on dynamic bodies only"},
      {R"({"bodies": [{"type": "kinematic", "torque": 2}]})",
       "s.json: body 0, torque: acts on dynamic bodies only"},
      {R"({"bodies": [{"type": "dynamic", "torque": "x"}]})",
       "s.json: body 0, torque: must be a number, got \"x\""},
  };
  for (const Case& c : cases)
    EXPECT_EQ(errorOf(c.text), c.message) << c.text;
}

// A constant torque on a free box (no gravity) from rest: angle tau t^2 / (2 I) in closed form.
// Semi-implicit Euler at substep h reaches tau h^2 n (n + 1) / (2 I) after n substeps, 1/n
// ahead: 240 substeps in a second, 0.42%. A constant force at a point off the centre both
// pushes and turns it; at the start the angular acceleration is (r x F) / I.
TEST(Scene, ConstantForcesAndTorquesActAtEveryInstant) {
  const game::SceneDesc spun = game::parseScene(
      R"({"settings": {"gravity": [0, 0]}, "bodies": [{"type": "dynamic", "torque": 3,
          "shapes": [{"type": "box", "halfExtents": [1, 0.5]}]}]})",
      "spun.json");
  game::BuiltWorld built = game::buildWorld(spun);
  const rc::BodyId box = built.ids[0];
  const float inertia = built.world->rotationalInertia(box);
  EXPECT_NEAR(inertia, 2.0f * (4.0f + 1.0f) / 12.0f, 1e-5f);  // m (w^2 + h^2) / 12, m = 2
  for (int k = 0; k < 60; ++k)
    built.world->step(spun.dt);
  const double exact = 3.0 / (2.0 * inertia), n = 240;
  EXPECT_NEAR(built.world->angle(box), exact * (n + 1) / n, exact * 2e-4);
  EXPECT_NEAR(built.world->angularVelocity(box), 3.0 / inertia, 1e-4);
  EXPECT_EQ(built.world->linearVelocity(box), rc::Vec2{});

  // 2 N along +y at the box's right end (1, 0) of a box whose origin is 0.5 m left of its
  // centre: r = (0.5, 0) from the centre of mass, torque 1 N m, mass 1 kg.
  const game::SceneDesc pushed = game::parseScene(
      R"({"settings": {"gravity": [0, 0], "substeps": 1}, "bodies": [{"type": "dynamic",
          "force": [0, 2], "forcePoint": [1, 0],
          "shapes": [{"type": "box", "halfExtents": [0.5, 0.5], "center": [0.5, 0]}]}]})",
      "pushed.json");
  built = game::buildWorld(pushed);
  const rc::BodyId b = built.ids[0];
  built.world->step(pushed.dt);
  const float h = pushed.dt, i = built.world->rotationalInertia(b);
  EXPECT_NEAR(built.world->linearVelocity(b).y, h * 2.0f, 1e-7f);
  EXPECT_NEAR(built.world->angularVelocity(b), h * 1.0f / i, 1e-6f);
  EXPECT_EQ(built.world->linearVelocity(b).x, 0.0f);
}

TEST(Scene, ReadsEveryField) {
  const char* text = R"({
    "settings": {"gravity": [1, -9], "integrator": "rk4", "substeps": 6, "dt": 0.01,
                 "restitutionThreshold": 2, "contactHertz": 20, "sleep": false,
                 "contactRecycleDistance": 0, "stackSolveDepth": 5, "continuous": false,
                 "bounds": {"lower": [-10, -10], "upper": [10, 30]}},
    "bodies": [
      {"name": "walls", "shapes": [
        {"type": "chain", "points": [[-5, 0], [0, -1], [5, 0]], "oneSided": true},
        {"type": "segment", "point1": [-5, 5], "point2": [5, 5]}]},
      {"name": "thing", "type": "dynamic", "position": [1, 2], "angle": 0.5,
       "linearVelocity": [3, 4], "angularVelocity": 1.5, "linearDamping": 0.1,
       "angularDamping": 0.2, "gravityScale": 0.5, "fixedRotation": true, "bullet": true,
       "allowSleep": false, "shapes": [
         {"type": "circle", "center": [0.5, 0], "radius": 0.25, "density": 2, "friction": 0.1,
          "restitution": 0.9, "sensor": true, "category": 4, "mask": 3},
         {"type": "box", "halfExtents": [1, 0.5], "angle": 0.3},
         {"type": "box", "halfExtents": [1, 0.5], "center": [0, 1]},
         {"type": "polygon", "points": [[0, 0], [1, 0], [0, 1]], "radius": 0.05},
         {"type": "capsule", "center1": [0, 0], "center2": [1, 0], "radius": 0.2}]}]})";
  const game::SceneDesc s = game::parseScene(text, "s.json");
  EXPECT_EQ(s.world.gravity, (rc::Vec2{1, -9}));
  EXPECT_EQ(s.world.integrator, rc::Integrator::rk4);
  EXPECT_EQ(s.world.substeps, 6);
  EXPECT_FLOAT_EQ(s.dt, 0.01f);
  EXPECT_FLOAT_EQ(s.world.restitutionThreshold, 2);
  EXPECT_FLOAT_EQ(s.world.contactHertz, 20);
  EXPECT_EQ(s.world.contactRecycleDistance, 0.0f);
  EXPECT_EQ(s.world.stackSolveDepth, 5);
  EXPECT_FALSE(s.world.enableSleep);
  EXPECT_FALSE(s.world.continuous);
  EXPECT_EQ(s.world.bounds.upper, (rc::Vec2{10, 30}));
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].def.type, rc::BodyType::staticBody);
  ASSERT_EQ(s.bodies[0].shapes.size(), 3u);  // two chain links and a segment
  EXPECT_EQ(s.bodies[0].shapes[0].shape.type, rc::ShapeType::chainSegment);
  EXPECT_TRUE(s.bodies[0].shapes[0].shape.chainSegment.oneSided);
  const rc::BodyDef& d = s.bodies[1].def;
  EXPECT_EQ(s.bodies[1].name, "thing");
  EXPECT_EQ(d.type, rc::BodyType::dynamicBody);
  EXPECT_EQ(d.position, (rc::Vec2{1, 2}));
  EXPECT_FLOAT_EQ(d.angle, 0.5f);
  EXPECT_EQ(d.linearVelocity, (rc::Vec2{3, 4}));
  EXPECT_FLOAT_EQ(d.angularVelocity, 1.5f);
  EXPECT_FLOAT_EQ(d.linearDamping, 0.1f);
  EXPECT_FLOAT_EQ(d.angularDamping, 0.2f);
  EXPECT_FLOAT_EQ(d.gravityScale, 0.5f);
  EXPECT_TRUE(d.fixedRotation && d.bullet && !d.allowSleep);
  const auto& shapes = s.bodies[1].shapes;
  ASSERT_EQ(shapes.size(), 5u);
  EXPECT_EQ(shapes[0].shape.type, rc::ShapeType::circle);
  EXPECT_EQ(shapes[0].shape.circle.center, (rc::Vec2{0.5f, 0}));
  EXPECT_FLOAT_EQ(shapes[0].def.density, 2);
  EXPECT_FLOAT_EQ(shapes[0].def.friction, 0.1f);
  EXPECT_FLOAT_EQ(shapes[0].def.restitution, 0.9f);
  EXPECT_TRUE(shapes[0].def.isSensor);
  EXPECT_EQ(shapes[0].def.filter.category, 4u);
  EXPECT_EQ(shapes[0].def.filter.mask, 3u);
  EXPECT_EQ(shapes[1].shape.type, rc::ShapeType::polygon);  // a box with an angle
  EXPECT_EQ(shapes[2].shape.type, rc::ShapeType::box);
  EXPECT_EQ(shapes[3].shape.type, rc::ShapeType::polygon);
  EXPECT_FLOAT_EQ(shapes[3].shape.polygon.radius, 0.05f);
  EXPECT_EQ(shapes[4].shape.type, rc::ShapeType::capsule);
  EXPECT_NO_THROW(game::buildWorld(s));
}

// The scene file and the same world built by hand step to the same bits.
TEST(Scene, BuildsTheWorldItDescribes) {
  const char* text = R"({"settings": {"gravity": [0, -10]}, "bodies": [
      {"position": [0, -10], "shapes": [{"type": "box", "halfExtents": [50, 10]}]},
      {"type": "dynamic", "position": [0, 4], "angle": 0.3,
       "shapes": [{"type": "box", "halfExtents": [1, 1], "friction": 0.3}]}]})";
  game::BuiltWorld built = game::buildWorld(game::parseScene(text, "s.json"));
  rc::World hand;
  rc::BodyDef groundDef;
  groundDef.position = {0, -10};
  hand.createShape(hand.createBody(groundDef), rc::makeBox(50, 10));
  rc::BodyDef boxDef;
  boxDef.type = rc::BodyType::dynamicBody;
  boxDef.position = {0, 4};
  boxDef.angle = 0.3f;
  rc::ShapeDef sd;
  sd.friction = 0.3f;
  hand.createShape(hand.createBody(boxDef), rc::makeBox(1, 1), sd);
  for (int i = 0; i < 120; ++i) {
    built.world->step(1.0f / 60.0f);
    hand.step(1.0f / 60.0f);
  }
  EXPECT_EQ(built.world->stateHash(), hand.stateHash());
}

TEST(Scene, OutputsAreWrittenWhole) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ricochet_scene_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "state.json").string();
  game::writeFileAtomically(path, "{}\n");
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "{}\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".part"));
  const std::string bad = (dir / "no such dir" / "state.json").string();
  try {
    game::writeFileAtomically(bad, "{}");
    ADD_FAILURE() << "no error";
  } catch (const game::SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(bad + ": cannot write", 0), 0u) << e.what();
  }
  EXPECT_THROW(game::loadScene((dir / "missing.json").string()), game::SceneError);
  // Why a write failed, from errno: a state written over a directory was "rename from ...part
  // failed" and nothing more.
  std::filesystem::create_directories(dir / "taken");
  try {
    game::writeFileAtomically((dir / "taken").string(), "{}");
    ADD_FAILURE() << "no error";
  } catch (const game::SceneError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "taken").string() + ": cannot write: rename from " +
                                         (dir / "taken").string() + ".part failed: Is a directory");
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "taken.part"));
  try {
    game::writeFileAtomically(bad, "{}");
    ADD_FAILURE() << "no error";
  } catch (const game::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(".part: No such file or directory"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace scene_test

namespace scene_test {

// Hostile scene files (issue 24): each gets one line naming the file and what is wrong, in
// bounded time and memory, never a crash.
TEST(Scene, HostileInputGetsOneLine) {
  // 100,000 levels of nesting crashed the error path (a recursive dump) with SIGSEGV.
  const std::string deep =
      R"({"bodies": [{"position": )" + std::string(100000, '[') + std::string(100000, ']') + "}]}";
  EXPECT_EQ(errorOf(deep), "s.json: not a scene: JSON nested deeper than 32 levels");
  // A key twice in one object was silently last-wins.
  EXPECT_EQ(errorOf(R"({"bodies": [], "bodies": []})"),
            "s.json: the key \"bodies\" appears twice in one object");
  EXPECT_EQ(errorOf(R"({"bodies": [{"type": "dynamic", "angle": 1, "angle": 2}]})"),
            "s.json: the key \"angle\" appears twice in one object");
  // 1e308 is finite: it is beyond float range, and the message says so.
  EXPECT_EQ(errorOf(R"({"bodies": [{"type": "dynamic", "angle": 1e308}]})"),
            "s.json: body 0, angle: is beyond the float range (3.4e38), got 1e+308");
  // A name with a newline and an ANSI escape stays on one line, quoted and escaped; a long one
  // is cut.
  const std::string message = errorOf("{\"bodies\": [{\"name\": \"a\\nb\\u001b[31m" +
                                      std::string(1000000, 'x') + "\", \"type\": \"wobbly\"}]}");
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_EQ(message.find('\x1b'), std::string::npos);
  EXPECT_LT(message.size(), 200u) << message;
  EXPECT_EQ(message.rfind("s.json: body 0 (\"a\\x0ab\\x1b[31mxxx", 0), 0u) << message;
  // An unknown key of 63 bytes, cut to 60 plus "...", is as long as itself quoted: it must still
  // be quoted, not shown raw with its newline and escape.
  const std::string key = std::string(60, 'k') + "\\n\\u001b[";
  const std::string unknown =
      errorOf("{\"bodies\": [{\"type\": \"dynamic\", \"" + key + "\": 1}]}");
  EXPECT_EQ(unknown.find('\n'), std::string::npos) << unknown;
  EXPECT_EQ(unknown.find('\x1b'), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("kkk..."), std::string::npos) << unknown;
  // A value shown in a message: characters past ASCII as \uXXXX, so a C1 CSI stays text and a
  // cut at 40 characters never splits one.
  const std::string csi = errorOf(R"({"bodies": [{"type": "\u009b31m\u00e9\u00e9"}]})");
  EXPECT_EQ(csi.find("\xc2\x9b"), std::string::npos) << csi;
  EXPECT_NE(csi.find(R"(got "\u009b31m\u00e9\u00e9")"), std::string::npos) << csi;
  // Larger than the limit: refused before parsing.
  EXPECT_EQ(errorOf(std::string(game::kMaxSceneBytes + 1, ' ')),
            "s.json: the file is larger than 32 MiB");
}

TEST(Scene, MissingFileAndDirectoryAreNamed) {
  auto loadError = [](const std::string& path) {
    try {
      game::loadScene(path);
    } catch (const game::SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  EXPECT_EQ(loadError(dir.string()), dir.string() + ": cannot open the file: it is a directory");
  EXPECT_EQ(loadError((dir / "no_such_scene.json").string()),
            (dir / "no_such_scene.json").string() + ": cannot open the file: it does not exist");
  // A device or a pipe has no size to check: /dev/zero was read until memory ran out, and a
  // FIFO with no writer waited for ever.
  EXPECT_EQ(loadError("/dev/zero"), "/dev/zero: cannot open the file: it is not a regular file");
  const std::filesystem::path fifo = dir / ("ricochet_scene_fifo_" + std::to_string(::getpid()));
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(loadError(fifo.string()),
            fifo.string() + ": cannot open the file: it is not a regular file");
  std::filesystem::remove(fifo);
}

// A small valid scene cut short at every byte (a file half copied, a run killed while writing
// it): each prefix is one line naming the file, never another exception or a crash.
TEST(Scene, TruncatedAtEveryByte) {
  const std::string text =
      R"({"settings": {"gravity": [0, -10], "integrator": "rk4", "substeps": 4, "dt": 0.0166,)"
      R"( "sleep": false, "bounds": {"lower": [-50, -50], "upper": [50, 50]}},)"
      R"( "bodies": [{"name": "ground", "position": [0, -1],)"
      R"( "shapes": [{"type": "box", "halfExtents": [20, 1], "friction": 0.5},)"
      R"( {"type": "chain", "points": [[2, 0], [3, 0], [3, 1]], "loop": true}]},)"
      R"( {"name": "ball \u00e9", "type": "dynamic", "position": [0, 4], "angle": 0.5,)"
      R"( "linearVelocity": [1, -2.5e-1], "bullet": true, "shapes": [{"type": "circle",)"
      R"( "radius": 0.5, "density": 2}, {"type": "polygon", "points": [[0, 0], [1, 0], [0, 1]]}]}]})";
  ASSERT_EQ(errorOf(text), "no error");
  for (std::size_t n = 0; n < text.size(); ++n) {
    const std::string message = errorOf(text.substr(0, n));
    EXPECT_EQ(message.rfind("s.json: ", 0), 0u) << n << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << n << ": " << message;
  }
}

// Huge values where small ones belong: one short line each, in bounded time.
TEST(Scene, HugeArraysStringsAndObjects) {
  // A million numbers where a pair belongs: the value shown is cut.
  std::string zeros = "[0";
  for (int i = 0; i < 1000000; ++i)
    zeros += ", 0";
  zeros += "]";
  std::string message = errorOf(R"({"settings": {"gravity": )" + zeros + R"(}, "bodies": []})");
  EXPECT_EQ(message.rfind("s.json: settings, gravity: must be [x, y], got [0,0,0,", 0), 0u)
      << message.substr(0, 200);
  EXPECT_LT(message.size(), 120u);
  // 16 MiB strings as a name and as an unknown key (a key used to be shown whole).
  const std::string huge(16u << 20, 'x');
  message = errorOf(R"({"bodies": [{"name": ")" + huge + R"(", "type": 7}]})");
  EXPECT_EQ(message.rfind("s.json: body 0 (\"xxxxxxxx", 0), 0u) << message.substr(0, 200);
  EXPECT_LT(message.size(), 200u);
  message = errorOf(R"({"bodies": [], ")" + huge + R"(\n": 1})");
  EXPECT_EQ(message.rfind("s.json: \"xxxxxxxx", 0), 0u) << message.substr(0, 200);
  EXPECT_NE(message.find("...\": unknown field"), std::string::npos) << message.substr(0, 200);
  EXPECT_LT(message.size(), 120u);
  EXPECT_EQ(errorOf(R"({"bodies": [], "a\nb": 1})"), "s.json: \"a\\x0ab\": unknown field");
  // 200,000 keys in one object: the duplicate-key check kept each object's keys in a list and
  // took n^2 / 2 comparisons (100,000 keys: 11 s; a 32 MiB file: hours). Now n log n.
  std::string keys = R"({"bodies": [])";
  for (int i = 0; i < 200000; ++i)
    keys += ", \"k" + std::to_string(i) + "\": 0";
  keys += "}";
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(errorOf(keys), "s.json: k0: unknown field");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 10.0);
}

// Shapes outside the quadtree's square are scanned by every query (20,000 circles there: 198
// ms a step instead of 3.5); a scene that gives no bounds gets a square fitted around its
// shapes when they reach past the default one, and keeps the default (and its results) when not.
TEST(Scene, BoundsAreFittedToAScenePastTheDefaultSquare) {
  const rc::AABB defaults = rc::WorldDef{}.bounds;
  const game::SceneDesc far = game::parseScene(R"({"bodies": [
      {"type": "dynamic", "position": [3000, 40], "shapes": [{"type": "circle", "radius": 2}]},
      {"type": "static", "position": [-40, 0], "angle": 0.5,
       "shapes": [{"type": "box", "halfExtents": [30, 1]}]}]})",
                                               "far.json");
  EXPECT_FALSE(far.world.bounds == defaults);
  for (const game::BodyDesc& b : far.bodies) {
    const rc::Transform xf{b.def.position, rc::Rot::fromAngle(b.def.angle)};
    for (const game::ShapeDesc& shape : b.shapes)
      EXPECT_TRUE(far.world.bounds.contains(rc::computeAABB(shape.shape, xf)));
  }
  const game::SceneDesc near = game::parseScene(
      R"({"bodies": [{"type": "dynamic", "position": [500, -500],
                      "shapes": [{"type": "circle", "radius": 1}]}]})",
      "near.json");
  EXPECT_EQ(near.world.bounds, defaults);
  const game::SceneDesc given = game::parseScene(
      R"({"settings": {"bounds": {"lower": [-10, -10], "upper": [10, 10]}},
          "bodies": [{"type": "dynamic", "position": [3000, 0],
                      "shapes": [{"type": "circle", "radius": 1}]}]})",
      "given.json");
  EXPECT_EQ(given.world.bounds, (rc::AABB{{-10, -10}, {10, 10}}));
}

}  // namespace scene_test
