// References: the targets themselves (issue 5 acceptance: generated surfaces hit target Rq,
// skewness and kurtosis within 5 %), the Fleishman (1978) moment equations, and the
// exponential autocorrelation's 10 % length.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/errors.h"
#include "wear/particles/surface.h"

using namespace kneesim::particles;

TEST_CASE("generated surfaces hit Rq, skewness and kurtosis within 5 % (study's surfaces)") {
  Grid g{256, 256, 102e-9, 102e-9, true};
  struct Case { double rq, sk, ku; };
  // cylinder, steel disk, brass disk (physics.md section 9) and a Gaussian one
  for (const Case& c : {Case{50e-9, -0.27, 8.6}, Case{610e-9, -0.84, 4.46},
                        Case{760e-9, -1.0, 4.94}, Case{100e-9, 0.0, 3.0}}) {
    SurfaceSpec s{c.rq, c.sk, c.ku, 1e-6, 7};
    const std::vector<double> h = make_rough_surface(g, s, "test");
    const SurfaceStats st = calc_surface_stats(h);
    CHECK(st.rq == doctest::Approx(c.rq).epsilon(0.05));
    CHECK(st.kurtosis == doctest::Approx(c.ku).epsilon(0.05));
    if (c.sk != 0.0) {
      CHECK(st.skewness == doctest::Approx(c.sk).epsilon(0.05));
    } else {
      CHECK(std::abs(st.skewness) < 0.05);
    }
  }
}

TEST_CASE("correlation: the autocorrelation falls to about 10 % at the correlation length") {
  Grid g{256, 256, 50e-9, 50e-9, true};
  const double beta = 1e-6;  // 20 cells
  const std::vector<double> h = make_rough_surface(g, SurfaceSpec{1e-7, 0.0, 3.0, beta, 3}, "t");
  const int lag = 20;
  double c0 = 0.0, c1 = 0.0;
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j) {
      c0 += h[i * g.ny + j] * h[i * g.ny + j];
      c1 += h[i * g.ny + j] * h[((i + lag) % g.nx) * g.ny + j];
    }
  // one random realisation: sampling scatter of the ACF at 20 cells is several per cent
  CHECK(c1 / c0 == doctest::Approx(0.1).epsilon(0.5));
}

TEST_CASE("Fleishman coefficients satisfy the unit-variance equation") {
  double b, c, d;
  REQUIRE(solve_fleishman(-0.84, 4.46, b, c, d));
  CHECK(b * b + 6 * b * d + 2 * c * c + 15 * d * d == doctest::Approx(1.0).epsilon(1e-10));
  CHECK_FALSE(solve_fleishman(2.0, 2.0, b, c, d));  // kurtosis below 1 + skewness^2
}

TEST_CASE("bad surface input is one clear error") {
  Grid g{64, 64, 1e-7, 1e-7, true};
  CHECK_THROWS_AS(make_rough_surface(g, SurfaceSpec{0.0, 0.0, 3.0, 1e-6, 1}, "cfg"),
                  kneesim::InputError);
  CHECK_THROWS_AS(make_rough_surface(g, SurfaceSpec{1e-7, 2.0, 2.0, 1e-6, 1}, "cfg"),
                  kneesim::InputError);
}
