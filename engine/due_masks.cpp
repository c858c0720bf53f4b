#include "engine/due_masks.h"

#include <algorithm>
#include <bit>
#ifdef __SSE2__
#include <emmintrin.h>
#include <xmmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define KNEESIM_HAS_AVX2_KERNEL 1
#endif

namespace kneesim::engine {
namespace {

// the bits of elements r[k .. end) of a word, one comparison each: a last word of fewer than
// 64 elements (both kernels; plain code inlines into the AVX2 one)
inline uint64_t tail_mask(const double* r, int k, int end, double motion) {
  uint64_t mask = 0;
  for (; k < end; ++k) mask |= static_cast<uint64_t>(r[k] <= motion) << k;
  return mask;
}

}  // namespace

long find_due_masks_baseline(const double* recheck_at, int n, double motion, uint64_t* masks) {
  long count = 0;
  for (int base = 0, w = 0; base < n; base += 64, ++w) {
    const double* r = recheck_at + base;
    uint64_t mask = 0;
    int k = 0;
#ifdef __SSE2__
    if (n - base >= 64) {
      const __m128d limit = _mm_set1_pd(motion);
      for (; k < 64; k += 4) {
        const __m128 lo = _mm_castpd_ps(_mm_cmple_pd(_mm_loadu_pd(r + k), limit));
        const __m128 hi = _mm_castpd_ps(_mm_cmple_pd(_mm_loadu_pd(r + k + 2), limit));
        // one 32-bit half of each 64-bit comparison: four mask bits at once
        const unsigned four =
            static_cast<unsigned>(_mm_movemask_ps(_mm_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0))));
        mask |= static_cast<uint64_t>(four) << k;
      }
    }
#endif
    mask |= tail_mask(r, k, std::min(64, n - base), motion);
    masks[w] = mask;
    count += std::popcount(mask);
  }
  return count;
}

#ifdef KNEESIM_HAS_AVX2_KERNEL
namespace {

// four comparisons and their four mask bits in two instructions, and the popcnt instruction
// instead of libgcc's popcount call (the baseline target has neither)
[[gnu::target("avx2,popcnt")]] long avx2_kernel(const double* recheck_at, int n, double motion,
                                                uint64_t* masks) {
  long count = 0;
  const __m256d limit = _mm256_set1_pd(motion);
  for (int base = 0, w = 0; base < n; base += 64, ++w) {
    const double* r = recheck_at + base;
    uint64_t mask = 0;
    int k = 0;
    if (n - base >= 64) {
      for (; k < 64; k += 4) {
        const __m256d due = _mm256_cmp_pd(_mm256_loadu_pd(r + k), limit, _CMP_LE_OQ);
        mask |= static_cast<uint64_t>(static_cast<unsigned>(_mm256_movemask_pd(due))) << k;
      }
    }
    mask |= tail_mask(r, k, std::min(64, n - base), motion);
    masks[w] = mask;
    count += __builtin_popcountll(mask);
  }
  return count;
}

// read once, at static initialization: __builtin_cpu_init first, as GCC asks of a check that
// may run before libgcc's own constructor
bool detect_avx2() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
}
const bool kCpuHasAvx2 = detect_avx2();

}  // namespace
#endif

bool find_due_masks_avx2(const double* recheck_at, int n, double motion, uint64_t* masks,
                         long* count) {
#ifdef KNEESIM_HAS_AVX2_KERNEL
  if (!kCpuHasAvx2) return false;
  *count = avx2_kernel(recheck_at, n, motion, masks);
  return true;
#else
  (void)recheck_at, (void)n, (void)motion, (void)masks, (void)count;
  return false;
#endif
}

long find_due_masks(const double* recheck_at, int n, double motion, uint64_t* masks) {
#ifdef KNEESIM_HAS_AVX2_KERNEL
  if (kCpuHasAvx2) return avx2_kernel(recheck_at, n, motion, masks);
#endif
  return find_due_masks_baseline(recheck_at, n, motion, masks);
}

}  // namespace kneesim::engine
