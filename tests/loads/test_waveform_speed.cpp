// Waveform lookups run every time step: they must not allocate. This executable replaces the
// global operator new with a counting one and checks that value() and derivative() leave the
// count unchanged; it also reports the time per lookup.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>
#include <new>

#include "engine/io/source_tree.h"
#include "loads/iso14243/waveform.h"

namespace {
std::size_t g_allocations = 0;  // operator new calls in this executable
}  // namespace

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

TEST_CASE("value and derivative do not allocate") {
  const char* src = std::getenv("KNEESIM_SOURCE_DIR");
  const std::filesystem::path dir = src ? std::filesystem::path(src) : kneesim::io::source_dir();
  const auto w = kneesim::loads::load_waveform(dir / "loads/iso14243/iso14243_1_approx.csv");
  const int n = 1000000;
  double sum = 0.0;
  const std::size_t before = g_allocations;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    const double p = 0.00137 * i;
    for (int c = 0; c < w.channel_count(); ++c) sum += w.value(c, p) + w.derivative(c, p);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(g_allocations == before);
  CHECK(sum != 0.0);
  MESSAGE("value + derivative: " << s / (n * w.channel_count()) * 1e9 << " ns per channel");
}
