// The contact schedule's scan (engine/contact.h): which elements are due this step, as bit
// masks of 64 elements. Every step compares every element's next evaluation time with the
// accumulated motion, so the comparisons run without a branch, several at a time: SSE2 on the
// baseline x86-64 target the build compiles for, AVX2 and popcnt when the CPU has them
// (chosen once at run time). Both make the same comparison, so the same masks.
#pragma once

#include <cstdint>

namespace kneesim::engine {

// bit k of masks[w] set when element 64 w + k is due, recheck_at <= motion (ordered: a NaN is
// never due), for the n elements; returns the number of due elements. Dispatches to one of
// the two kernels below.
long find_due_masks(const double* recheck_at, int n, double motion, uint64_t* masks);

// the kernels, for the test that compares them: SSE2 (any x86-64; plain C++ elsewhere) and
// AVX2 + popcnt (false when this build or CPU has none, masks untouched)
long find_due_masks_baseline(const double* recheck_at, int n, double motion, uint64_t* masks);
bool find_due_masks_avx2(const double* recheck_at, int n, double motion, uint64_t* masks,
                         long* count);

}  // namespace kneesim::engine
