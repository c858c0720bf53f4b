// Contact and restraint kernels (engine/contact_law.h) against their closed forms
// (physics.md sections 2 and 4): the foundation modulus, the linear and nonlinear
// elastic-foundation laws and their tangent stiffness, regularized Coulomb friction, and the
// spring-gap restraint law with the Pal 2008 Stanmore values.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "engine/contact_law.h"

using namespace kneesim::engine;

TEST_CASE("elastic-foundation laws with an exponent: p = K g^n") {
  const double K = 4.1e9, h = 6e-3;
  // closed forms: linear d/h = 1/4, n = 1/2 gives K/2; nonlinear d/h = 1 - 1/e gives g = 1 and
  // p = K for any n; the tangent n K g^(n-1) g'(d) against a central difference
  CHECK(ef_pressure(ContactLaw::kLinear, K, 0.5, 0.25 * h, h) == doctest::Approx(0.5 * K).epsilon(1e-14));
  CHECK(ef_pressure(ContactLaw::kNonlinear, K, 0.7, (1.0 - 0.36787944117144233) * h, h) ==
        doctest::Approx(K).epsilon(1e-13));
  CHECK(ef_stiffness(ContactLaw::kLinear, K, 0.5, 0.25 * h, h) == doctest::Approx(K / h).epsilon(1e-14));
  for (ContactLaw law : {ContactLaw::kLinear, ContactLaw::kNonlinear}) {
    for (double n : {0.4, 0.7, 1.3}) {
      for (double d : {1e-5, 1e-4, 1e-3, 3e-3}) {
        const double s = d * 1e-4;
        const double fd = (ef_pressure(law, K, n, d + s, h) - ef_pressure(law, K, n, d - s, h)) / (2 * s);
        CHECK(fd == doctest::Approx(ef_stiffness(law, K, n, d, h)).epsilon(1e-6));
      }
      CHECK(ef_pressure(law, K, n, 0.0, h) == 0.0);
      CHECK(ef_pressure(law, K, n, -1e-4, h) == 0.0);
    }
  }
  SUBCASE("n < 1 runs linear in g below kExponentLinearStrain: continuous, finite tangent") {
    const double n = 0.5, d_t = kExponentLinearStrain * h;
    CHECK(ef_pressure(ContactLaw::kLinear, K, n, d_t * (1 - 1e-12), h) ==
          doctest::Approx(ef_pressure(ContactLaw::kLinear, K, n, d_t * (1 + 1e-12), h)).epsilon(1e-9));
    // below it the law is the chord K g_t^(n-1) g: tangent K g_t^(n-1) / h at first touch
    CHECK(ef_stiffness(ContactLaw::kLinear, K, n, 0.0, h) ==
          doctest::Approx(K * std::pow(kExponentLinearStrain, n - 1.0) / h).epsilon(1e-14));
    CHECK(ef_pressure(ContactLaw::kLinear, K, n, 0.5 * d_t, h) ==
          doctest::Approx(0.5 * ef_pressure(ContactLaw::kLinear, K, n, d_t, h)).epsilon(1e-12));
  }
  SUBCASE("n = 1 is the classical law bit for bit") {
    for (double d : {1e-7, 3.3e-5, 1.7e-3}) {
      CHECK(ef_pressure(ContactLaw::kLinear, K, 1.0, d, h) == K * d / h);
      CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, d, h) == -K * std::log(1.0 - d / h));
    }
  }
  SUBCASE("the contact loop's fused kernel gives ef_pressure's and ef_stiffness's bits") {
    // invariant: the loop takes both from one strain evaluation; any difference would change
    // every result of the default law
    for (ContactLaw law : {ContactLaw::kLinear, ContactLaw::kNonlinear}) {
      for (double n : {0.5, 0.628, 1.0, 1.3}) {
        for (double d : {-1e-6, 0.0, 1e-8, 3.3e-5, 1.7e-3}) {
          const EfPressureStiffness ps = ef_pressure_and_stiffness(law, K, n, d, h);
          CHECK(ps.pressure == ef_pressure(law, K, n, d, h));
          CHECK(ps.stiffness == ef_stiffness(law, K, n, d, h));
        }
      }
    }
  }
  SUBCASE("a paraboloidal overclosure: the patch's peak pressure is n + 1 times its mean") {
    // d(r) = d0 - r^2 / (2 R) on a bed of 0.02 mm square elements: p = K (d/h)^n gives
    // P = 2 pi R K d0^(n+1) / ((n + 1) h^n) over the area pi 2 R d0, so the mean pressure is
    // K (d0/h)^n / (n + 1) and the peak K (d0/h)^n: peak / mean = n + 1 (2 for the linear law,
    // 1.5 = Hertz's for n = 1/2). Discretization: a few 1e-3 on the area at 100 elements across.
    const double R = 0.03, d0 = 3e-5, a = 0.02e-3, half = std::sqrt(2 * R * d0);
    for (double n : {0.5, 0.75, 1.0}) {
      double force = 0.0, area = 0.0, peak = 0.0;
      for (double x = -half; x <= half; x += a) {
        for (double z = -half; z <= half; z += a) {
          const double d = d0 - (x * x + z * z) / (2 * R);
          const double p = ef_pressure(ContactLaw::kLinear, K, n, d, h);
          if (p <= 0.0) continue;
          force += p * a * a;
          area += a * a;
          peak = std::max(peak, p);
        }
      }
      CHECK(peak / (force / area) == doctest::Approx(n + 1.0).epsilon(0.01));
    }
  }
}

TEST_CASE("foundation modulus K = (1 - nu) E / ((1 + nu)(1 - 2 nu))") {
  // UHMWPE E = 685 MPa, nu = 0.47: K = 0.53 * 685 / (1.47 * 0.06) MPa = 4116.1 MPa, the
  // "6.0 E" of physics.md section 4; nu = 1/3: K = (2/3) / ((4/3)(1/3)) E = 1.5 E exactly
  CHECK(foundation_modulus(685e6, 0.47) == doctest::Approx(4116.1e6).epsilon(1e-4));
  CHECK(foundation_modulus(685e6, 0.47) / 685e6 == doctest::Approx(6.0).epsilon(0.01));
  CHECK(foundation_modulus(1e9, 1.0 / 3.0) == doctest::Approx(1.5e9).epsilon(1e-14));
  // nu = 0: K = E
  CHECK(foundation_modulus(1e9, 0.0) == 1e9);
}

TEST_CASE("elastic-foundation pressure laws") {
  const double K = 4.1e9, h = 6e-3;
  SUBCASE("linear p = K d / h, zero out of contact") {
    // values at strains whose answer is known without the formula: d = h/4 gives K/4, the
    // tangent is K/h = 6.8333e11 Pa/m at any depth
    CHECK(ef_pressure(ContactLaw::kLinear, K, 1.0, 1.5e-3, h) == doctest::Approx(1.025e9).epsilon(1e-15));
    CHECK(ef_pressure(ContactLaw::kLinear, K, 1.0, 6e-5, h) == doctest::Approx(4.1e7).epsilon(1e-15));
    for (double d : {1e-6, 1e-4, 3e-3}) {
      CHECK(ef_stiffness(ContactLaw::kLinear, K, 1.0, d, h) ==
            doctest::Approx(6.833333333333e11).epsilon(1e-12));
    }
    CHECK(ef_pressure(ContactLaw::kLinear, K, 1.0, 0.0, h) == 0.0);
    CHECK(ef_pressure(ContactLaw::kLinear, K, 1.0, -1e-4, h) == 0.0);
  }
  SUBCASE("nonlinear p = -K ln(1 - d/h), tangent K / (h - d), -> linear for d << h") {
    // special strains with known answers: d/h = 1/2 gives K ln 2 and a tangent 2K/h; d/h = 3/4
    // gives K ln 4 = 2 K ln 2 and 4K/h; d/h = 1 - 1/e gives exactly K
    constexpr double kLn2 = 0.69314718055994531;
    CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, 0.5 * h, h) == doctest::Approx(K * kLn2).epsilon(1e-14));
    CHECK(ef_stiffness(ContactLaw::kNonlinear, K, 1.0, 0.5 * h, h) == doctest::Approx(2.0 * K / h).epsilon(1e-14));
    CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, 0.75 * h, h) ==
          doctest::Approx(2.0 * K * kLn2).epsilon(1e-14));
    CHECK(ef_stiffness(ContactLaw::kNonlinear, K, 1.0, 0.75 * h, h) == doctest::Approx(4.0 * K / h).epsilon(1e-14));
    CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, (1.0 - 0.36787944117144233) * h, h) ==
          doctest::Approx(K).epsilon(1e-14));
    for (double d : {1e-6, 1e-5, 1e-4, 1e-3, 3e-3, 5e-3}) {
      // tangent stiffness is the derivative of the law (central difference, step d/1e4)
      const double s = d * 1e-4;
      const double fd = (ef_pressure(ContactLaw::kNonlinear, K, 1.0, d + s, h) -
                         ef_pressure(ContactLaw::kNonlinear, K, 1.0, d - s, h)) /
                        (2 * s);
      CHECK(fd == doctest::Approx(ef_stiffness(ContactLaw::kNonlinear, K, 1.0, d, h)).epsilon(1e-6));
    }
    // small strain: -ln(1 - e) = e + e^2/2 + e^3/3 + ..., relative excess e/2 + e^2/3 at
    // e = 1e-4 (next term 2.5e-13; log of 1 - e loses ~1e-12 relative)
    const double d = 6e-7, e = d / h;
    CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, d, h) / (K * d / h) ==
          doctest::Approx(1.0 + 0.5 * e + e * e / 3.0).epsilon(1e-11));
    CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, 0.0, h) == 0.0);
    CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, -1e-4, h) == 0.0);
    // beyond the singularity the law is capped at d = 0.99 h (finite, documented)
    CHECK(std::isfinite(ef_pressure(ContactLaw::kNonlinear, K, 1.0, 2.0 * h, h)));
    CHECK(ef_pressure(ContactLaw::kNonlinear, K, 1.0, 2.0 * h, h) ==
          doctest::Approx(-K * std::log(0.01)));
  }
  SUBCASE("flat punch on a bed of elements: F = K A d / h (linear), -K ln(1 - d/h) A") {
    // summing the kernel over a 40 x 40 grid of 0.5 mm square elements under a rigid flat
    // punch pressed by d: every element has penetration d; the sum must equal the closed form
    // to round-off (1e-12 relative)
    const int n = 40;
    const double a = 0.5e-3, d = 0.2e-3;
    double f_lin = 0.0, f_non = 0.0;
    for (int i = 0; i < n * n; ++i) {
      f_lin += a * a * ef_pressure(ContactLaw::kLinear, K, 1.0, d, h);
      f_non += a * a * ef_pressure(ContactLaw::kNonlinear, K, 1.0, d, h);
    }
    const double area = n * n * a * a;
    CHECK(f_lin == doctest::Approx(K * area * d / h).epsilon(1e-12));
    CHECK(f_non == doctest::Approx(-K * area * std::log(1.0 - d / h)).epsilon(1e-12));
  }
}

TEST_CASE("regularized Coulomb friction") {
  // t = -mu p v / sqrt(|v|^2 + eps^2): opposite to the slip, magnitude -> mu p for |v| >> eps,
  // -> mu p |v| / eps (linear in v) for |v| << eps
  const double mu = 0.07, p = 10e6, eps = 1e-3;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    Eigen::Vector3d dir(u(rng), u(rng), u(rng));
    dir.normalize();
    // direction: antiparallel to the slip for any speed
    for (double speed : {1e-9, 1e-5, 1e-3, 0.1, 10.0}) {
      const Eigen::Vector3d t = friction_traction(mu, p, speed * dir, eps);
      CHECK(t.normalized().dot(dir) == doctest::Approx(-1.0).epsilon(1e-12));
      CHECK(t.norm() <= mu * p);
    }
    // |v| = 1000 eps: magnitude mu p / sqrt(1 + 1e-6) = mu p (1 - 5e-7)
    CHECK(friction_traction(mu, p, 1.0 * dir, eps).norm() ==
          doctest::Approx(mu * p).epsilon(1e-6));
    // |v| = eps / 1000: magnitude mu p |v| / eps (1 - 5e-7): linear in |v|
    const double v = 1e-6;
    CHECK(friction_traction(mu, p, v * dir, eps).norm() ==
          doctest::Approx(mu * p * v / eps).epsilon(1e-6));
    CHECK(friction_traction(mu, p, 2 * v * dir, eps).norm() ==
          doctest::Approx(2.0 * friction_traction(mu, p, v * dir, eps).norm()).epsilon(1e-5));
    // |v| = eps: mu p / sqrt(2)
    CHECK(friction_traction(mu, p, eps * dir, eps).norm() ==
          doctest::Approx(mu * p / std::sqrt(2.0)).epsilon(1e-12));
  }
  CHECK(friction_traction(mu, p, Eigen::Vector3d::Zero(), eps).norm() == 0.0);
  CHECK(friction_traction(0.0, p, Eigen::Vector3d(1, 0, 0), eps).norm() == 0.0);
}

TEST_CASE("spring-gap restraint law with the Pal 2008 Stanmore values") {
  // physics.md section 2: gap 3 mm, k_ant 4.75 N/mm, k_post 22.18 N/mm, no stiffness inside
  RestraintSpring s;
  s.gap = 3e-3;
  s.k_inside = 0.0;
  s.k_positive = 4.75e3;
  s.k_negative = 22.18e3;
  CHECK(spring_gap_force(s, 2.9e-3) == 0.0);
  CHECK(spring_gap_force(s, -2.9e-3) == 0.0);
  CHECK(spring_gap_force(s, 0.0) == 0.0);
  CHECK(spring_gap_force(s, 4e-3) == doctest::Approx(-4.75).epsilon(1e-12));
  CHECK(spring_gap_force(s, -5e-3) == doctest::Approx(44.36).epsilon(1e-12));
  // continuity at +-gap: the limits from both sides agree (to the rounding of one ulp of x)
  for (double g : {s.gap, -s.gap}) {
    const double in = spring_gap_force(s, std::nextafter(g, 0.0));
    const double out = spring_gap_force(s, std::nextafter(g, 2.0 * g));
    CHECK(std::abs(in - out) < 1e-12);
  }
}

TEST_CASE("spring-gap law with stiffness inside the gap (ISO-like preset) is continuous") {
  // inside: -k_in x; beyond +g: -k_in g - k_out (x - g); beyond -g: +k_in g - k_out (x + g)
  RestraintSpring s;
  s.gap = 2.5e-3;
  s.k_inside = 9.3e3;
  s.k_positive = s.k_negative = 44e3;
  CHECK(spring_gap_force(s, 1e-3) == doctest::Approx(-9.3));
  CHECK(spring_gap_force(s, 3.5e-3) == doctest::Approx(-9.3 * 2.5 - 44.0));
  CHECK(spring_gap_force(s, -3.5e-3) == doctest::Approx(9.3 * 2.5 + 44.0));
  for (double g : {s.gap, -s.gap}) {
    const double in = spring_gap_force(s, std::nextafter(g, 0.0));
    const double out = spring_gap_force(s, std::nextafter(g, 2.0 * g));
    CHECK(std::abs(in - out) < 1e-9);
  }
  // odd symmetry for equal stiffnesses
  for (double x : {0.5e-3, 2.5e-3, 7e-3}) CHECK(spring_gap_force(s, -x) == -spring_gap_force(s, x));
}
