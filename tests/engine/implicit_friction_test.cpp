// The implicit friction update of one carriage DOF (engine/implicit_friction.h) against closed
// forms of its equation a (u - v) = G + clamp(F - c (u - v), -Phi, Phi), and a one-DOF block
// on a moving belt integrated with it against Coulomb's law. References:
//  - no friction (c = 0): the explicit update u = v + (G + F) / a;
//  - inside the cap: the secant-implicit update u = v + (G + F) / (a + c) (the update used
//    before the cap, unchanged where the friction stays within Coulomb's bound);
//  - breakaway: a block at rest under a pull G above its Coulomb bound Phi accelerates at
//    (G - Phi) / m from the first step (the secant update alone gives nearly zero: its slope
//    mu N / eps acts as an added mass c dt);
//  - the solution makes both sides equal and is monotone in G (unique root);
//  - a block dragged by a belt (slip v_belt - u) under a spring: it sticks to the belt while
//    the spring force is below mu N and then slides with the spring force at mu N (stick-slip
//    closed form: the spring stretches to mu N / k while sticking).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "engine/implicit_friction.h"

using kneesim::engine::find_implicit_friction_rate;

namespace {

// the equation's residual a (u - v) - G - clamp(F - c (u - v), -phi, phi)
double residual(double u, double v, double a, double G, double F, double c, double phi) {
  return a * (u - v) - G - std::clamp(F - c * (u - v), -phi, phi);
}

}  // namespace

TEST_CASE("implicit friction: closed forms of the three branches") {
  const double a = 500.0, v = 0.01;
  // no friction on the DOF: explicit
  CHECK(find_implicit_friction_rate(v, a, 20.0, 0.0, 0.0, 0.0) == doctest::Approx(v + 20.0 / a));
  // sliding at 10 mm/s, friction -50 N, secant 5000 N s/m, bound 60 N: a small push stays on
  // the secant line
  const double c = 5000.0, F = -50.0, phi = 60.0;
  const double u = find_implicit_friction_rate(v, a, 5.0, F, c, phi);
  CHECK(u == doctest::Approx(v + (5.0 + F) / (a + c)).epsilon(1e-14));
  CHECK(std::abs(residual(u, v, a, 5.0, F, c, phi)) < 1e-9);
  // a large pull saturates the friction at -phi: u = v + (G - phi) / a
  const double u_pull = find_implicit_friction_rate(v, a, 400.0, F, c, phi);
  CHECK(u_pull == doctest::Approx(v + (400.0 - phi) / a).epsilon(1e-14));
  // a large push the other way saturates it at +phi
  const double u_push = find_implicit_friction_rate(v, a, -900.0, F, c, phi);
  CHECK(u_push == doctest::Approx(v + (-900.0 + phi) / a).epsilon(1e-14));
  // the root is unique: every answer satisfies the equation and rises with G
  double last = -1e300;
  for (double G = -2000.0; G <= 2000.0; G += 7.0) {
    const double r = find_implicit_friction_rate(v, a, G, F, c, phi);
    CHECK(std::abs(residual(r, v, a, G, F, c, phi)) < 1e-9 * (1.0 + std::abs(G)));
    CHECK(r >= last);
    last = r;
  }
}

TEST_CASE("implicit friction: breakaway from stick in the first step") {
  // a 0.06 kg block at rest on a contact carrying 2000 N, mu 0.07 (Phi = 140 N), eps 0.1 mm/s:
  // secant slope at zero slip mu N / eps = 1.4e6 N s/m; dt = 0.46 ms
  const double m = 0.06, dt = 4.6e-4, phi = 140.0, c = phi / 1e-4;
  const double G = 200.0;  // pull above the bound
  const double u = find_implicit_friction_rate(0.0, m / dt, G, 0.0, c, phi);
  CHECK(u == doctest::Approx(dt * (G - phi) / m).epsilon(1e-12));  // Newton: (G - Phi) / m
  // the secant update alone barely moves: (G + F) / (a + c) = 0.14 mm/s
  CHECK((G + 0.0) / (m / dt + c) < 2e-4);
  // a pull below the bound keeps it stuck to within eps
  const double u_stuck = find_implicit_friction_rate(0.0, m / dt, 100.0, 0.0, c, phi);
  CHECK(std::abs(u_stuck) < 1e-4);
}

TEST_CASE("implicit friction: a block on a moving belt sticks, then slides at mu N") {
  // block of mass m on a belt moving at 10 mm/s, held by a spring k from a fixed point; the
  // regularized friction with the block's slip (belt - block) at each step gives F, c and the
  // bound mu N. Closed form: it moves with the belt until k x = mu N, then stays there
  // (steady sliding) with the spring force mu N.
  const double m = 0.06, dt = 1e-4, k = 2e4, muN = 50.0, eps = 1e-4, belt = 0.01;
  double x = 0.0, u = 0.0;
  double max_force = 0.0;
  for (int n = 0; n < 20000; ++n) {  // 2 s
    const double slip = belt - u;
    const double s = std::sqrt(slip * slip + eps * eps);
    const double F = muN * slip / s;  // friction on the block, along the belt's motion
    const double c = muN / s;
    u = find_implicit_friction_rate(u, m / dt, -k * x, F, c, muN);
    x += dt * u;
    max_force = std::max(max_force, k * x);
    if (n * dt > 0.01 && n * dt < 0.2) CHECK(u == doctest::Approx(belt).epsilon(0.02));  // stuck
  }
  CHECK(k * x == doctest::Approx(muN).epsilon(0.01));      // sliding at the Coulomb force
  CHECK(max_force <= muN * 1.01);                          // never beyond it
}
