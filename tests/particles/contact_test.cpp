// References: Love's closed-form deflection of a uniformly loaded rectangle (Johnson,
// Contact Mechanics, 1985, eq. 3.25), Hertz sphere and cylinder (Johnson 4.2 and 4.3), and
// the layered half-space limits (film of the same material = homogeneous; very thick film =
// film half-space; very thin film = substrate half-space).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "engine/errors.h"
#include "wear/particles/contact.h"
#include "wear/particles/deflection.h"
#include "tests/particles/hertz_sphere.h"

using namespace kneesim::particles;

namespace {
constexpr double kPi = 3.14159265358979323846;
const ElasticBody kSteel{210e9, 0.3};
double e_star() { return 1.0 / (2.0 * compliance(210e9, 0.3)); }
}  // namespace

TEST_CASE("Love rectangle: centre deflection of a square is 8 a asinh(1) / pi") {
  const double a = 1e-6;
  CHECK(love_rectangle(0.0, 0.0, a, a) ==
        doctest::Approx(8.0 * a * std::asinh(1.0) / kPi).epsilon(1e-14).scale(0));
  // far away it tends to the point load: area / (pi r)
  const double r = 1000 * a;
  CHECK(love_rectangle(r, 0.0, a, a) ==
        doctest::Approx(4 * a * a / (kPi * r)).epsilon(1e-6).scale(0));
}

TEST_CASE("DC-FFT deflection of a uniform square patch equals Love's closed form") {
  Grid g{64, 48, 1e-7, 1.5e-7, false};
  DeflectionOperator op(g, kSteel, kSteel);
  std::vector<double> p(g.size(), 0.0), u(g.size());
  const int i0 = 20, i1 = 36, j0 = 10, j1 = 26;  // a 16 x 16 cell patch
  for (int i = i0; i < i1; ++i)
    for (int j = j0; j < j1; ++j) p[i * g.ny + j] = 1e8;
  op.apply(p.data(), u.data());
  const double a = 0.5 * (i1 - i0) * g.dx, b = 0.5 * (j1 - j0) * g.dy;
  const double xc = 0.5 * (g.x(i0) + g.x(i1 - 1)), yc = 0.5 * (g.y(j0) + g.y(j1 - 1));
  const double k = 2.0 * compliance(210e9, 0.3) * 1e8;
  double worst = 0.0, peak = 0.0;
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j) {
      const double exact = k * love_rectangle(g.x(i) - xc, g.y(j) - yc, a, b);
      worst = std::max(worst, std::abs(u[i * g.ny + j] - exact));
      peak = std::max(peak, exact);
    }
  CHECK(worst / peak < 1e-10);  // superposition of exact rectangles: round-off only
}

TEST_CASE("Hertz sphere on a half-space within 2 % at 128 x 128 over +-1.6 a") {
  const double radius = 0.01, load = 10.0;
  const kneesim::test::HertzSphere s = kneesim::test::solve_hertz_sphere(radius, load, 128, 3.2);
  const double a = s.a, p0 = s.p0;
  const Grid& g = s.grid;
  const ContactResult& r = s.contact;
  CHECK(r.converged);
  const double p_max = *std::max_element(r.pressure.begin(), r.pressure.end());
  const double a_num = std::sqrt(r.contact_fraction * g.size() * g.cell_area() / kPi);
  CHECK(p_max == doctest::Approx(p0).epsilon(0.02));
  CHECK(a_num == doctest::Approx(a).epsilon(0.02).scale(0));
  CHECK(r.load == doctest::Approx(load).epsilon(1e-6));
  CHECK(r.approach == doctest::Approx(a * a / radius).epsilon(0.02).scale(0));
}

TEST_CASE("Hertz cylinder (periodic along its axis) within 2 % at 256 x 8 over +-2 b") {
  const double radius = 2e-3, w = 10.0 / 6e-3, es = e_star();
  const double b = std::sqrt(4.0 * w * radius / (kPi * es));
  const double p0 = 2.0 * w / (kPi * b);
  const int nx = 256, ny = 8;
  Grid g{nx, ny, 4.0 * b / nx, 4.0 * b / nx, true};
  DeflectionOperator op(g, kSteel, kSteel);
  std::vector<double> h(g.size());
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) h[i * ny + j] = g.x(i) * g.x(i) / (2 * radius);
  ContactOptions opt;
  opt.load = w * ny * g.dy;
  const ContactResult r = solve_contact(op, h, opt);
  CHECK(r.converged);
  const double p_max = *std::max_element(r.pressure.begin(), r.pressure.end());
  const double b_num = 0.5 * r.contact_fraction * nx * g.dx;
  CHECK(p_max == doctest::Approx(p0).epsilon(0.02));
  CHECK(b_num == doctest::Approx(b).epsilon(0.02).scale(0));
  // the pressure is uniform along the axis (periodic images act like an infinite cylinder)
  for (int i = 0; i < nx; ++i)
    for (int j = 1; j < ny; ++j)
      CHECK(r.pressure[i * ny + j] == doctest::Approx(r.pressure[i * ny]).epsilon(1e-9));
}

TEST_CASE("hardness cap limits the pressure and keeps the load") {
  const double load = 10.0;
  const kneesim::test::HertzSphere s = kneesim::test::solve_hertz_sphere(0.01, load, 64, 3.2, 0.8);
  const ContactResult& r = s.contact;
  CHECK(*std::max_element(r.pressure.begin(), r.pressure.end()) <= s.hardness);
  CHECK(r.capped_fraction > 0.0);
  CHECK(r.load == doctest::Approx(load).epsilon(1e-6));
}

TEST_CASE("layered frequency response: limits of film thickness") {
  const double e1 = 88e9, e2 = 210e9, nu = 0.3, h = 1e-6;
  const double g1 = e1 / (2 * 1.3), g2 = e2 / (2 * 1.3);
  for (double alpha : {1e4, 1e6, 1e7}) {
    CHECK(layered_compliance_frf(alpha, h, e2, nu, e2, nu) ==
          doctest::Approx((1 - nu) / (g2 * alpha)).epsilon(1e-9).scale(0));
  }
  CHECK(layered_compliance_frf(30.0 / h, h, e1, nu, e2, nu) ==
        doctest::Approx((1 - nu) / (g1 * 30.0 / h)).epsilon(1e-6).scale(0));
  CHECK(layered_compliance_frf(1e-4 / h, h, e1, nu, e2, nu) ==
        doctest::Approx((1 - nu) / (g2 * 1e-4 / h)).epsilon(1e-3).scale(0));
}

TEST_CASE("bad input: load above hardness x area, bad grids") {
  Grid g{64, 64, 1e-7, 1e-7, true};
  CHECK_THROWS_AS(check_load(1.0, 1.8e9, g, "cli --load-N"), kneesim::InputError);
  CHECK_THROWS_AS(check_load(-1.0, 1.8e9, g, "cli --load-N"), kneesim::InputError);
  CHECK_NOTHROW(check_load(1e-3, 1.8e9, g, "cli --load-N"));
  CHECK_THROWS_AS(check_grid(Grid{0, 64, 1e-7, 1e-7}, 16, "config"), kneesim::InputError);
  CHECK_THROWS_AS(check_grid(Grid{63, 64, 1e-7, 1e-7}, 16, "config"), kneesim::InputError);
  CHECK_THROWS_AS(check_grid(Grid{64, 64, 0.0, 1e-7}, 16, "config"), kneesim::InputError);
  CHECK_THROWS_AS(check_grid(Grid{1 << 20, 1 << 20, 1e-7, 1e-7}, 64, "config"),
                  kneesim::InputError);
  try {
    check_grid(Grid{64, 64, -1e-7, 1e-7}, 16, "particles.toml [grid]");
  } catch (const kneesim::InputError& e) {
    CHECK(std::string(e.what()).find("particles.toml [grid]") != std::string::npos);
  }
}

// Reference: the closed-form surface compliance of a layer bonded to a half-space under a
// normal Fourier mode (O'Sullivan & King, J. Tribol. 110:235, 1988; k = G1/G2,
// l = 1 - 4(1 - nu1)/(1 + k(3 - 4 nu2)), m = (k - 1)/(k + 3 - 4 nu1)), independent of the 6x6
// boundary system used in deflection.cpp; film softer and stiffer than the substrate, and
// unequal Poisson ratios.
TEST_CASE("layered frequency response equals the closed form of a bonded layer") {
  const double h = 0.5e-6;
  struct M { double ef, es, nuf, nus; };
  for (const M& m : {M{88e9, 210e9, 0.3, 0.3}, M{210e9, 88e9, 0.3, 0.3}, M{88e9, 210e9, 0.35, 0.25}}) {
    const double g1 = m.ef / (2 * (1 + m.nuf)), g2 = m.es / (2 * (1 + m.nus)), k = g1 / g2;
    const double l = 1 - 4 * (1 - m.nuf) / (1 + k * (3 - 4 * m.nus));
    const double mm = (k - 1) / (k + 3 - 4 * m.nuf);
    for (double ah : {0.01, 0.1, 0.3, 1.0, 2.0, 5.0}) {
      const double e2 = std::exp(-2 * ah), e4 = e2 * e2;
      const double closed = (1 - m.nuf) / (g1 * (ah / h)) * (1 + 4 * mm * ah * e2 - l * mm * e4) /
                            (1 - (l + mm + 4 * mm * ah * ah) * e2 + l * mm * e4);
      CHECK(layered_compliance_frf(ah / h, h, m.ef, m.nuf, m.es, m.nus) ==
            doctest::Approx(closed).epsilon(1e-9).scale(0));
    }
  }
}
