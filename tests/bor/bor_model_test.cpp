// Block-on-ring semi-analytic model (physics.md section 7) against the sanity numbers printed
// there, closed forms and invariants. Tolerances: the printed numbers have three significant
// figures, so each is checked to half a unit in its last printed digit (about 0.5-1.5 %).
#include <doctest/doctest.h>

#include <cmath>

#include "engine/errors.h"
#include "wear/bor/bor_contact.h"
#include "wear/bor/bor_rig.h"
#include "wear/bor/bor_simulation.h"
#include "wear/bor/bor_wear_law.h"

using namespace kneesim::bor;

namespace {
constexpr double kMm = 1e-3;
constexpr double kMm3 = 1e-9;
constexpr double kMPa = 1e6;
}  // namespace

TEST_CASE("foundation constant and Sarkar factor of the Hussin rig") {
  const BorRig rig;
  // physics.md: C ~ 81.5 MPa/mm with E 690 MPa, nu 0.317, h 12 mm
  CHECK(foundation_constant(rig) * kMm / kMPa == doctest::Approx(81.5).epsilon(0.001));
  // physics.md section 6: 1.053 for mu 0.19, 1.007 for mu 0.07
  CHECK(sarkar_factor(0.19) == doctest::Approx(1.053).epsilon(0.0005).scale(0));
  CHECK(sarkar_factor(0.07) == doctest::Approx(1.007).epsilon(0.0005).scale(0));
  CHECK(sarkar_factor(0.0) == 1.0);
}

TEST_CASE("unworn contact reproduces physics.md section 7 at 225 N and 130 N") {
  const BorRig rig;
  const BorContact c225 = solve_bor_contact(rig, 225.0, 0.0);
  CHECK(c225.contact_width / 2.0 / kMm == doctest::Approx(1.93).epsilon(0.005 / 1.93).scale(0));
  CHECK(c225.penetration / kMm == doctest::Approx(0.107).epsilon(0.0005 / 0.107).scale(0));
  CHECK(c225.mean_pressure / kMPa == doctest::Approx(5.8).epsilon(0.05 / 5.8).scale(0));
  const BorContact c130 = solve_bor_contact(rig, 130.0, 0.0);
  CHECK(c130.contact_width / 2.0 / kMm == doctest::Approx(1.61).epsilon(0.005 / 1.61).scale(0));
  CHECK(c130.penetration / kMm == doctest::Approx(0.074).epsilon(0.0005 / 0.074).scale(0));
  CHECK(c130.mean_pressure / kMPa == doctest::Approx(4.0).epsilon(0.05 / 4.0).scale(0));
  // equilibrium invariant: F = C R_c^2 w seg(theta)
  const double rc = rig.ring_radius;
  CHECK(foundation_constant(rig) * rc * rc * rig.ring_width * segment_factor(c225.theta) ==
        doctest::Approx(225.0).epsilon(1e-10));
}

TEST_CASE("Archard volume at 200 000 cycles is 2.03 and 1.17 mm^3") {
  const BorRig rig;
  const BorWearParams p;  // k_D = 4.1e-10 mm^3/(N mm)
  const double s = sliding_distance_per_cycle(rig);
  CHECK(s / kMm == doctest::Approx(M_PI * 35.0));
  // printed to two decimals: tolerance 0.005 mm^3
  CHECK(closed_form_volume(BorWearLaw::archard, p, 225.0, s, 2e5) / kMm3 ==
        doctest::Approx(2.03).epsilon(0.005 / 2.03).scale(0));
  CHECK(closed_form_volume(BorWearLaw::archard, p, 130.0, s, 2e5) / kMm3 ==
        doctest::Approx(1.17).epsilon(0.005 / 1.17).scale(0));
  // the full solve carries the same volume through the geometry
  const auto rows = simulate_bor(rig, 225.0, BorWearLaw::archard, p, {0.0, 2e5});
  CHECK(rows[1].volume / kMm3 == doctest::Approx(2.0287).epsilon(1e-4).scale(0));
}

TEST_CASE("worn contact satisfies all three equations from 0 to 1e6 cycles") {
  const BorRig rig;
  const BorWearParams p;
  const double rc = rig.ring_radius, w = rig.ring_width, cf = foundation_constant(rig);
  for (double load : {130.0, 225.0}) {
    std::vector<double> cycles;
    for (int i = 0; i <= 100; ++i) cycles.push_back(1e4 * i);
    const auto rows = simulate_bor(rig, load, BorWearLaw::archard, p, cycles);
    double prev_depth = -1.0, prev_width = 0.0;
    for (size_t i = 1; i < rows.size(); ++i) {
      const BorRow& r = rows[i];
      CAPTURE(load);
      CAPTURE(r.cycles);
      // scar spans the contact, circular-segment volume, foundation equilibrium
      CHECK(rc * std::sin(r.theta) ==
            doctest::Approx(r.scar_radius * std::sin(r.theta_scar)).scale(0));
      CHECK(r.scar_radius * r.scar_radius * segment_factor(r.theta_scar) * w ==
            doctest::Approx(r.volume).epsilon(1e-9).scale(0));
      CHECK(cf * (rc * rc * segment_factor(r.theta) * w - r.volume) ==
            doctest::Approx(load).epsilon(1e-9));
      // the scar is flatter than the ring, depth and width grow, pressure falls
      CHECK(r.scar_radius > rc);
      CHECK(r.depth > prev_depth);
      CHECK(r.contact_width > prev_width);
      CHECK(r.mean_pressure < rows[i - 1].mean_pressure);
      prev_depth = r.depth;
      prev_width = r.contact_width;
    }
  }
}

TEST_CASE("tiny wear tends to the unworn contact and a shallow scar") {
  const BorRig rig;
  const BorContact c0 = solve_bor_contact(rig, 225.0, 0.0);
  const BorContact c = solve_bor_contact(rig, 225.0, 1e-6 * kMm3);
  CHECK(c.theta == doctest::Approx(c0.theta).epsilon(1e-6).scale(0));
  // flat-scar limit: V = (2/3) a^2 theta' w with a the half-width, depth = 3 V / (4 a w)
  const double a = c.contact_width / 2.0;
  CHECK(c.scar_depth ==
        doctest::Approx(0.75 * c.volume / (a * rig.ring_width)).epsilon(1e-5).scale(0));
}

TEST_CASE("running-in and creep laws against their closed forms") {
  const BorRig rig;
  BorWearParams p;
  p.running_in_excess = 2.0;
  p.running_in_cycles = 10000.0;
  const double s = sliding_distance_per_cycle(rig);
  const double per = p.k * 225.0 * s;
  // long after running-in, the curve is the steady line offset by a N_r k F S
  const double v = closed_form_volume(BorWearLaw::running_in, p, 225.0, s, 3e5);
  CHECK(v == doctest::Approx(per * (3e5 + 2.0 * 1e4)).epsilon(1e-9).scale(0));
  // initial rate is (1 + a) k F S
  CHECK(closed_form_volume(BorWearLaw::running_in, p, 225.0, s, 1.0) ==
        doctest::Approx(3.0 * per).epsilon(1e-4).scale(0));
  // creep: volume as Archard, depth above the wear-only depth by phi delta_el (1 - e^-t/tau)
  p.creep_ratio = 0.5;
  p.creep_time = 3600.0;
  const auto wear_only = simulate_bor(rig, 225.0, BorWearLaw::archard, p, {6e4});
  const auto crept = simulate_bor(rig, 225.0, BorWearLaw::creep, p, {6e4});
  CHECK(crept[0].volume == wear_only[0].volume);
  const double delta_el = solve_bor_contact(rig, 225.0, 0.0).penetration;
  const double t = 6e4 * 60.0 / 1000.0;
  CHECK(crept[0].depth - wear_only[0].depth ==
        doctest::Approx(0.5 * delta_el * (1.0 - std::exp(-t / 3600.0))).epsilon(1e-12).scale(0));
}

TEST_CASE("pressure-dependent wear: CVODE path, table path and the alpha = 0 limit agree") {
  const BorRig rig;
  BorWearParams p;
  p.pressure_exponent = 1.0;
  p.reference_pressure = 5.8e6;
  const std::vector<double> cycles = {0.0, 5e4, 1e5, 2e5, 5e5};
  const auto ref = simulate_bor(rig, 130.0, BorWearLaw::pressure_dependent_wear, p, cycles);
  BorContactTable table(rig, 130.0, 1.0 * kMm3);
  const auto fast =
      simulate_bor_table(table, rig, BorWearLaw::pressure_dependent_wear, p, cycles);
  const double archard_200k =
      closed_form_volume(BorWearLaw::archard, p, 130.0, sliding_distance_per_cycle(rig), 2e5);
  for (size_t i = 1; i < cycles.size(); ++i) {
    CAPTURE(cycles[i]);
    CHECK(fast[i].volume == doctest::Approx(ref[i].volume).epsilon(1e-4).scale(0));
    CHECK(fast[i].depth == doctest::Approx(ref[i].depth).epsilon(1e-4).scale(0));
  }
  // at 130 N the pressure is below p_ref, so alpha = 1 wears faster than Archard
  CHECK(ref[3].volume > 1.3 * archard_200k);
  p.pressure_exponent = 0.0;
  const auto flat = simulate_bor(rig, 130.0, BorWearLaw::pressure_dependent_wear, p, cycles);
  CHECK(flat[3].volume == doctest::Approx(archard_200k).epsilon(1e-7).scale(0));
}

TEST_CASE("wear-law names and parameters validate their input") {
  CHECK(parse_wear_law("none", "test") == BorWearLaw::archard);
  CHECK(parse_wear_law("creep", "test") == BorWearLaw::creep);
  CHECK_THROWS_AS(parse_wear_law("cross_shear", "test"), kneesim::InputError);
  BorWearParams p;
  set_wear_param(p, "reference_pressure_MPa", 4.0, "test");
  CHECK(p.reference_pressure == 4.0e6);
  CHECK(get_wear_param(p, "reference_pressure_MPa") == 4.0);
  CHECK_THROWS_AS(set_wear_param(p, "creep_time_s", -1.0, "test"), kneesim::InputError);
  CHECK_THROWS_AS(set_wear_param(p, "bogus", 1.0, "test"), kneesim::InputError);
  BorRig rig;
  rig.poisson_ratio = 0.5;
  CHECK_THROWS_AS(check_rig(rig, "test"), kneesim::InputError);
}

TEST_CASE("table interpolation does not depend on the volumes asked for before") {
  // determinism: a table extended by an earlier large request gives bit-identical values
  const BorRig rig;
  BorContactTable fresh(rig, 225.0, 1.0 * kMm3);
  BorContactTable used(rig, 225.0, 1.0 * kMm3);
  used.at(7.3 * kMm3);
  for (double v : {0.05, 0.5, 0.99, 2.5}) {
    const BorContact a = fresh.at(v * kMm3);
    const BorContact b = used.at(v * kMm3);
    CHECK(a.scar_depth == b.scar_depth);
    CHECK(a.mean_pressure == b.mean_pressure);
  }
  // and the interpolation matches a direct solve to 1e-5 relative
  const BorContact direct = solve_bor_contact(rig, 225.0, 0.77 * kMm3);
  CHECK(fresh.at(0.77 * kMm3).scar_depth ==
        doctest::Approx(direct.scar_depth).epsilon(1e-5).scale(0));
  CHECK(fresh.at(0.77 * kMm3).contact_width ==
        doctest::Approx(direct.contact_width).epsilon(1e-5).scale(0));
}

TEST_CASE("incubation law: closed form against a quadrature of its rate factor") {
  // reference: the volume is the integral of the rate factor 1 - exp(-N / N_i) times k F S,
  // integrated here by Simpson's rule (independent of the closed form); limits: the initial
  // rate is zero, and long after N_i the curve is the steady line shifted by N_i cycles
  const BorRig rig;
  BorWearParams p;
  p.incubation_cycles = 25000.0;
  const double s = sliding_distance_per_cycle(rig);
  const double per = p.k * 225.0 * s;
  for (double n : {1e3, 2.5e4, 5e4, 2e5}) {
    const int m = 2000;
    double sum = 0.0;
    for (int i = 0; i <= m; ++i) {
      const double w = (i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      sum += w * wear_rate_factor(BorWearLaw::incubation, p, n * i / m, 0.0);
    }
    const double quadrature = per * sum * n / (3.0 * m);
    CHECK(closed_form_volume(BorWearLaw::incubation, p, 225.0, s, n) ==
          doctest::Approx(quadrature).epsilon(1e-9).scale(0));
  }
  CHECK(wear_rate_factor(BorWearLaw::incubation, p, 0.0, 0.0) == 0.0);
  CHECK(closed_form_volume(BorWearLaw::incubation, p, 225.0, s, 1e6) ==
        doctest::Approx(per * (1e6 - 25000.0)).epsilon(1e-12).scale(0));
  CHECK(parse_wear_law("incubation", "test") == BorWearLaw::incubation);
  CHECK(wear_law_param_names(BorWearLaw::incubation) ==
        std::vector<std::string>{"incubation_cycles"});
}
