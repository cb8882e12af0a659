#include "physics/simd.h"

#include <atomic>

namespace rc::simd {
namespace {

std::atomic<bool> allowed{true};

bool cpuHasAvx2() {
#if RC_HAVE_AVX2_PATHS
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

}  // namespace

bool avx2Enabled() {
  return cpuHasAvx2() && allowed.load(std::memory_order_relaxed);
}

void enableAvx2(bool enable) {
  allowed.store(enable, std::memory_order_relaxed);
}

}  // namespace rc::simd
