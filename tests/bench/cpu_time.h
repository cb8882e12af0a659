// What the round-based benchmarks (skip_bench, scaling_bench) time with: the CPU time of the
// calling thread, which another process on the other core does not add to (wall-clock time
// does, when the machine is shared), and the median of the rounds.
#pragma once

#include <time.h>

#include <algorithm>
#include <vector>

namespace cpu_time {

// Seconds of CPU time this thread has used.
inline double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace cpu_time
