#include "physics/simd.h"

namespace rc::simd {

bool avx2Enabled() {
#if RC_HAVE_AVX2_PATHS
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

}  // namespace rc::simd
