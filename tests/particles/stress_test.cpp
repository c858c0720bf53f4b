// References: Hertz sphere subsurface field (Johnson, Contact Mechanics, 1985, fig. 4.5 and
// eq. 3.72: on the axis, for nu = 0.3, the maximum shear 0.31 p0 lies at z = 0.48 a, so the
// von Mises maximum is 0.62 p0 there); a uniform traction over a wide patch gives, just below
// its centre, sigma_zz = -p and sigma_xz = -mu p (equilibrium with the surface tractions).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "wear/particles/contact.h"
#include "wear/particles/stress.h"
#include "tests/particles/hertz_sphere.h"

using namespace kneesim::particles;

TEST_CASE("Hertz sphere: von Mises maximum 0.62 p0 at depth 0.48 a (nu = 0.3)") {
  const int n = 128;
  const kneesim::test::HertzSphere hertz = kneesim::test::solve_hertz_sphere(0.01, 10.0, n, 4.0);
  const double a = hertz.a, p0 = hertz.p0;
  const Grid& g = hertz.grid;
  const ContactResult& r = hertz.contact;
  SubsurfaceStress st(g, 0.3);
  st.set_traction(r.pressure, 0.0);
  // maximum over the field (levels every a/50 down to 1.2 a)
  const int nz = 61;
  const double dz = 1.2 * a / (nz - 1);
  const std::vector<double> vm = calc_von_mises_field(st, nz, dz);
  const long best = std::max_element(vm.begin(), vm.end()) - vm.begin();
  const double z_best = (best / g.size()) * dz;
  CHECK(vm[best] == doctest::Approx(0.62 * p0).epsilon(0.02));
  CHECK(std::abs(z_best - 0.48 * a) <= 0.03 * a);
  // at the surface centre sigma_zz = -p0
  std::array<std::vector<double>, 6> s;
  st.calc_stress(0.0, s);
  const long c = (n / 2) * n + n / 2;
  CHECK(s[2][c] == doctest::Approx(-r.pressure[c]).epsilon(0.01));
}

TEST_CASE("uniform pressure and friction over a wide patch: sigma_zz = -p, sigma_xz = -mu p") {
  // a 192-cell patch probed one cell deep: z / half-width = 0.01, so the depth terms of
  // the finite patch (order z / half-width) stay below 2 %
  const int n = 256;
  Grid g{n, n, 1e-7, 1e-7, false};
  std::vector<double> p(g.size(), 0.0);
  for (int i = 32; i < 224; ++i)
    for (int j = 32; j < 224; ++j) p[i * n + j] = 1e9;
  SubsurfaceStress st(g, 0.3);
  st.set_traction(p, 0.2);
  std::array<std::vector<double>, 6> s;
  st.calc_stress(1e-7, s);
  const long c = (n / 2) * n + n / 2;
  CHECK(s[2][c] == doctest::Approx(-1e9).epsilon(0.01));
  CHECK(s[4][c] == doctest::Approx(-0.2e9).epsilon(0.02));
  CHECK(std::abs(s[5][c]) < 1e6);
  // under a wide uniform pressure the lateral stress is -(1 + 2 nu)/2 p (Boussinesq, inside
  // a wide loaded region near the surface)
  CHECK(s[0][c] == doctest::Approx(-0.8e9).epsilon(0.02));
}

TEST_CASE("vertical refinement interpolates linearly between levels") {
  const std::vector<double> coarse{0.0, 10.0, 30.0};  // one cell, three levels
  const std::vector<double> fine = refine_levels(coarse, 1, 3, 2);
  REQUIRE(fine.size() == 4);
  CHECK(fine[0] == doctest::Approx(2.5));
  CHECK(fine[1] == doctest::Approx(7.5));
  CHECK(fine[2] == doctest::Approx(15.0));
  CHECK(fine[3] == doctest::Approx(25.0));
}
