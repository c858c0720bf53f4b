// A smooth sphere (radius R, load F) pressed on a steel half-space by the contact solver on an
// n x n grid spanning +-(span/2) a, with the Hertz values (Johnson, Contact Mechanics, 1985,
// section 4.2) it is checked against: contact radius a and peak pressure p0. Shared by the
// contact and the subsurface-stress tests.
#pragma once

#include <cmath>
#include <vector>

#include "wear/particles/contact.h"
#include "wear/particles/deflection.h"

namespace kneesim::test {

struct HertzSphere {
  double a = 0.0;   // Hertz contact radius [m]
  double p0 = 0.0;  // Hertz peak pressure [Pa]
  particles::Grid grid;
  double hardness = 0.0;  // the cap used, 0 when none [Pa]
  particles::ContactResult contact;
};

// hardness_over_p0 > 0 caps the pressure at that fraction of the Hertz peak
inline HertzSphere solve_hertz_sphere(double radius, double load, int n, double span,
                                      double hardness_over_p0 = 0.0) {
  constexpr double kPi = 3.14159265358979323846;
  const particles::ElasticBody steel{210e9, 0.3};
  const double e_star = 1.0 / (2.0 * particles::compliance(210e9, 0.3));
  HertzSphere s;
  s.a = std::cbrt(3.0 * load * radius / (4.0 * e_star));
  s.p0 = 3.0 * load / (2.0 * kPi * s.a * s.a);
  s.grid = particles::Grid{n, n, span * s.a / n, span * s.a / n, false};
  const particles::Grid& g = s.grid;
  particles::DeflectionOperator op(g, steel, steel);
  std::vector<double> h(g.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) h[i * n + j] = (g.x(i) * g.x(i) + g.y(j) * g.y(j)) / (2 * radius);
  particles::ContactOptions opt;
  opt.load = load;
  if (hardness_over_p0 > 0.0) opt.hardness = hardness_over_p0 * s.p0;
  s.hardness = hardness_over_p0 > 0.0 ? opt.hardness : 0.0;
  s.contact = particles::solve_contact(op, h, opt);
  return s;
}

}  // namespace kneesim::test
