// Run time against error on scenes with an answer, ours and Box2D 2.4.1 on the same axes.
// Each scene is one scene file's text, built in both engines (game/scene.h and
// tests/support/box2d_world.h), run over a ladder of settings that trade time for accuracy:
//   ours    substeps 1..32 at dt 1/60, with semi-implicit Euler, Verlet and RK4
//   Box2D   velocity/position iterations 1/1..32/10 at dt 1/60, 1/120, 1/240, 1/480
// and measured as CPU seconds per simulated second (the stepping alone, best of three
// batches of at least 20 ms) against the scene's error from its closed form:
//   stack       10 boxes on the ground, 10 s: |top box's height - 9.5| + |its drift|
//   pyramid     base 10 (55 boxes), 10 s: the same for the top box (its centre at 9.5 m)
//   bounce      ball dropped from 5 m, e = 0.8: worst |apex_k - e^(2k) h| of 4 bounces
//   slide       box at 5 m/s, mu = 0.5: |distance - v^2 / (2 mu g)| = |d - 2.5 m|
//   cradle      a ball at 5 m/s into a row of 4, e = 1: |v_last - 5| + sum |v_other| after 1.5 s.
//               The balls stand 0.2 m apart, more than a step's travel, so each impact is one
//               pair's: touching balls have no single answer (the rigid contact problem with
//               e = 1 does not hand the momentum on as a real cradle's waves do).
//   torque      free box spun by 3 N m from rest, 2 s: |angle - tau t^2 / (2 I)|
//   drag        projectile at (10, 10) m/s with linear damping 0.5 under g: position after 3 s
//               against x0 + v_inf t + (v0 - v_inf)(1 - e^(-ct)) / c
//   kepler      GM = 1000, a = 10 m, e = 0.6 from periapsis, 3.25 orbits: position error
// Box2D's polygons carry a 0.01 m skin (b2_polygonRadius) around the polygon it is given: in
// the stack and the pyramid its boxes are given 0.01 m smaller (and denser, the same mass), so
// that both engines' boxes have the same surfaces and rest at the same heights (elsewhere the
// skin changes nothing measured, and Box2D's inertia, the core's, would be 2% off).
//
//   ./build/release/tests/contact_precision [--out DIR] [--scenes a,b,...]
// writes DIR/contact_precision.csv (every run), DIR/contact_precision_front.csv (each
// engine's cheapest settings per error: its Pareto front), DIR/contact_precision.png
// (gnuplot, log-log, a panel per scene) and DIR/contact_precision.md (the winners).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "game/scene.h"
#include "support/box2d_world.h"

namespace contact_precision {

using Clock = std::chrono::steady_clock;

// A body's state as both engines give it: origin, angle, velocities.
struct State {
  double x = 0, y = 0, angle = 0, vx = 0, vy = 0, w = 0;
};

// One engine running one scene at one setting.
class Run {
 public:
  virtual ~Run() = default;
  virtual void step() = 0;
  virtual State body(std::size_t i) const = 0;
};

// An extra force the scene file cannot say (Kepler's central attraction): ours as a force
// field at every integrator stage, Box2D's applied before every step at the step's position.
struct CentralForce {
  std::size_t body = 0;
  double gm = 0;  // times the body's mass: F = -GM m r / |r|^3
};

class OursRun final : public Run {
 public:
  OursRun(game::SceneDesc scene, int substeps, rc::Integrator integrator,
          std::optional<CentralForce> central)
      : dt_(scene.dt) {
    scene.world.substeps = substeps;
    scene.world.integrator = integrator;
    built_ = game::buildWorld(scene);
    if (central) {
      const rc::BodyId id = built_.ids[central->body];
      const double gm = central->gm * static_cast<double>(built_.world->mass(id));
      built_.world->addForceField([id, gm](rc::ForceStage& stage) {
        const rc::Vec2 p = stage.center(id);
        const double r2 = double{p.x} * p.x + double{p.y} * p.y, k = -gm / (r2 * std::sqrt(r2));
        stage.addForce(id, {static_cast<float>(k * p.x), static_cast<float>(k * p.y)});
      });
    }
  }
  void step() override { built_.world->step(dt_); }
  State body(std::size_t i) const override {
    const rc::World& w = *built_.world;
    const rc::BodyId id = built_.ids[i];
    const auto p = w.precisePosition(id);
    return {p[0],
            p[1],
            w.angle(id),
            w.linearVelocity(id).x,
            w.linearVelocity(id).y,
            w.angularVelocity(id)};
  }

 private:
  float dt_;
  game::BuiltWorld built_;
};

class Box2DRun final : public Run {
 public:
  Box2DRun(const game::SceneDesc& scene, rc::testing::Box2DScene::Skin skin, float dt,
           int velocityIterations, int positionIterations, std::optional<CentralForce> central)
      : scene_(scene, skin),
        dt_(dt),
        velocity_(velocityIterations),
        position_(positionIterations),
        central_(central) {}
  void step() override {
    if (central_) {
      b2Body* b = scene_.bodies[central_->body];
      const b2Vec2 p = b->GetWorldCenter();
      const double r2 = double{p.x} * p.x + double{p.y} * p.y,
                   k = -central_->gm * b->GetMass() / (r2 * std::sqrt(r2));
      b->ApplyForceToCenter(b2Vec2(static_cast<float>(k * p.x), static_cast<float>(k * p.y)), true);
    }
    scene_.step(dt_, velocity_, position_);
  }
  State body(std::size_t i) const override {
    const b2Body* b = scene_.bodies[i];
    return {b->GetPosition().x,       b->GetPosition().y,       b->GetAngle(),
            b->GetLinearVelocity().x, b->GetLinearVelocity().y, b->GetAngularVelocity()};
  }

 private:
  rc::testing::Box2DScene scene_;
  float dt_;
  int velocity_, position_;
  std::optional<CentralForce> central_;
};

// What a scene measures: told the state after every step, asked for the error at the end.
class Judge {
 public:
  virtual ~Judge() = default;
  virtual void afterStep(double /*time*/, const Run& /*run*/) {}
  virtual double error(const Run& run) const = 0;
};

struct Scene {
  std::string name, title;
  std::string text;  // the scene file
  double duration;   // simulated seconds
  std::optional<CentralForce> central;
  std::function<std::unique_ptr<Judge>()> judge;
  bool skinInside = false;  // Box2D's boxes given smaller by its skin
  // Errors below this are float rounding (the quantity's size in ulps times the steps), not
  // the method's: counted as equal when settings are compared.
  double floor = 0;
};

constexpr double kG = 10.0;

// Top box of a stack or pyramid: its height against the geometry's, and its sideways drift.
class TopBox final : public Judge {
 public:
  TopBox(std::size_t body, double height) : body_(body), height_(height) {}
  double error(const Run& run) const override {
    const State s = run.body(body_);
    return std::abs(s.y - height_) + std::abs(s.x);
  }

 private:
  std::size_t body_;
  double height_;
};

// Apex heights of a bouncing ball from the state in flight (y + vy^2 / 2g is exact between
// bounces, so the apex is not rounded to a step), against e^(2k) h.
class Bounce final : public Judge {
 public:
  void afterStep(double, const Run& run) override {
    const State s = run.body(1);
    if (s.vy > 0) rising_ = true;
    if (rising_ && s.vy <= 0 && apexes_.size() < 4) {
      apexes_.push_back(previous_.y + previous_.vy * previous_.vy / (2 * kG) - 0.5);
      rising_ = false;
    }
    previous_ = s;
  }
  double error(const Run&) const override {
    if (apexes_.size() < 4) return 1.0;  // lost a bounce: as bad as it gets at this scale
    double worst = 0;
    for (std::size_t k = 0; k < 4; ++k)
      worst = std::max(
          worst, std::abs(apexes_[k] - 5.0 * std::pow(0.8, 2.0 * static_cast<double>(k + 1))));
    return worst;
  }

 private:
  bool rising_ = false;
  State previous_;
  std::vector<double> apexes_;
};

class Slide final : public Judge {
 public:
  double error(const Run& run) const override {
    return std::abs(run.body(1).x - 25.0 / (2 * 0.5 * kG));
  }
};

class Cradle final : public Judge {
 public:
  double error(const Run& run) const override {
    double e = std::abs(run.body(4).vx - 5.0);
    for (std::size_t i = 0; i < 4; ++i)
      e += std::hypot(run.body(i).vx, run.body(i).vy);
    return e;
  }
};

class Torque final : public Judge {
 public:
  double error(const Run& run) const override {
    // A 2 x 1 box of density 1: m = 2, I = m (4 + 1) / 12.
    const double inertia = 2.0 * 5.0 / 12.0, t = 2.0;
    return std::abs(run.body(0).angle - 3.0 * t * t / (2 * inertia));
  }
};

class Drag final : public Judge {
 public:
  double error(const Run& run) const override {
    const double c = 0.5, t = 3.0, vInf = -kG / c, decay = (1 - std::exp(-c * t)) / c;
    const double x = 10.0 * decay, y = vInf * t + (10.0 - vInf) * decay;
    const State s = run.body(0);
    return std::hypot(s.x - x, s.y - y);
  }
};

// Kepler's orbit of GM = 1000, a = 10 m, e = 0.6 from periapsis on the +x axis: the position
// at time t from Kepler's equation E - e sin E = n t, solved by Newton's method.
constexpr double kGm = 1000, kA = 10, kEcc = 0.6;
class Kepler final : public Judge {
 public:
  double error(const Run& run) const override {
    const double n = std::sqrt(kGm / (kA * kA * kA)), m = n * duration();
    double e = m;
    for (int k = 0; k < 50; ++k)
      e -= (e - kEcc * std::sin(e) - m) / (1 - kEcc * std::cos(e));
    const double x = kA * (std::cos(e) - kEcc), y = kA * std::sqrt(1 - kEcc * kEcc) * std::sin(e);
    const State s = run.body(0);
    return std::hypot(s.x - x, s.y - y);
  }
  static double duration() { return 3.25 * 2 * std::numbers::pi * std::sqrt(kA * kA * kA / kGm); }
};

const char* kGround = R"({"position": [0, -1], "shapes": [{"type": "box", "halfExtents": [50, 1],
    "friction": 0.6}]})";

std::vector<Scene> scenes() {
  std::vector<Scene> out;
  const std::string open = R"({"settings": {"sleep": false}, "bodies": [)";
  {
    std::string text = open + kGround;
    for (int k = 0; k < 10; ++k)
      text += R"(, {"type": "dynamic", "position": [0, )" + std::to_string(0.5 + k) +
              R"(], "shapes": [{"type": "box", "halfExtents": [0.5, 0.5], "friction": 0.6}]})";
    out.push_back({"stack", "stack of 10 boxes, 10 s: top box's |height error| + |drift|",
                   text + "]}", 10.0, std::nullopt,
                   [] { return std::make_unique<TopBox>(10, 9.5); }, true});
  }
  {
    std::string text = open + kGround;
    int count = 0;
    for (int row = 0; row < 10; ++row)
      for (int k = 0; k < 10 - row; ++k, ++count)
        text += R"(, {"type": "dynamic", "position": [)" +
                std::to_string(-0.5 * (9 - row) + 1.0 * k) + ", " + std::to_string(0.5 + row) +
                R"(], "shapes": [{"type": "box", "halfExtents": [0.5, 0.5], "friction": 0.6}]})";
    out.push_back(
        {"pyramid", "pyramid of base 10 (55 boxes), 10 s: top box's |height error| + |drift|",
         text + "]}", 10.0, std::nullopt,
         [count] { return std::make_unique<TopBox>(static_cast<std::size_t>(count), 9.5); }, true});
  }
  out.push_back({"bounce", "ball dropped from 5 m, e = 0.8: worst |apex - e^{2k} h| of 4",
                 open + kGround + R"(, {"type": "dynamic", "position": [0, 5.5], "shapes":
                   [{"type": "circle", "radius": 0.5, "restitution": 0.8, "friction": 0}]}]})",
                 6.0, std::nullopt, [] { return std::make_unique<Bounce>(); }});
  out.push_back({"slide", "box sliding at 5 m/s, mu = 0.5: |distance - v^2 / (2 mu g)|",
                 open + R"({"position": [0, -1], "shapes": [{"type": "box", "halfExtents": [50, 1],
         "friction": 0.5}]}, {"type": "dynamic", "position": [0, 0.5], "linearVelocity": [5, 0],
         "shapes": [{"type": "box", "halfExtents": [0.5, 0.5], "friction": 0.5}]}]})",
                 2.0, std::nullopt, [] { return std::make_unique<Slide>(); }});
  {
    std::string text = R"({"settings": {"sleep": false, "gravity": [0, 0]}, "bodies": [)";
    for (int k = 0; k < 5; ++k)
      text += std::string(k ? ", " : "") + R"({"type": "dynamic", "position": [)" +
              std::to_string(k == 0 ? -2.5 : 1.2 * static_cast<double>(k - 1)) +
              R"(, 0], "linearVelocity": [)" + (k == 0 ? "5" : "0") +
              R"(, 0], "shapes": [{"type": "circle", "radius": 0.5, "restitution": 1,
                 "friction": 0}]})";
    out.push_back(
        {"cradle", "a ball at 5 m/s into a row of 4 (0.2 m apart), e = 1: momentum handed on",
         text + "]}", 1.5, std::nullopt, [] { return std::make_unique<Cradle>(); }, false, 1e-5});
  }
  out.push_back({"torque", "free box spun by a constant torque, 2 s: |angle - tau t^2 / (2 I)|",
                 R"({"settings": {"sleep": false, "gravity": [0, 0]}, "bodies": [{"type":
                   "dynamic", "torque": 3, "shapes": [{"type": "box", "halfExtents": [1, 0.5]}]}]})",
                 2.0, std::nullopt, [] { return std::make_unique<Torque>(); }, false, 1e-4});
  out.push_back({"drag", "projectile with linear drag c = 0.5, 3 s: position error",
                 R"({"settings": {"sleep": false}, "bodies": [{"type": "dynamic", "linearDamping":
                   0.5, "linearVelocity": [10, 10], "shapes": [{"type": "circle", "radius":
                   0.1}]}]})",
                 3.0, std::nullopt, [] { return std::make_unique<Drag>(); }});
  {
    const double vPeri = std::sqrt(kGm / kA * (1 + kEcc) / (1 - kEcc));
    out.push_back(
        {"kepler", "Kepler orbit e = 0.6, 3.25 orbits: position error",
         R"({"settings": {"sleep": false, "gravity": [0, 0], "bounds": {"lower":
                     [-64, -64], "upper": [64, 64]}}, "bodies": [{"type": "dynamic",
                     "position": [)" +
             std::to_string(kA * (1 - kEcc)) + R"(, 0], "linearVelocity": [0, )" +
             std::to_string(vPeri) + R"(], "shapes": [{"type": "circle", "radius": 0.1}]}]})",
         Kepler::duration(), CentralForce{0, kGm}, [] { return std::make_unique<Kepler>(); }});
  }
  return out;
}

struct Setting {
  std::string engine;  // "ours" or "box2d"
  std::string label;   // the curve it belongs to in the plot
  int substeps = 0;
  rc::Integrator integrator = rc::Integrator::semiImplicitEuler;
  int velocityIterations = 0, positionIterations = 0;
  float dt = 1.0f / 60.0f;
};

std::vector<Setting> settings() {
  std::vector<Setting> out;
  for (const rc::Integrator m :
       {rc::Integrator::semiImplicitEuler, rc::Integrator::velocityVerlet, rc::Integrator::rk4})
    for (int s = 1; s <= 32; s *= 2) {
      Setting x;
      x.engine = "ours";
      x.label = "ours " + std::string(rc::integratorName(m));
      x.substeps = s;
      x.integrator = m;
      out.push_back(x);
    }
  const std::pair<int, int> iterations[] = {{1, 1}, {2, 1}, {4, 2}, {8, 3}, {16, 6}, {32, 10}};
  for (const int hz : {60, 120, 240, 480})
    for (const auto& [v, p] : iterations) {
      Setting x;
      x.engine = "box2d";
      x.label = "box2d " + std::to_string(hz) + " Hz";
      x.velocityIterations = v;
      x.positionIterations = p;
      x.dt = 1.0f / static_cast<float>(hz);
      out.push_back(x);
    }
  return out;
}

std::unique_ptr<Run> start(const Scene& scene, const game::SceneDesc& desc, const Setting& s) {
  if (s.engine == "ours")
    return std::make_unique<OursRun>(desc, s.substeps, s.integrator, scene.central);
  return std::make_unique<Box2DRun>(desc,
                                    scene.skinInside ? rc::testing::Box2DScene::Skin::inside
                                                     : rc::testing::Box2DScene::Skin::outside,
                                    s.dt, s.velocityIterations, s.positionIterations,
                                    scene.central);
}

struct Result {
  double cost = 0;  // CPU seconds per simulated second
  double error = 0;
};

Result measure(const Scene& scene, const game::SceneDesc& desc, const Setting& s) {
  const long steps = std::lround(scene.duration / s.dt);
  Result r;
  {
    std::unique_ptr<Run> run = start(scene, desc, s);
    std::unique_ptr<Judge> judge = scene.judge();
    for (long k = 0; k < steps; ++k) {
      run->step();
      judge->afterStep(static_cast<double>(k + 1) * s.dt, *run);
    }
    r.error = judge->error(*run);
  }
  double best = 1e300;
  for (int batch = 0; batch < 3; ++batch) {
    double elapsed = 0;
    long done = 0;
    do {
      std::unique_ptr<Run> run = start(scene, desc, s);
      const auto begin = Clock::now();
      for (long k = 0; k < steps; ++k)
        run->step();
      elapsed += std::chrono::duration<double>(Clock::now() - begin).count();
      done += steps;
    } while (elapsed < 0.02);
    best = std::min(best, elapsed / static_cast<double>(done));
  }
  r.cost = best / s.dt;
  return r;
}

struct Row {
  std::string scene;
  Setting setting;
  Result result;
};

// An engine's Pareto front on one scene: its settings that no other of its settings beats on
// both cost and error, cheapest first.
std::vector<Row> front(const std::vector<Row>& rows, const std::string& scene,
                       const std::string& engine) {
  std::vector<Row> mine;
  for (const Row& r : rows)
    if (r.scene == scene && r.setting.engine == engine) mine.push_back(r);
  std::sort(mine.begin(), mine.end(),
            [](const Row& a, const Row& b) { return a.result.cost < b.result.cost; });
  std::vector<Row> out;
  for (const Row& r : mine)
    if (out.empty() || r.result.error < out.back().result.error) out.push_back(r);
  return out;
}

std::string describe(const Setting& s) {
  char text[96];
  if (s.engine == "ours")
    std::snprintf(text, sizeof text, "ours %s, %d substep%s",
                  std::string(rc::integratorName(s.integrator)).c_str(), s.substeps,
                  s.substeps == 1 ? "" : "s");
  else
    std::snprintf(text, sizeof text, "Box2D %d/%d iterations at %.0f Hz", s.velocityIterations,
                  s.positionIterations, 1.0 / s.dt);
  return text;
}

std::string num(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

// Floors the plot and the table at 1e-9: an error of 0 has no place on a log axis.
double shown(double error) {
  return std::max(error, 1e-9);
}

}  // namespace contact_precision

int main(int argc, char** argv) {
  using namespace contact_precision;
  std::string dir = ".", only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--out" || a == "--scenes") && i + 1 < argc) {
      (a == "--out" ? dir : only) = argv[++i];
    } else {
      std::fprintf(stderr, "usage: contact_precision [--out DIR] [--scenes a,b,...]\n");
      return 2;
    }
  }
  std::vector<Scene> all = scenes();
  if (!only.empty()) {
    std::erase_if(all, [&](const Scene& s) {
      return ("," + only + ",").find("," + s.name + ",") == std::string::npos;
    });
    if (all.empty()) {
      std::fprintf(stderr, "contact_precision: no scene named in '%s'\n", only.c_str());
      return 2;
    }
  }
  const std::string csvPath = dir + "/contact_precision.csv",
                    frontPath = dir + "/contact_precision_front.csv",
                    plotPath = dir + "/contact_precision.png",
                    tablePath = dir + "/contact_precision.md";
  std::ofstream csv(csvPath), frontCsv(frontPath);
  if (!csv || !frontCsv) {
    std::fprintf(stderr, "contact_precision: %s: cannot write\n", dir.c_str());
    return 1;
  }
  csv << "scene,engine,curve,substeps,integrator,velocity_iterations,position_iterations,dt,"
         "cpu_s_per_sim_s,error\n";
  std::vector<Row> rows;
  for (const Scene& scene : all) {
    const game::SceneDesc desc = game::parseScene(scene.text, scene.name + ".json");
    for (const Setting& s : settings()) {
      const Result r = measure(scene, desc, s);
      rows.push_back({scene.name, s, {r.cost, std::max(r.error, scene.floor)}});
      char line[256];
      std::snprintf(line, sizeof line, "%s,%s,%s,%d,%s,%d,%d,%.9g,%.4g,%.4g\n", scene.name.c_str(),
                    s.engine.c_str(), s.label.c_str(), s.substeps,
                    s.engine == "ours" ? std::string(rc::integratorName(s.integrator)).c_str() : "",
                    s.velocityIterations, s.positionIterations, s.dt, r.cost, r.error);
      csv << line;
      std::fputs(line, stdout);
    }
  }
  csv.close();
  frontCsv << "scene,engine,cpu_s_per_sim_s,error,setting\n";
  for (const Scene& scene : all)
    for (const char* engine : {"ours", "box2d"})
      for (const Row& r : front(rows, scene.name, engine))
        frontCsv << scene.name << ',' << engine << ',' << r.result.cost << ','
                 << shown(r.result.error) << ',' << describe(r.setting) << '\n';
  frontCsv.close();

  // The winners: at Box2D's best error, what it costs each engine; at the cost Box2D pays for
  // its best, the error each engine reaches.
  std::ofstream md(tablePath);
  md << "| scene | Box2D's best error | its cost (CPU s / sim s) | our error at that cost | "
        "our cost for that error | cost ratio (Box2D / ours) | winner |\n"
     << "|---|---:|---:|---:|---:|---:|---|\n";
  for (const Scene& scene : all) {
    const std::vector<Row> ours = front(rows, scene.name, "ours"),
                           box2d = front(rows, scene.name, "box2d");
    const Row& best = box2d.back();
    double oursAtCost = -1;
    for (const Row& r : ours)
      if (r.result.cost <= best.result.cost) oursAtCost = r.result.error;
    double oursCost = -1;
    for (const Row& r : ours)
      if (r.result.error <= best.result.error) {
        oursCost = r.result.cost;
        break;
      }
    const bool atFloor = best.result.error <= scene.floor;
    md << "| " << scene.name << " | "
       << (atFloor ? "float rounding (< " + num(scene.floor) + ")" : num(best.result.error)) << " ("
       << describe(best.setting) << ") | " << num(best.result.cost) << " | "
       << (oursAtCost < 0 ? "none that cheap" : num(oursAtCost)) << " | "
       << (oursCost < 0 ? "not reached" : num(oursCost)) << " | "
       << (oursCost < 0 ? "-" : num(best.result.cost / oursCost)) << " | "
       << (oursCost >= 0 && oursCost <= best.result.cost ? "ours" : "Box2D") << " |\n";
  }
  // Each engine at its default: ours 4 substeps of semi-implicit Euler, Box2D 8/3 iterations at
  // 60 Hz (its testbed's).
  md << "\n| scene | ours at its default: error | cost | Box2D at its default: error | cost |\n"
     << "|---|---:|---:|---:|---:|\n";
  for (const Scene& scene : all) {
    const Row* ours = nullptr;
    const Row* box2d = nullptr;
    for (const Row& r : rows) {
      if (r.scene != scene.name) continue;
      const Setting& s = r.setting;
      if (s.engine == "ours" && s.substeps == 4 &&
          s.integrator == rc::Integrator::semiImplicitEuler)
        ours = &r;
      if (s.engine == "box2d" && s.velocityIterations == 8 && s.dt == 1.0f / 60.0f) box2d = &r;
    }
    md << "| " << scene.name << " | " << num(ours->result.error) << " | " << num(ours->result.cost)
       << " | " << num(box2d->result.error) << " | " << num(box2d->result.cost) << " |\n";
  }
  md.close();

  const std::string script = plotPath + ".gp";
  std::ofstream gp(script);
  gp << "set terminal pngcairo size 1800,1500 font 'DejaVu Sans,10'\n"
     << "set output '" << plotPath << "'\n"
     << "set datafile separator ','\n"
     << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset grid\n"
     << "set key bottom left font ',8'\n"
     << "set xlabel 'error (closed form)'\nset ylabel 'CPU s per simulated s'\n"
     << "set multiplot layout 3,3 title \"Run time against error: Ricochet and Box2D 2.4.1 "
        "(points: every setting; lines: each engine's cheapest per error)\"\n";
  for (const Scene& scene : all) {
    gp << "set title \"" << scene.title << "\"\n"
       << "plot '" << csvPath << "' using ((strcol(1) eq '" << scene.name
       << "' && strcol(2) eq 'ours') ? ($10 > 1e-9 ? $10 : 1e-9) : 1/0):9 with points pt 7 ps 0.5 "
          "lc rgb '#9ecae1' notitle, '"
       << csvPath << "' using ((strcol(1) eq '" << scene.name
       << "' && strcol(2) eq 'box2d') ? ($10 > 1e-9 ? $10 : 1e-9) : 1/0):9 with points pt 5 "
          "ps 0.5 lc rgb '#fdae6b' notitle, '"
       << frontPath << "' using ((strcol(1) eq '" << scene.name
       << "' && strcol(2) eq 'ours') ? $4 : 1/0):3 with linespoints lw 2 pt 7 lc rgb '#08519c' "
          "title 'Ricochet', '"
       << frontPath << "' using ((strcol(1) eq '" << scene.name
       << "' && strcol(2) eq 'box2d') ? $4 : 1/0):3 with linespoints lw 2 pt 5 lc rgb "
          "'#d94801' title 'Box2D 2.4.1'\n";
  }
  gp << "unset multiplot\n";
  gp.close();
  const std::string command = "gnuplot '" + script + "' 2>/dev/null";
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr,
                 "contact_precision: gnuplot failed or is not installed; the CSVs are in %s\n",
                 dir.c_str());
    return 0;
  }
  std::fprintf(stderr, "contact_precision: wrote %s, %s, %s and %s\n", csvPath.c_str(),
               frontPath.c_str(), plotPath.c_str(), tablePath.c_str());
  return 0;
}
