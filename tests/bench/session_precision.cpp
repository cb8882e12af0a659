// Run time against error on a real workload: a recorded match (bots, players, crates,
// grenades on a Tiled level), replayed with the physics at a ladder of settings.
//
// A match is chaotic (a bot that turns a tick earlier fires another shot), so one long run at
// two settings ends in two different matches and their distance says nothing of accuracy.
// Instead the recording is played once at the reference setting (32 substeps of semi-implicit
// Euler), saving the match at the start of each window; each setting then restarts from each
// saved state (World::setStepping after the restore), plays the window's ticks with the
// recorded inputs, and is compared with the reference at the window's end: the error is the
// root mean square distance of the dynamic bodies' positions, averaged over the windows (the
// median and the worst window too). The cost is the physics phase's CPU time per simulated
// second (MatchProfile), the least of three passes. The reference
// setting itself is run too: its error must be exactly 0 (restores are exact), a check of the
// method.
//
//   ./build/release/tests/session_precision [RECORDING] [--window TICKS] [--windows N]
//                                           [--out DIR]
// (default assets/sessions/arena.rec, windows of 15 ticks, 200 of them spread over the
// recording: short enough that a bot seldom decides otherwise within one) writes
// DIR/session_precision.csv, .png (gnuplot) and .md.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "game/match/match.h"
#include "game/match/match_snapshot.h"
#include "game/session/recording.h"
#include "game/session/replay.h"

namespace session_precision {

struct Setting {
  int substeps;
  rc::Integrator integrator;
};

constexpr Setting kReference{32, rc::Integrator::semiImplicitEuler};

// Dynamic bodies' positions by body id (ids are kept by snapshots, so the same body has the
// same id in the reference and in a restored match).
using Positions = std::map<std::uint64_t, std::array<double, 2>>;

Positions positions(const rc::World& world) {
  Positions out;
  for (const rc::BodyId id : world.bodies())
    if (world.type(id) == rc::BodyType::dynamicBody && world.isEnabled(id))
      out[(std::uint64_t{id.generation} << 32) | static_cast<std::uint32_t>(id.index)] =
          world.precisePosition(id);
  return out;
}

// RMS distance over the bodies in both (a body made or destroyed by only one of them, a grenade
// thrown a tick apart, is a difference of events, counted apart).
struct Distance {
  double rms = 0;
  int onlyInOne = 0;
};
Distance distance(const Positions& a, const Positions& b) {
  double sum = 0;
  int n = 0, only = 0;
  for (const auto& [id, p] : a) {
    const auto it = b.find(id);
    if (it == b.end()) {
      ++only;
      continue;
    }
    const double dx = p[0] - it->second[0], dy = p[1] - it->second[1];
    sum += dx * dx + dy * dy;
    ++n;
  }
  for (const auto& [id, p] : b)
    if (a.find(id) == a.end()) ++only;
  return {n > 0 ? std::sqrt(sum / n) : 0.0, only};
}

std::string name(const Setting& s) {
  return std::string(rc::integratorName(s.integrator)) + " x" + std::to_string(s.substeps);
}

}  // namespace session_precision

int main(int argc, char** argv) {
  using namespace session_precision;
  std::string path = "assets/sessions/arena.rec", dir = ".";
  long window = 15, windows = 200;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if ((a == "--window" || a == "--windows") && i + 1 < argc) {
      const std::string_view v = argv[++i];
      long& target = a == "--window" ? window : windows;
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), target);
      if (ec != std::errc() || end != v.data() + v.size() || target < 1) {
        std::fprintf(stderr, "session_precision: %s must be a whole number >= 1\n", argv[i - 1]);
        return 2;
      }
    } else if (a == "--out" && i + 1 < argc) {
      dir = argv[++i];
    } else if (!a.empty() && a[0] != '-') {
      path = std::string(a);
    } else {
      std::fprintf(stderr,
                   "usage: session_precision [RECORDING] [--window TICKS] [--windows N] "
                   "[--out DIR]\n");
      return 2;
    }
  }
  try {
    const game::Recording recording = game::loadRecording(path);
    game::ReplaySetup setup(recording);
    game::MatchConfig config = setup.config();
    config.profile = true;
    const std::int64_t ticks = recording.ticks;
    if (ticks < window) {
      std::fprintf(stderr, "session_precision: %s: %lld ticks, fewer than a window\n", path.c_str(),
                   static_cast<long long>(ticks));
      return 1;
    }
    // Window starts spread evenly over the recording.
    std::vector<std::int64_t> starts;
    const std::int64_t room = ticks - window;
    for (long k = 0; k < windows; ++k)
      starts.push_back(windows == 1 ? 0 : room * k / (windows - 1));
    starts.erase(std::unique(starts.begin(), starts.end()), starts.end());

    // The reference run: the state at each window's start and its bodies at the window's end.
    game::Match reference(setup.level(), config);
    reference.state().world->setStepping(kReference.substeps, kReference.integrator);
    std::vector<game::MatchSnapshot> saved;
    std::vector<Positions> ends;
    std::size_t next = 0;
    for (std::int64_t t = 0; t < ticks && ends.size() < starts.size(); ++t) {
      if (next < starts.size() && t == starts[next]) {
        saved.push_back(game::saveMatch(reference.state()));
        ++next;
      }
      reference.tick(recording.inputsAt(t));
      for (std::size_t w = ends.size(); w < saved.size(); ++w)
        if (t + 1 == starts[w] + window) ends.push_back(positions(*reference.state().world));
    }

    std::vector<Setting> settings;
    for (const rc::Integrator m :
         {rc::Integrator::semiImplicitEuler, rc::Integrator::velocityVerlet, rc::Integrator::rk4})
      for (int s = 1; s <= 16; s *= 2)
        settings.push_back({s, m});
    settings.push_back(kReference);

    const std::string csvPath = dir + "/session_precision.csv",
                      plotPath = dir + "/session_precision.png",
                      tablePath = dir + "/session_precision.md";
    std::ofstream csv(csvPath);
    if (!csv) {
      std::fprintf(stderr, "session_precision: %s: cannot write\n", csvPath.c_str());
      return 1;
    }
    csv << "integrator,substeps,physics_cpu_s_per_sim_s,rms_error_m,median_window_m,"
           "worst_window_m,bodies_in_one_only\n";
    struct Row {
      Setting setting;
      double cost, error, median, worst;
      int only;
    };
    std::vector<Row> rows;
    game::Match scratch(setup.level(), config);
    const double dt = 1.0 / 60.0;
    for (const Setting& s : settings) {
      // Errors from the first pass; the cost is the least of three passes' physics time.
      double physics = 1e300, sum = 0, worst = 0;
      std::vector<double> errors;
      int only = 0;
      for (int pass = 0; pass < 3; ++pass) {
        double spent = 0;
        for (std::size_t w = 0; w < saved.size(); ++w) {
          // The saved state is the reference setting's: restored into a world set so, then
          // switched.
          scratch.state().world->setStepping(kReference.substeps, kReference.integrator);
          game::restoreMatch(scratch.state(), saved[w]);
          scratch.state().world->setStepping(s.substeps, s.integrator);
          const double before = scratch.state().profile.physics;
          for (std::int64_t t = starts[w]; t < starts[w] + window; ++t)
            scratch.tick(recording.inputsAt(t));
          spent += scratch.state().profile.physics - before;
          if (pass > 0) continue;
          const Distance d = distance(positions(*scratch.state().world), ends[w]);
          errors.push_back(d.rms);
          sum += d.rms;
          worst = std::max(worst, d.rms);
          only += d.onlyInOne;
        }
        physics = std::min(physics, spent);
      }
      std::sort(errors.begin(), errors.end());
      const double median = errors[errors.size() / 2];
      const double simulated = static_cast<double>(saved.size()) * static_cast<double>(window) * dt;
      const Row row{
          s, physics / simulated, sum / static_cast<double>(saved.size()), median, worst, only};
      rows.push_back(row);
      char line[160];
      std::snprintf(line, sizeof line, "%s,%d,%.4g,%.4g,%.4g,%.4g,%d\n",
                    std::string(rc::integratorName(s.integrator)).c_str(), s.substeps, row.cost,
                    row.error, row.median, row.worst, row.only);
      csv << line;
      std::fputs(line, stdout);
    }
    csv.close();
    if (rows.back().error != 0.0) {
      std::fprintf(stderr,
                   "session_precision: the reference setting restarted from its own states "
                   "differs from itself (%.3g m): restores are not exact\n",
                   rows.back().error);
      return 1;
    }

    std::ofstream md(tablePath);
    md << "| setting | physics CPU s per simulated s | mean RMS error (m) | median window (m) | "
          "worst window (m) | bodies in one run only |\n|---|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows) {
      char line[200];
      std::snprintf(line, sizeof line, "| %s | %.3g | %.3g | %.3g | %.3g | %d |\n",
                    name(r.setting).c_str(), r.cost, r.error, r.median, r.worst, r.only);
      md << line;
    }
    md.close();

    const std::string script = plotPath + ".gp";
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 1000,700 font 'DejaVu Sans,11'\n"
       << "set output '" << plotPath << "'\n"
       << "set datafile separator ','\n"
       << "set logscale xy\nset format x '10^{%L}'\nset grid\nset key top right\n"
       << "set xlabel 'median over windows of the RMS position error against 32 substeps, after "
       << window << " ticks (m)'\n"
       << "set ylabel 'physics CPU s per simulated s'\n"
       << "set title \"" << path << ": " << saved.size() << " windows of " << window
       << " ticks, substeps 1 to 16\"\n"
       << "plot ";
    const char* methods[] = {"semi-implicit-euler", "verlet", "rk4"};
    for (int k = 0; k < 3; ++k)
      gp << (k ? ", " : "") << "'" << csvPath << "' using ((strcol(1) eq '" << methods[k]
         << "' && $5 > 0) ? $5 : 1/0):3 with linespoints lw 2 pt 7 title '" << methods[k] << "'";
    gp << "\n";
    gp.close();
    if (std::system(("gnuplot '" + script + "' 2>/dev/null").c_str()) != 0)
      std::fprintf(stderr, "session_precision: gnuplot failed or is not installed\n");
    std::fprintf(stderr, "session_precision: %zu windows of %ld ticks; wrote %s, %s, %s\n",
                 saved.size(), window, csvPath.c_str(), plotPath.c_str(), tablePath.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "session_precision: %s\n", e.what());
    return 1;
  }
}
