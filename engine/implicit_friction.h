// Implicit friction of one carriage DOF in the central-difference step (physics.md section 5).
//
// The regularized Coulomb law t = -mu p v / sqrt(|v|^2 + eps^2) is a stiff damper near stick
// (slope mu N / eps): explicit it would need a step far below the contact's. The contact stage
// gives, per DOF and at the old rate v, the friction force F, its secant slope
// c = sum_e c_e |J_e,t|^2 (c_e = mu p_e A_e / sqrt(|v_e|^2 + eps^2), J_e,t the element's
// tangential slip per unit DOF rate) and a bound Phi on the friction the DOF can receive at
// all (sum_e mu p_e A_e |J_e,t|). The step takes the friction at the new rate u as the secant
// line capped at the Coulomb bound,
//   F(u) = clamp(F - c (u - v), -Phi, Phi),
// and solves m (u - v) / dt = G + F(u) exactly (G: every other generalized force; the left
// side rises with u, the right side does not, so the root is unique and one of three
// branches, in closed form).
//
// Why the cap: the secant line alone (the update used before) is stable for any eps and
// never lets a DOF chatter through zero slip, but near stick its slope mu N / eps acts as an
// added mass c dt, hundreds of kg at eps = 0.1 mm/s: a DOF whose other forces exceed the
// friction needed tens of steps to break away, and the ranges of motion moved with dt and with
// the carriage masses (issue 24). With the cap the friction never exceeds what Coulomb's law
// allows, so the DOF breaks away in the step its other forces exceed it. Rejected: the tangent
// slope (Rosenbrock-Euler) and a one-element saturating law fitted to F, c and the tangent:
// a light carriage overshot through zero slip with the full Coulomb force and chattered, which
// added sliding and wear (+19 % against the CVODE reference at the default step).
#pragma once

#include <algorithm>

namespace kneesim::engine {

// the rate u [m/s or rad/s] after one step of a DOF at rate v whose update without friction
// is a (u - v) = G: a = m / dt for a generalized mass m [kg or kg m^2] and step dt [s]
// [N s/m or N m s/rad], G the other generalized forces [N or N m]; F the friction at v, c its
// secant slope [N s/m or N m s/rad] and phi its Coulomb bound [N or N m] (c, phi >= 0)
inline double find_implicit_friction_rate(double v, double a, double G, double F, double c,
                                          double phi) {
  if (!(c > 0.0)) return v + (G + F) / a;  // no friction on this DOF: explicit
  // x = u - v; the secant line F - c x leaves [-phi, phi] below x_hi and above x_lo
  const double x_hi = (F - phi) / c;  // F(u) = +phi for x <= x_hi
  const double x_lo = (F + phi) / c;  // F(u) = -phi for x >= x_lo
  const double x_mid = (G + F) / (a + c);
  if (x_mid >= x_hi && x_mid <= x_lo) return v + x_mid;
  if (x_mid < x_hi) return v + std::min((G + phi) / a, x_hi);
  return v + std::max((G - phi) / a, x_lo);
}

}  // namespace kneesim::engine
