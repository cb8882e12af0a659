// How many random cases a statistical test draws: all of them in an optimised build, a tenth
// under ASan+UBSan. A sanitized case costs 5-20x an optimised one, and the sanitizers look for
// memory and undefined-behaviour errors, which the first tenth of the cases (the same seeds)
// meets on the same code paths; the figures the tests claim (agreement with Box2D on 100,000
// cases per pair) are held by the Release and Debug runs.
#pragma once

namespace rc::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

constexpr int casesUnderSanitizers(int cases) {
  return kSanitized ? cases / 10 : cases;
}

}  // namespace rc::testing
