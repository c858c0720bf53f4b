// The schedule's scan kernels (engine/due_masks.h). Reference: a plain loop's
// `recheck_at[e] <= motion` per element and its count; the SSE2 kernel and, on a CPU with
// AVX2, the AVX2 kernel must give the same masks and count, over element counts with and
// without a partial last word, values equal to the motion (due), one ulp above it (not due),
// NaN (never due), +-0 and infinities.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "engine/due_masks.h"

using namespace kneesim;

TEST_CASE("the schedule's mask kernels agree with the element-by-element comparison") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  int avx2_checked = 0;
  for (const int n : {1, 3, 63, 64, 65, 130, 6624}) {
    const double motion = 1.0;
    std::vector<double> r(n);
    for (int e = 0; e < n; ++e) {
      switch (e % 9) {
        case 0: r[e] = motion; break;                                // equal: due
        case 1: r[e] = std::nextafter(motion, 2.0); break;           // one ulp above: not due
        case 2: r[e] = nan; break;                                   // never due
        case 3: r[e] = (e % 2) ? 0.0 : -0.0; break;                  // due
        case 4: r[e] = (e % 2) ? inf : -inf; break;
        default: r[e] = u(rng);
      }
    }
    const size_t words = (n + 63) / 64;
    std::vector<uint64_t> expected(words, 0);
    long expected_count = 0;
    for (int e = 0; e < n; ++e) {
      if (r[e] <= motion) {
        expected[e / 64] |= uint64_t{1} << (e % 64);
        ++expected_count;
      }
    }
    CAPTURE(n);
    std::vector<uint64_t> masks(words, ~uint64_t{0});
    CHECK(engine::find_due_masks_baseline(r.data(), n, motion, masks.data()) == expected_count);
    CHECK(masks == expected);
    std::fill(masks.begin(), masks.end(), ~uint64_t{0});
    long count = -1;
    if (engine::find_due_masks_avx2(r.data(), n, motion, masks.data(), &count)) {
      CHECK(count == expected_count);
      CHECK(masks == expected);
      ++avx2_checked;
    }
    std::fill(masks.begin(), masks.end(), ~uint64_t{0});
    CHECK(engine::find_due_masks(r.data(), n, motion, masks.data()) == expected_count);
    CHECK(masks == expected);
  }
  const std::string avx2 = avx2_checked > 0 ? "checked" : "not available on this CPU";
  MESSAGE("AVX2 kernel " << avx2);
}
