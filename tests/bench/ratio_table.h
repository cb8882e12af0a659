// Benchmarks that race our code against Box2D 2.4.1 (or against brute force): benchmarks are
// registered in pairs named "query/case/ours" and "query/case/box2d" (or ".../brute"), each
// calling state.SetItemsProcessed. After the usual console output a Markdown table gives the
// time per item of each and the speed-up (the other's time over ours: above 1 means we are
// faster). A pair "query/case/with" and "query/case/without" races an optimisation against its
// absence the same way: "with" takes the ours column and the speed-up is the time without over
// the time with (above 1: the optimisation pays). With --benchmark_repetitions the medians are
// used. --table=FILE also writes the table to FILE.
#pragma once

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace rc::bench {

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration && r.aggregate_name != "median") continue;
      auto rate = r.counters.find("items_per_second");
      if (rate == r.counters.end() || rate->second.value <= 0.0) continue;
      const std::string name = r.run_name.function_name;
      const std::size_t slash = name.rfind('/');
      const std::string key = name.substr(0, slash), engine = name.substr(slash + 1);
      if (engine == "ours" || engine == "with") {
        ours_[key] = 1e9 / rate->second.value;
      } else {
        other_[key] = 1e9 / rate->second.value;
        otherName_[key] = engine == "box2d"     ? "Box2D 2.4.1"
                          : engine == "brute"   ? "brute force"
                          : engine == "without" ? "without it"
                                                : engine;
      }
      order_.push_back(key);
    }
  }

  // | query | case | ours | against | its time | speed-up |, times per item with a unit.
  std::string table() const {
    std::string out =
        "| query | case | ours | against | its time | speed-up |\n"
        "|---|---|---:|---|---:|---:|\n";
    std::map<std::string, bool> seen;
    for (const std::string& key : order_) {
      if (seen[key] || !ours_.count(key) || !other_.count(key)) continue;
      seen[key] = true;
      const std::size_t slash = key.find('/');
      char line[320];
      std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %s | %.2fx |\n",
                    key.substr(0, slash).c_str(),
                    slash == std::string::npos ? "" : key.substr(slash + 1).c_str(),
                    withUnit(ours_.at(key)).c_str(), otherName_.at(key).c_str(),
                    withUnit(other_.at(key)).c_str(), other_.at(key) / ours_.at(key));
      out += line;
    }
    return out;
  }

 private:
  static std::string withUnit(double ns) {
    char s[32];
    if (ns < 1e4)
      std::snprintf(s, sizeof s, "%.1f ns", ns);
    else if (ns < 1e7)
      std::snprintf(s, sizeof s, "%.1f us", ns * 1e-3);
    else
      std::snprintf(s, sizeof s, "%.2f ms", ns * 1e-6);
    return s;
  }

  std::map<std::string, double> ours_, other_;
  std::map<std::string, std::string> otherName_;
  std::vector<std::string> order_;
};

// main() of a racing benchmark: strips --table=FILE, registers, runs, prints and writes the
// table. Returns the process exit code.
template <class Register>
int runWithRatioTable(int argc, char** argv, const char* program, Register registerAll) {
  std::string tablePath;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--table=", 8) == 0)
      tablePath = argv[i] + 8;
    else
      args.push_back(argv[i]);
  }
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  registerAll();
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const std::string table = reporter.table();
  std::printf("\n%s", table.c_str());
  if (!tablePath.empty()) {
    FILE* f = std::fopen(tablePath.c_str(), "w");
    if (f == nullptr) {
      std::fprintf(stderr, "%s: cannot write %s\n", program, tablePath.c_str());
      return 1;
    }
    std::fputs(table.c_str(), f);
    std::fclose(f);
  }
  benchmark::Shutdown();
  return 0;
}

}  // namespace rc::bench
