// References: the targets themselves (issue 5 acceptance: generated surfaces hit target Rq,
// skewness and kurtosis within 5 %), the Fleishman (1978) moment equations, and the
// exponential autocorrelation's 10 % length.
#include <doctest/doctest.h>

#include <algorithm>
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
    CHECK(st.rq == doctest::Approx(c.rq).epsilon(0.05).scale(0));
    CHECK(st.kurtosis == doctest::Approx(c.ku).epsilon(0.05));
    if (c.sk != 0.0) {
      CHECK(st.skewness == doctest::Approx(c.sk).epsilon(0.05).scale(0));
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
  CHECK(c1 / c0 == doctest::Approx(0.1).epsilon(0.5).scale(0));
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
  CHECK_THROWS_AS(make_rough_surface(g, SurfaceSpec{1e-7, 0.0, 3.0, 1e-6, 1, -1e-9}, "cfg"),
                  kneesim::InputError);
}

// Reference: a band-limited surface is a property of the window, not of the grid (surface.h).
// On a 2x coarser grid over the same window it must equal the fine grid's surface averaged over
// the 2 x 2 fine cells around each coarse cell centre, up to the curvature error of that
// average (about (pi dx / lambda_s)^2 / 2, 2 % of Rq with lambda_s = 16 fine cells). Without
// the cutoff the coarse grid drops the short wavelengths the fine one carries, so the same
// comparison must show a large difference.
TEST_CASE("lambda_s: grids over the same window sample the same surface") {
  const double window = 12.8e-6, d = window / 128;
  auto mismatch = [&](double lambda_s) {
    const SurfaceSpec s{100e-9, 0.0, 3.0, 2e-6, 9, lambda_s};
    const std::vector<double> fine = make_rough_surface(Grid{128, 128, d, d, true}, s, "t");
    const std::vector<double> coarse = make_rough_surface(Grid{64, 64, 2 * d, 2 * d, true}, s, "t");
    double worst = 0.0;
    for (int i = 0; i < 64; ++i)
      for (int j = 0; j < 64; ++j) {
        const double avg = 0.25 * (fine[(2 * i) * 128 + 2 * j] + fine[(2 * i + 1) * 128 + 2 * j] +
                                   fine[(2 * i) * 128 + 2 * j + 1] + fine[(2 * i + 1) * 128 + 2 * j + 1]);
        worst = std::max(worst, std::abs(coarse[i * 64 + j] - avg));
      }
    return worst / 100e-9;
  };
  CHECK(mismatch(16 * d) < 0.05);
  CHECK(mismatch(0.0) > 0.2);
  CHECK(lambda_s_transmission(2.0 * M_PI / 0.5e-6, 0.5e-6) ==
        doctest::Approx(0.5).epsilon(1e-12).scale(0));
  CHECK(lambda_s_transmission(1e9, 0.0) == 1.0);
}

// Reference: the exponential autocorrelation R = Rq^2 exp(-2.3 sqrt((tx/bx)^2 + (ty/by)^2))
// (surface.h) falls to 10 % at bx along x and by = bx / gamma across (Peklenik's lay ratio).
// One realisation's ACF scatters by about 0.02 at the 10 % lag on this grid (Bartlett), i.e.
// about 9 % in length; the mean over eight seeds is compared within 7 %. lambda_s = 0 (the
// target is the unfiltered autocorrelation); by >= 10 cells keeps the Nyquist truncation
// below 3 %.
TEST_CASE("lay: directional correlation lengths hit bx and bx / gamma within 7 % (8 seeds)") {
  const double d = 50e-9;
  Grid g{512, 512, d, d, true};
  struct Case { double bx, gamma; };
  for (const Case& k : {Case{2e-6, 4.0}, Case{1e-6, 1.0}, Case{0.75e-6, 0.25}}) {
    double lx = 0.0, ly = 0.0;
    const int seeds = 8;
    for (int s = 0; s < seeds; ++s) {
      SurfaceSpec spec{100e-9, 0.0, 3.0, k.bx, static_cast<std::uint64_t>(40 + s), 0.0, k.gamma};
      const std::vector<double> h = make_rough_surface(g, spec, "t");
      lx += measure_correlation_length(g, h, true) / seeds;
      ly += measure_correlation_length(g, h, false) / seeds;
    }
    INFO("bx " << k.bx << " gamma " << k.gamma << ": measured " << lx << " / " << ly);
    CHECK(lx == doctest::Approx(k.bx).epsilon(0.07).scale(0));
    CHECK(ly == doctest::Approx(k.bx / k.gamma).epsilon(0.07).scale(0));
  }
  CHECK_THROWS_AS(make_rough_surface(g, SurfaceSpec{1e-7, 0.0, 3.0, 1e-6, 1, 0.0, 0.0}, "cfg"),
                  kneesim::InputError);
}

// Reference: z = A sin(2 pi x / lambda) has rms slope A (2 pi / lambda) / sqrt 2 along x, none
// along y, and rms curvature (Laplacian / 2) A (2 pi / lambda)^2 / (2 sqrt 2).
TEST_CASE("rms slope and curvature of a sine surface") {
  Grid g{128, 64, 100e-9, 100e-9, true};
  const double a = 50e-9, lambda = 16 * 100e-9, k = 2 * M_PI / lambda;
  std::vector<double> h(g.size());
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j) h[i * g.ny + j] = a * std::sin(k * i * g.dx);
  const SurfaceGradients gr = calc_surface_gradients(g, h);
  CHECK(gr.slope_x == doctest::Approx(a * k / std::sqrt(2.0)).epsilon(1e-9).scale(0));
  // none along y: an absolute bound (a relative one on 0 would be exact equality), 1e-9 of a
  // dimensionless slope, 7e-9 of the x slope (0.139), as before
  CHECK(std::abs(gr.slope_y) < 1e-9);
  CHECK(gr.curvature == doctest::Approx(a * k * k / (2 * std::sqrt(2.0))).epsilon(1e-9));
}
