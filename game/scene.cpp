#include "game/scene.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <vector>

#include "game/input_file.h"
#include "game/json_guard.h"
#include "game/quote.h"
#include "physics/integrate.h"

namespace game {
namespace {

using json = nlohmann::json;

// Where a value sits in the file, for messages: "body 3 ("crate"), shapes[0].radius".
struct Where {
  const std::string& file;
  std::string context;  // "settings" or "body 3 (\"crate\")"
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    std::string where = context;
    if (!field.empty()) where += (where.empty() ? "" : ", ") + field;
    throw SceneError(file + ": " + (where.empty() ? "" : where + ": ") + what);
  }
};

std::string describe(const json& j) {
  return describeJson(j);
}

// An unknown key as a message shows it: as it is when quoting would only add the quotes (a
// typo such as "radiuss"), else quoted, escaped and cut (game/quote.h): a key of a megabyte
// or with a newline in it must not make the line.
std::string fieldName(const std::string& key) {
  return isPlainText(key, '"') ? key : quoteName(key, '"');
}

void onlyKnown(const json& obj, std::initializer_list<const char*> keys, const Where& at,
               const std::string& prefix) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool known = false;
    for (const char* k : keys)
      known = known || it.key() == k;
    if (!known) at.fail(prefix + fieldName(it.key()), "unknown field");
  }
}

const json* find(const json& obj, const char* key) {
  auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

float number(const json& obj, const char* key, float fallback, const Where& at,
             const std::string& prefix, bool required = false) {
  const json* v = find(obj, key);
  if (v == nullptr) {
    if (required) at.fail(prefix + key, "is missing");
    return fallback;
  }
  if (!v->is_number()) at.fail(prefix + key, "must be a number, got " + describe(*v));
  const double d = v->get<double>();
  if (!std::isfinite(d) || std::fabs(d) > 3.0e38)
    at.fail(prefix + key, "is beyond the float range (3.4e38), got " + describe(*v));
  return static_cast<float>(d);
}

rc::Vec2 vec2(const json& v, const Where& at, const std::string& field) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    at.fail(field, "must be [x, y], got " + describe(v));
  const double x = v[0].get<double>(), y = v[1].get<double>();
  if (!std::isfinite(x) || !std::isfinite(y) || std::fabs(x) > 3.0e38 || std::fabs(y) > 3.0e38)
    at.fail(field, "is beyond the float range (3.4e38), got " + describe(v));
  return {static_cast<float>(x), static_cast<float>(y)};
}

rc::Vec2 vec2(const json& obj, const char* key, rc::Vec2 fallback, const Where& at,
              const std::string& prefix, bool required = false) {
  const json* v = find(obj, key);
  if (v == nullptr) {
    if (required) at.fail(prefix + key, "is missing");
    return fallback;
  }
  return vec2(*v, at, prefix + key);
}

bool boolean(const json& obj, const char* key, bool fallback, const Where& at,
             const std::string& prefix) {
  const json* v = find(obj, key);
  if (v == nullptr) return fallback;
  if (!v->is_boolean()) at.fail(prefix + key, "must be true or false, got " + describe(*v));
  return v->get<bool>();
}

std::uint32_t bits(const json& obj, const char* key, std::uint32_t fallback, const Where& at,
                   const std::string& prefix) {
  const json* v = find(obj, key);
  if (v == nullptr) return fallback;
  if (!v->is_number_unsigned() || v->get<std::uint64_t>() > 0xFFFFFFFFull)
    at.fail(prefix + key, "must be an integer from 0 to 4294967295, got " + describe(*v));
  return static_cast<std::uint32_t>(v->get<std::uint64_t>());
}

std::vector<rc::Vec2> points(const json& obj, const Where& at, const std::string& prefix) {
  const json* v = find(obj, "points");
  if (v == nullptr) at.fail(prefix + "points", "is missing");
  if (!v->is_array()) at.fail(prefix + "points", "must be an array of [x, y]");
  std::vector<rc::Vec2> out;
  for (std::size_t i = 0; i < v->size(); ++i)
    out.push_back(vec2((*v)[i], at, prefix + "points[" + std::to_string(i) + "]"));
  return out;
}

void parseShape(const json& j, BodyDesc& body, const Where& at, const std::string& prefix) {
  if (!j.is_object()) at.fail(prefix.substr(0, prefix.size() - 1), "must be an object");
  const json* typeField = find(j, "type");
  if (typeField == nullptr || !typeField->is_string())
    at.fail(prefix + "type", "must be one of circle, box, polygon, capsule, segment, chain");
  const std::string type = typeField->get<std::string>();
  rc::ShapeDef def;
  def.density = number(j, "density", def.density, at, prefix);
  def.friction = number(j, "friction", def.friction, at, prefix);
  def.restitution = number(j, "restitution", def.restitution, at, prefix);
  def.isSensor = boolean(j, "sensor", false, at, prefix);
  def.filter.category = bits(j, "category", def.filter.category, at, prefix);
  def.filter.mask = bits(j, "mask", def.filter.mask, at, prefix);
  const auto materials = {"type",   "density",  "friction", "restitution",
                          "sensor", "category", "mask"};
  auto known = [&](std::initializer_list<const char*> own) {
    std::vector<const char*> all(materials);
    all.insert(all.end(), own.begin(), own.end());
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      for (const char* k : all)
        ok = ok || it.key() == k;
      if (!ok) at.fail(prefix + fieldName(it.key()), "unknown field for a " + type);
    }
  };
  try {
    if (type == "circle") {
      known({"center", "radius"});
      body.shapes.push_back({rc::makeCircle(vec2(j, "center", {}, at, prefix),
                                            number(j, "radius", 0, at, prefix, true)),
                             def});
    } else if (type == "box") {
      known({"halfExtents", "center", "angle"});
      const rc::Vec2 half = vec2(j, "halfExtents", {}, at, prefix, true);
      const rc::Vec2 center = vec2(j, "center", {}, at, prefix);
      const float angle = number(j, "angle", 0, at, prefix);
      if (angle == 0.0f)
        body.shapes.push_back({rc::makeBox(half.x, half.y, center), def});
      else
        body.shapes.push_back({rc::makeOrientedBox(half.x, half.y, center, angle), def});
    } else if (type == "polygon") {
      known({"points", "radius"});
      const std::vector<rc::Vec2> pts = points(j, at, prefix);
      body.shapes.push_back({rc::makePolygon(pts, number(j, "radius", 0, at, prefix)), def});
    } else if (type == "capsule") {
      known({"center1", "center2", "radius"});
      body.shapes.push_back({rc::makeCapsule(vec2(j, "center1", {}, at, prefix, true),
                                             vec2(j, "center2", {}, at, prefix, true),
                                             number(j, "radius", 0, at, prefix, true)),
                             def});
    } else if (type == "segment") {
      known({"point1", "point2"});
      body.shapes.push_back({rc::makeSegment(vec2(j, "point1", {}, at, prefix, true),
                                             vec2(j, "point2", {}, at, prefix, true)),
                             def});
    } else if (type == "chain") {
      known({"points", "loop", "oneSided"});
      const std::vector<rc::Vec2> pts = points(j, at, prefix);
      for (const rc::ChainSegment& link : rc::makeChain(pts, boolean(j, "loop", false, at, prefix),
                                                        boolean(j, "oneSided", false, at, prefix)))
        body.shapes.push_back({link, def});
    } else {
      at.fail(prefix + "type",
              "must be one of circle, box, polygon, capsule, segment, chain; got " +
                  quoteName(type, '"'));
    }
  } catch (const rc::InvalidShape& e) {
    at.fail(prefix.substr(0, prefix.size() - 1), e.what());
  }
}

rc::BodyType bodyType(const json& j, const Where& at) {
  const json* v = find(j, "type");
  if (v == nullptr) return rc::BodyType::staticBody;
  const std::string t = v->is_string() ? v->get<std::string>() : "";
  if (t == "static") return rc::BodyType::staticBody;
  if (t == "kinematic") return rc::BodyType::kinematicBody;
  if (t == "dynamic") return rc::BodyType::dynamicBody;
  at.fail("type", "must be \"static\", \"kinematic\" or \"dynamic\", got " + describe(*v));
}

void parseSettings(const json& j, SceneDesc& scene, const std::string& file) {
  const Where at{file, "settings"};
  if (!j.is_object()) at.fail("", "must be an object");
  onlyKnown(j,
            {"gravity", "integrator", "substeps", "dt", "restitutionThreshold", "hitEventThreshold",
             "contactHertz", "contactDampingRatio", "maxPushoutSpeed", "contactRecycleDistance",
             "stackSolveDepth", "continuous", "sleep", "bounds"},
            at, "");
  rc::WorldDef& w = scene.world;
  w.gravity = vec2(j, "gravity", w.gravity, at, "");
  if (const json* v = find(j, "integrator")) {
    const auto m = v->is_string() ? rc::parseIntegrator(v->get<std::string>()) : std::nullopt;
    if (!m)
      at.fail(
          "integrator",
          "must be one of explicit-euler, semi-implicit-euler, verlet, rk4; got " + describe(*v));
    w.integrator = *m;
  }
  if (const json* v = find(j, "substeps")) {
    if (!v->is_number_integer() || v->get<long long>() < 1 || v->get<long long>() > 64)
      at.fail("substeps", "must be an integer from 1 to 64, got " + describe(*v));
    w.substeps = static_cast<int>(v->get<long long>());
  }
  scene.dt = number(j, "dt", scene.dt, at, "");
  if (!(scene.dt > 0.0f)) at.fail("dt", "must be > 0");
  w.restitutionThreshold = number(j, "restitutionThreshold", w.restitutionThreshold, at, "");
  w.hitEventThreshold = number(j, "hitEventThreshold", w.hitEventThreshold, at, "");
  w.contactHertz = number(j, "contactHertz", w.contactHertz, at, "");
  w.contactDampingRatio = number(j, "contactDampingRatio", w.contactDampingRatio, at, "");
  w.maxPushoutSpeed = number(j, "maxPushoutSpeed", w.maxPushoutSpeed, at, "");
  w.contactRecycleDistance = number(j, "contactRecycleDistance", w.contactRecycleDistance, at, "");
  if (const json* v = find(j, "stackSolveDepth")) {
    if (!v->is_number_integer() || v->get<long long>() < 0 ||
        v->get<long long>() > rc::kMaxStackSolveDepth)
      at.fail("stackSolveDepth", "must be an integer from 0 to " +
                                     std::to_string(rc::kMaxStackSolveDepth) + ", got " +
                                     describe(*v));
    w.stackSolveDepth = static_cast<int>(v->get<long long>());
  }
  w.continuous = boolean(j, "continuous", w.continuous, at, "");
  w.enableSleep = boolean(j, "sleep", w.enableSleep, at, "");
  if (const json* b = find(j, "bounds")) {
    if (!b->is_object()) at.fail("bounds", "must be {\"lower\": [x, y], \"upper\": [x, y]}");
    onlyKnown(*b, {"lower", "upper"}, at, "bounds.");
    w.bounds = {vec2(*b, "lower", {}, at, "bounds.", true),
                vec2(*b, "upper", {}, at, "bounds.", true)};
    if (!w.bounds.isValid() || w.bounds.lower == w.bounds.upper)
      at.fail("bounds", "lower must be below upper");
  }
}

BodyDesc parseBody(const json& j, std::size_t index, const std::string& file) {
  std::string name;
  if (j.is_object())
    if (const json* n = find(j, "name"); n != nullptr && n->is_string())
      name = n->get<std::string>();
  const Where at{file, "body " + std::to_string(index) +
                           (name.empty() ? "" : " (" + quoteName(name, '"') + ")")};
  if (!j.is_object()) at.fail("", "must be an object");
  onlyKnown(j,
            {"name", "type", "position", "angle", "linearVelocity", "angularVelocity",
             "linearDamping", "angularDamping", "gravityScale", "fixedRotation", "bullet",
             "allowSleep", "force", "forcePoint", "torque", "shapes"},
            at, "");
  if (const json* n = find(j, "name"); n != nullptr && !n->is_string())
    at.fail("name", "must be a string");
  BodyDesc body;
  body.name = name;
  rc::BodyDef& d = body.def;
  d.type = bodyType(j, at);
  d.position = vec2(j, "position", d.position, at, "");
  d.angle = number(j, "angle", d.angle, at, "");
  d.linearVelocity = vec2(j, "linearVelocity", d.linearVelocity, at, "");
  d.angularVelocity = number(j, "angularVelocity", d.angularVelocity, at, "");
  d.linearDamping = number(j, "linearDamping", d.linearDamping, at, "");
  d.angularDamping = number(j, "angularDamping", d.angularDamping, at, "");
  d.gravityScale = number(j, "gravityScale", d.gravityScale, at, "");
  d.fixedRotation = boolean(j, "fixedRotation", d.fixedRotation, at, "");
  d.bullet = boolean(j, "bullet", d.bullet, at, "");
  d.allowSleep = boolean(j, "allowSleep", d.allowSleep, at, "");
  body.force = vec2(j, "force", {}, at, "");
  body.torque = number(j, "torque", 0, at, "");
  if (find(j, "forcePoint") != nullptr) {
    body.forcePoint = vec2(j, "forcePoint", {}, at, "");
    if (body.force == rc::Vec2{}) at.fail("forcePoint", "is given without a force");
  }
  // Box2D ignores a force on a body that is not dynamic; here it is a mistake in the file.
  if (body.pushed() && d.type != rc::BodyType::dynamicBody)
    at.fail(body.force == rc::Vec2{} ? "torque" : "force", "acts on dynamic bodies only");
  const json* shapes = find(j, "shapes");
  if (shapes != nullptr) {
    if (!shapes->is_array()) at.fail("shapes", "must be an array");
    for (std::size_t s = 0; s < shapes->size(); ++s)
      parseShape((*shapes)[s], body, at, "shapes[" + std::to_string(s) + "].");
  }
  return body;
}

}  // namespace

namespace {

// A scene that gives no bounds and reaches beyond the default square gets a square fitted around
// its shapes, as a level does (levelWorldDef): shapes outside the quadtree's square sit in a
// list every query scans, and 20,000 circles there made each step about 9x slower. A scene
// inside the default square keeps it, and so its results.
void fitBounds(SceneDesc& scene) {
  bool any = false;
  rc::AABB extent;
  for (const BodyDesc& b : scene.bodies) {
    const rc::Transform xf{b.def.position, rc::Rot::fromAngle(b.def.angle)};
    for (const ShapeDesc& s : b.shapes) {
      const rc::AABB box = rc::computeAABB(s.shape, xf);
      extent = any ? rc::unionOf(extent, box) : box;
      any = true;
    }
  }
  if (!any || scene.world.bounds.contains(extent)) return;
  const float side = std::max(extent.upper.x - extent.lower.x, extent.upper.y - extent.lower.y);
  // At least the default square's size: a small far cluster has room to move and fall.
  const float half = std::max(0.75f * side + 1.0f, 512.0f);
  const rc::Vec2 c = extent.center();
  if (!std::isfinite(half) || !std::isfinite(c.x + half) || !std::isfinite(c.y + half) ||
      !std::isfinite(c.x - half) || !std::isfinite(c.y - half))
    return;  // beyond float range: the default square, and the outside list, it is
  scene.world.bounds = {{c.x - half, c.y - half}, {c.x + half, c.y + half}};
}

}  // namespace

SceneDesc parseScene(std::string_view text, const std::string& name) {
  if (text.size() > kMaxSceneBytes)
    throw SceneError(name + ": the file is larger than " + std::to_string(kMaxSceneBytes >> 20) +
                     " MiB");
  // The parser's callback sees every value as it opens and every key (game/json_guard.h):
  // refusing depth here bounds the parser's stack and every later walk of the tree (an error
  // message renders the offending value); a key seen twice in one object is refused rather than
  // silently taking the last one.
  JsonGuard limits(kMaxSceneDepth);
  const json::parser_callback_t guard = [&](int depth, json::parse_event_t event, json& value) {
    switch (limits.check(depth, event, value)) {
      case JsonGuard::Problem::tooDeep:
        throw SceneError(name + ": not a scene: JSON nested deeper than " +
                         std::to_string(kMaxSceneDepth) + " levels");
      case JsonGuard::Problem::duplicateKey:
        throw SceneError(name + ": the key " + quoteName(value.get<std::string>(), '"') +
                         " appears twice in one object");
      case JsonGuard::Problem::none:
        break;
    }
    return true;
  };
  json root;
  try {
    root = json::parse(text.begin(), text.end(), guard);
  } catch (const json::exception& e) {
    // nlohmann's messages: "[json.exception.parse_error.101] parse error at line L, column
    // C: what", or "[json.exception.out_of_range.406] number overflow parsing '1e999'". Keep
    // what follows its tag.
    std::string what = e.what();
    const auto line = what.find("line "), tag = what.find("] ");
    if (line != std::string::npos)
      throw SceneError(name + ": not valid JSON at " + what.substr(line));
    throw SceneError(
        name + ": not valid JSON: " + (tag == std::string::npos ? what : what.substr(tag + 2)));
  }
  const Where at{name, ""};
  if (!root.is_object()) at.fail("", "the top level must be an object with \"bodies\"");
  onlyKnown(root, {"settings", "bodies"}, at, "");
  SceneDesc scene;
  scene.source = name;
  if (const json* s = find(root, "settings")) parseSettings(*s, scene, name);
  const json* bodies = find(root, "bodies");
  if (bodies == nullptr || !bodies->is_array()) at.fail("bodies", "must be an array");
  for (std::size_t i = 0; i < bodies->size(); ++i)
    scene.bodies.push_back(parseBody((*bodies)[i], i, name));
  const json* settings = find(root, "settings");
  if (settings == nullptr || find(*settings, "bounds") == nullptr) fitBounds(scene);
  return scene;
}

SceneDesc loadScene(const std::string& path) {
  // The size refused before reading: the parsed tree takes about ten times the file.
  std::string text;
  if (const auto why = readInputFile(path, kMaxSceneBytes, text))
    throw SceneError(path + ": " + *why);
  return parseScene(text, path);
}

BuiltWorld buildWorld(const SceneDesc& scene) {
  BuiltWorld built;
  built.world = std::make_unique<rc::World>(scene.world);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    try {
      const rc::BodyId id = built.world->createBody(b.def);
      for (const ShapeDesc& s : b.shapes)
        built.world->createShape(id, s.shape, s.def);
      built.ids.push_back(id);
    } catch (const rc::InvalidDefinition& e) {
      // The world says "body: field ..." or "shape: ..."; the scene says which body.
      std::string what = e.what();
      if (what.rfind("body: ", 0) == 0) what = what.substr(6);
      throw SceneError(scene.source + ": body " + std::to_string(i) +
                       (b.name.empty() ? "" : " (" + quoteName(b.name, '"') + ")") + ": " + what);
    }
  }
  // The pushed bodies, their forces and where each acts relative to the centre of mass in the
  // body's frame (the stage gives the centre and the angle).
  struct Push {
    rc::BodyId id;
    rc::Vec2 force, offset;
    float torque;
    bool atPoint;
  };
  std::vector<Push> pushes;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    if (!b.pushed()) continue;
    const rc::BodyId id = built.ids[i];
    rc::Vec2 offset{};
    if (b.forcePoint) {
      const rc::Transform xf = built.world->transform(id);
      offset = *b.forcePoint - rc::invRotate(xf.q, built.world->worldCenter(id) - xf.p);
    }
    pushes.push_back({id, b.force, offset, b.torque, b.forcePoint.has_value()});
  }
  if (!pushes.empty())
    built.world->addForceField([pushes = std::move(pushes)](rc::ForceStage& stage) {
      for (const Push& p : pushes) {
        if (p.atPoint) {
          const rc::Vec2 point =
              stage.center(p.id) + rc::rotate(rc::Rot::fromAngle(stage.angle(p.id)), p.offset);
          stage.addForceAt(p.id, p.force, point);
        } else if (p.force != rc::Vec2{}) {
          stage.addForce(p.id, p.force);
        }
        if (p.torque != 0.0f) stage.addTorque(p.id, p.torque);
      }
    });
  return built;
}

SceneState captureState(const SceneDesc& scene, const BuiltWorld& built, int steps) {
  SceneState state;
  state.engine = "ricochet";
  state.steps = steps;
  state.time = built.world->time();
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx",
                static_cast<unsigned long long>(built.world->stateHash()));
  state.hash = hash;
  for (std::size_t i = 0; i < built.ids.size(); ++i) {
    const rc::BodyId id = built.ids[i];
    state.bodies.push_back({scene.bodies[i].name, built.world->position(id), built.world->angle(id),
                            built.world->linearVelocity(id), built.world->angularVelocity(id)});
  }
  return state;
}

std::string stateToJson(const SceneState& state) {
  json bodies = json::array();
  for (const BodyState& b : state.bodies)
    bodies.push_back({{"name", b.name},
                      {"position", {b.position.x, b.position.y}},
                      {"angle", b.angle},
                      {"linearVelocity", {b.linearVelocity.x, b.linearVelocity.y}},
                      {"angularVelocity", b.angularVelocity}});
  json root = {{"engine", state.engine},
               {"steps", state.steps},
               {"time", state.time},
               {"hash", state.hash},
               {"bodies", bodies}};
  return root.dump(1) + "\n";
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".part";
  // Each failure says why, from the errno of the call that failed ("No such file or directory",
  // "Is a directory", "No space left on device"), and leaves no temporary file behind.
  auto fail = [&](const std::string& what, int error, bool made) {
    if (made) std::remove(temporary.c_str());
    throw SceneError(path + ": cannot write: " + what + ": " + std::strerror(error));
  };
  std::FILE* out = std::fopen(temporary.c_str(), "wb");
  if (out == nullptr) fail("cannot create " + temporary, errno, false);
  errno = 0;
  const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size();
  const int writeError = errno;
  const bool closed = std::fclose(out) == 0;  // the last flush: a full disk may show only here
  if (!written || !closed)
    fail("writing " + temporary + " failed", written ? errno : writeError, true);
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
    fail("rename from " + temporary + " failed", errno, true);
}

}  // namespace game
