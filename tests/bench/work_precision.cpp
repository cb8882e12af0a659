// Run time against error: for each integrator and a ladder of time steps, the CPU time per
// simulated second against the error from the closed form, on three problems:
//   oscillator   q'' = -(2 pi)^2 q from q = 1, 10.25 s (a quarter period past a whole one: at
//                whole periods semi-implicit Euler's O(h) distortion of the orbit vanishes
//                and it would look second order): error |q - cos wt| + |v / w + sin wt|
//   drag         free fall with linear drag, v' = -g - c v (g = 10, c = 0.5) from rest, 5 s:
//                error in position at the end (closed form with exp)
//   kepler       GM = 1, a = 1, e = 0.6 from periapsis, 10.25 orbits (off the periapsis for
//                the same reason): position error at the end (Kepler's equation solved by
//                Newton) and the largest energy error on the way
// Double precision (the study of the integrators, not of float rounding). Not part of ctest:
//   ./build/release/tests/work_precision [--csv FILE] [--plot FILE.png]
// writes the CSV (problem,integrator,dt,steps,ns_per_step,cpu_s_per_sim_s,error,energy_error)
// and, when gnuplot is installed, a log-log plot with one curve per integrator per problem.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "physics/integrate.h"

namespace {

using rc::Integrator;
using Clock = std::chrono::steady_clock;

struct Problem {
  const char* name;
  double duration;
  std::vector<double> q0, v0;
  void (*accel)(std::span<const double> q, std::span<const double> v, double t,
                std::span<double> a);
  double (*error)(std::span<const double> q, std::span<const double> v, double t);
  double (*energy)(std::span<const double> q, std::span<const double> v);  // null: none
};

constexpr double kOmega = 2 * std::numbers::pi, kG = 10, kDrag = 0.5, kEcc = 0.6;

void oscillatorAccel(std::span<const double> q, std::span<const double>, double,
                     std::span<double> a) {
  a[0] = -kOmega * kOmega * q[0];
}
double oscillatorError(std::span<const double> q, std::span<const double> v, double t) {
  return std::abs(q[0] - std::cos(kOmega * t)) + std::abs(v[0] / kOmega + std::sin(kOmega * t));
}

void dragAccel(std::span<const double>, std::span<const double> v, double, std::span<double> a) {
  a[0] = -kG - kDrag * v[0];
}
double dragError(std::span<const double> q, std::span<const double>, double t) {
  const double vt = kG / kDrag;  // terminal speed
  const double exact = -vt * t + vt * (1 - std::exp(-kDrag * t)) / kDrag;
  return std::abs(q[0] - exact);
}

void keplerAccel(std::span<const double> x, std::span<const double>, double, std::span<double> a) {
  const double r2 = x[0] * x[0] + x[1] * x[1], inv3 = 1 / (r2 * std::sqrt(r2));
  a[0] = -x[0] * inv3;
  a[1] = -x[1] * inv3;
}
// Position on the orbit at time t from periapsis: mean anomaly M = t (a = GM = 1), eccentric
// anomaly from Kepler's equation E - e sin E = M by Newton's method.
double keplerError(std::span<const double> q, std::span<const double>, double t) {
  double E = t;
  for (int k = 0; k < 50; ++k)
    E -= (E - kEcc * std::sin(E) - t) / (1 - kEcc * std::cos(E));
  const double x = std::cos(E) - kEcc, y = std::sqrt(1 - kEcc * kEcc) * std::sin(E);
  return std::hypot(q[0] - x, q[1] - y);
}
double keplerEnergy(std::span<const double> q, std::span<const double> v) {
  return 0.5 * (v[0] * v[0] + v[1] * v[1]) - 1 / std::hypot(q[0], q[1]) + 0.5;  // minus E0
}

struct Result {
  double dt = 0;
  long steps = 0;
  double nsPerStep = 0, error = 0, energyError = 0;
};

Result measure(const Problem& p, Integrator m, double dt) {
  Result r;
  r.dt = dt;
  r.steps = std::lround(p.duration / dt);
  rc::IntegratorScratch<double> scratch;
  // Accuracy run, with the energy error tracked.
  {
    std::vector<double> q = p.q0, v = p.v0;
    for (long k = 0; k < r.steps; ++k) {
      rc::integrate<double>(m, q, v, static_cast<double>(k) * dt, dt, p.accel, scratch);
      if (p.energy != nullptr) r.energyError = std::max(r.energyError, std::abs(p.energy(q, v)));
    }
    r.error = p.error(q, v, static_cast<double>(r.steps) * dt);
  }
  // Timing runs: repeated until 20 ms have passed, the best of three batches.
  double best = 1e300;
  for (int batch = 0; batch < 3; ++batch) {
    long done = 0;
    const auto start = Clock::now();
    double elapsed = 0;
    volatile double sink = 0;
    do {
      std::vector<double> q = p.q0, v = p.v0;
      for (long k = 0; k < r.steps; ++k)
        rc::integrate<double>(m, q, v, static_cast<double>(k) * dt, dt, p.accel, scratch);
      sink = sink + q[0];
      done += r.steps;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < 0.02);
    best = std::min(best, elapsed * 1e9 / static_cast<double>(done));
  }
  r.nsPerStep = best;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string csvPath = "work_precision.csv", plotPath = "work_precision.png";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--csv")
      csvPath = argv[i + 1];
    else if (a == "--plot")
      plotPath = argv[i + 1];
    else {
      std::fprintf(stderr, "work_precision: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  const double period = 2 * std::numbers::pi;
  const std::vector<Problem> problems = {
      {"oscillator", 10.25, {1.0}, {0.0}, oscillatorAccel, oscillatorError, nullptr},
      {"drag", 5.0, {0.0}, {0.0}, dragAccel, dragError, nullptr},
      {"kepler",
       10.25 * period,
       {1 - kEcc, 0.0},
       {0.0, std::sqrt((1 + kEcc) / (1 - kEcc))},
       keplerAccel,
       keplerError,
       keplerEnergy},
  };
  std::ofstream csv(csvPath);
  if (!csv) {
    std::fprintf(stderr, "work_precision: %s: cannot write\n", csvPath.c_str());
    return 1;
  }
  csv << "problem,integrator,dt,steps,ns_per_step,cpu_s_per_sim_s,error,energy_error\n";
  for (const Problem& p : problems) {
    for (Integrator m : rc::kIntegrators) {
      for (int k = 4; k <= 14; ++k) {
        // The Kepler orbit needs finer steps to stay bound at all with the Euler methods.
        const double dt = std::ldexp(1.0, -k) * (p.name == std::string("kepler") ? 0.25 : 1.0);
        const Result r = measure(p, m, dt);
        const double perSimSecond = r.nsPerStep * 1e-9 / dt;
        char line[256];
        std::snprintf(line, sizeof line, "%s,%s,%.9g,%ld,%.4g,%.6g,%.6g,%.6g\n", p.name,
                      std::string(rc::integratorName(m)).c_str(), dt, r.steps, r.nsPerStep,
                      perSimSecond, r.error, r.energyError);
        csv << line;
        std::fputs(line, stdout);
      }
    }
  }
  csv.close();
  // The plot: cost against error, log-log, one panel per problem (two for Kepler).
  const std::string script = csvPath + ".gp";
  std::ofstream gp(script);
  gp << "set terminal pngcairo size 1600,1200 font 'DejaVu Sans,11'\n"
     << "set output '" << plotPath << "'\n"
     << "set datafile separator ','\n"
     << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
     << "set grid\nset key top right\n"
     << "set xlabel 'error (closed form)'\nset ylabel 'CPU seconds per simulated second'\n"
     << "set multiplot layout 2,2 title 'Ricochet integrators: run time against error "
        "(double precision)'\n";
  const char* methods[] = {"explicit-euler", "semi-implicit-euler", "verlet", "rk4"};
  struct Panel {
    const char* problem;
    const char* title;
    int column;
  };
  const Panel panels[] = {{"oscillator", "harmonic oscillator, 10.25 s", 7},
                          {"drag", "free fall with linear drag, 5 s", 7},
                          {"kepler", "Kepler orbit e = 0.6, 10.25 orbits: final position", 7},
                          {"kepler", "Kepler orbit e = 0.6, 10.25 orbits: max energy error", 8}};
  for (const Panel& panel : panels) {
    gp << "set title '" << panel.title << "'\n";
    if (panel.column == 8) gp << "set xlabel 'max |energy error|'\n";
    gp << "plot ";
    for (int k = 0; k < 4; ++k)
      gp << (k ? ", " : "") << "'" << csvPath << "' using ((strcol(1) eq '" << panel.problem
         << "' && strcol(2) eq '" << methods[k] << "' && $" << panel.column << " > 0) ? $"
         << panel.column << " : 1/0):6 with linespoints lw 2 pt 7 title '" << methods[k] << "'";
    gp << "\n";
  }
  gp << "unset multiplot\n";
  gp.close();
  const std::string command = "gnuplot '" + script + "' 2>/dev/null";
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "work_precision: gnuplot failed or is not installed; the CSV is %s\n",
                 csvPath.c_str());
    return 0;
  }
  std::fprintf(stderr, "work_precision: wrote %s and %s\n", csvPath.c_str(), plotPath.c_str());
  return 0;
}
