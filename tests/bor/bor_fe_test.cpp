// Numerical block-on-ring model (wear/bor/bor_fe.h) on a coarse mesh, fast enough for the
// default suite. References:
// - the unworn contact against Hertz line contact (plane strain at the ring's mid-plane,
//   P' the centre row's line load, b = sqrt(4 P' R / (pi E*)), p0 = 2 P' / (pi b), E* = E / (1 - nu^2)); the block
//   is 12 mm deep against b = 0.8 mm, close to the half-space. Tolerance 10 %: the coarse mesh
//   puts 8 elements in the half-width and the penalty's compliance adds about 2 % (the fine
//   Hertz test in tests/engine/solid_contact_test.cpp holds 5 % with 13 elements);
// - the ring's reaction equals the dead load to the relaxation tolerance (0.1 %);
// - the worn volume after the first update, measured from the worn surface, against the
//   semi-analytic model's first step k F S dN (Archard; 2 %: the normal nodal forces exceed the
//   vertical load by 1 - cos of the contact slope, and the wear integration is nodal);
// - the surface recedes where the pressure is (deepest at the centre, none outside the contact).
#include <doctest/doctest.h>

#include <cmath>

#include "engine/errors.h"
#include "wear/bor/bor_fe.h"

using namespace kneesim;
using namespace kneesim::bor;

namespace {

BorFeOptions coarse_options() {
  BorFeOptions o;
  o.element_size = 0.1e-3;
  o.fine_half_width = 1.2e-3;
  o.fine_depth = 0.4e-3;
  o.growth = 1.4;
  o.axial_element_size = 2.5e-3;
  o.update_cycles = 10000.0;
  return o;
}

}  // namespace

TEST_CASE("block-on-ring FE: unworn contact against Hertz, first update against k F S dN") {
  const BorRig rig;
  const BorWearParams params;  // k_D 4.1e-10 mm^3/(N mm)
  const double load = 225.0;
  BorFeMeshInfo info;
  const auto rows = simulate_bor_fe(rig, load, params, {0.0, 10000.0}, coarse_options(),
                                    [&](const BorFeRow&, const BorFeMeshInfo& i) { info = i; });
  REQUIRE(rows.size() == 2);
  const BorFeRow& unworn = rows[0];
  const BorFeRow& worn = rows[1];

  // Hertz at the centre row's own line load (the ring's edges carry more than F / w)
  const double p_line = unworn.centre_line_load;
  const double e_star = rig.youngs_modulus / (1.0 - rig.poisson_ratio * rig.poisson_ratio);
  const double b = std::sqrt(4.0 * p_line * rig.ring_radius / (M_PI * e_star));
  const double p0 = 2.0 * p_line / (M_PI * b);
  const double kfsn = params.k * load * sliding_distance_per_cycle(rig) * 10000.0;
  MESSAGE("FE block-on-ring, " << info.elements << " elements (half block), dt " << info.dt * 1e9
          << " ns, alpha " << info.damping_alpha << " 1/s; unworn: centre line load " << p_line * 1e-3
          << " N/mm (F / w " << load / rig.ring_width * 1e-3 << "), " << unworn.relax_steps
          << " steps, reaction " << unworn.contact_force << " N, half-width (second moment) "
          << unworn.hertz_half_width * 1e3 << " mm, (contact nodes) "
          << 0.5e3 * unworn.row.contact_width << " mm vs Hertz " << b * 1e3 << " mm; centre-row peak "
          << unworn.centre_peak_pressure * 1e-6 << " MPa (edge " << unworn.peak_pressure * 1e-6 << ") vs " << p0 * 1e-6 << " MPa; first update: "
          << worn.relax_steps << " steps, volume " << worn.row.volume * 1e9 << " mm3 (nodal sum "
          << worn.wear_sum_volume * 1e9 << ") vs k F S dN " << kfsn * 1e9 << " mm3, depth "
          << worn.row.depth * 1e3 << " mm");
  CHECK(unworn.contact_force == doctest::Approx(load).epsilon(1e-3));
  CHECK(unworn.hertz_half_width == doctest::Approx(b).epsilon(0.10).scale(0));
  CHECK(unworn.centre_peak_pressure == doctest::Approx(p0).epsilon(0.10));
  CHECK(unworn.row.volume == 0.0);
  CHECK(worn.contact_force == doctest::Approx(load).epsilon(1e-3));
  CHECK(worn.row.volume == doctest::Approx(kfsn).epsilon(0.02).scale(0));
  // the deepest wear is the centre's Hertz pressure over dN revolutions (coarse: 10 %)
  CHECK(worn.row.depth == doctest::Approx(params.k * p0 * sliding_distance_per_cycle(rig) * 10000.0)
                              .epsilon(0.10)
                              .scale(0));
  // a worn surface conforms: wider contact, lower peak
  CHECK(worn.row.contact_width > unworn.row.contact_width);
  CHECK(worn.peak_pressure < unworn.peak_pressure);
}

TEST_CASE("block-on-ring FE: options out of range are one sentence naming the option") {
  const BorRig rig;
  BorFeOptions o;
  o.element_size = 5e-3;
  CHECK_THROWS_WITH_AS(check_bor_fe_options(o, rig),
                       doctest::Contains("--fe-element-mm = 5 mm"), InputError);
  o = BorFeOptions{};
  o.update_cycles = 0.5;
  CHECK_THROWS_WITH_AS(check_bor_fe_options(o, rig), doctest::Contains("--update-every = 0.5"),
                       InputError);
  o = BorFeOptions{};
  o.axial_element_size = 6e-3;
  CHECK_THROWS_WITH_AS(check_bor_fe_options(o, rig),
                       doctest::Contains("--fe-axial-element-mm = 6 mm"), InputError);
}
