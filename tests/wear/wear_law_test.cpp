// The wear laws of wear/wear_law.h against closed forms and invariants (issue 25 acceptance):
//  - cross-shear ratio CS (Kang 2008: smallest over total principal frictional work): 0 for a
//    linear reciprocating path; b / (a + b) for a rectangular path of sides 2a x 2b (b < a) at
//    constant speed and pressure (the work along each side is p ds, so the tensor is
//    diag(4a, 4b) p per lap);
//  - the contact-area law (Abdelgaied 2011, V = C f(CS) A S): the volume of a flat contact of
//    fixed area A is C A S whatever the pressure, i.e. independent of the load;
//  - creep phi d_el (1 - exp(-t / tau)) saturates at phi d_el and is zero without creep;
//  - the config's [wear] section and the --wear-law/--law-param shorthands build the same
//    WearLawParams, and bad input is refused with one sentence naming key, value and range.
// Tolerances are rounding tolerances (closed forms evaluated in floating point).
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>

#include "engine/errors.h"
#include "engine/state.h"
#include "models/build_model.h"
#include "tests/wear/wear_fixtures.h"
#include "wear/archard.h"
#include "wear/geometry_update.h"
#include "wear/wear_accumulator.h"
#include "wear/wear_law.h"

using namespace kneesim;

namespace {

engine::InsertSurface flat_surface(int n) {
  const models::TriMesh box = test::make_flat_box(0.040, 0.030, 0.008, n, 0.0);
  return models::make_insert_surface(box, 0.0, 0.35, nullptr, nullptr);
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// steps of uniform contact at pressure p sliding with velocity (vx, 0, vz)
void slide(wear::WearAccumulator& acc, const engine::Model& model, double p, double vx,
           double vz, int steps) {
  engine::Data d = test::make_uniform_contact(model.insert, p, std::hypot(vx, vz));
  for (auto& u : d.slip_velocity_T) u = Eigen::Vector3d(vx, 0.0, vz);
  for (int i = 0; i < steps; ++i) acc.observe(model, engine::State{}, d);
}

}  // namespace

TEST_CASE("cross-shear ratio: 0 for linear reciprocation, b / (a + b) for a rectangular path") {
  engine::Model model;
  model.dt = 1e-3;
  model.insert = flat_surface(3);
  wear::WearLawParams law;
  law.law = wear::WearLaw::kCrossShear;
  law.wear_factor = 1e-16;
  law.beta = 4.0;
  const double p = 4e6, v = 0.03;

  // back and forth along x, 10 laps: the work tensor has no z component
  wear::WearAccumulator lin(model.insert.size(), law);
  for (int lap = 0; lap < 10; ++lap) {
    slide(lin, model, p, v, 0.0, 50);
    slide(lin, model, p, -v, 0.0, 50);
  }
  for (double cs : lin.cross_shear_ratio()) CHECK(cs == 0.0);
  // k f(CS) = k: the cross-shear law equals Archard on a linear path
  const double archard = 1e-16 * p * 1000 * v * model.dt * wear::sarkar_factor(law.friction);
  for (double d : lin.depth_per_cycle()) CHECK(rel(d, archard) < 1e-12);

  // rectangle 2a x 2b traversed at speed v: sides of 2a / (v dt) and 2b / (v dt) steps
  const int na = 60, nb = 20;  // a : b = 3 : 1 -> CS = 1/4
  wear::WearAccumulator rect(model.insert.size(), law);
  slide(rect, model, p, v, 0.0, na);
  slide(rect, model, p, 0.0, v, nb);
  slide(rect, model, p, -v, 0.0, na);
  slide(rect, model, p, 0.0, -v, nb);
  const double cs_expected = double(nb) / (na + nb);
  for (double cs : rect.cross_shear_ratio()) CHECK(rel(cs, cs_expected) < 1e-12);
  const double path = 2.0 * (na + nb) * v * model.dt;
  for (double d : rect.depth_per_cycle()) {
    CHECK(rel(d, 1e-16 * p * path * wear::sarkar_factor(law.friction) *
                     (1.0 + law.beta * cs_expected)) < 1e-12);
  }
}

TEST_CASE("contact-area law: volume C f(CS) A S, independent of the load at fixed area") {
  engine::Model model;
  model.dt = 1e-3;
  model.insert = flat_surface(6);
  const double area = std::accumulate(model.insert.area.begin(), model.insert.area.end(), 0.0);
  wear::WearLawParams law;
  law.law = wear::WearLaw::kContactArea;
  law.area_coefficient = 2.5e-6;
  law.wear_factor = 1e-16;  // not used by the area law
  const int steps = 400;
  const double v = 0.04, S = steps * v * model.dt;
  for (double beta : {0.0, 6.0}) {
    law.beta = beta;
    std::vector<double> volumes;
    for (double p : {1e6, 5e6, 2e7}) {  // the load F = p A changes twenty-fold
      wear::WearAccumulator acc(model.insert.size(), law);
      slide(acc, model, p, v, 0.0, steps);
      const std::vector<double> d = acc.depth_per_cycle();
      double volume = 0.0;
      for (int e = 0; e < model.insert.size(); ++e) volume += d[e] * model.insert.area[e];
      volumes.push_back(volume);
      CHECK(rel(volume, law.area_coefficient * area * S) < 1e-12);  // CS = 0: f = 1
      CHECK(acc.coefficient() == law.area_coefficient);
    }
    CHECK(volumes[0] == volumes[1]);
    CHECK(volumes[1] == volumes[2]);
  }
  // crossing path: f(CS) = 1 + g CS multiplies the volume, still without the load
  law.beta = 6.0;
  wear::WearAccumulator cross(model.insert.size(), law);
  slide(cross, model, 3e6, v, 0.0, steps / 2);
  slide(cross, model, 3e6, 0.0, v, steps / 2);
  for (double d : cross.depth_per_cycle()) {
    CHECK(rel(d, law.area_coefficient * S * (1.0 + 6.0 * 0.5)) < 1e-12);
  }
}

TEST_CASE("creep: phi d_el (1 - exp(-t / tau)) saturates at phi d_el; none without creep") {
  wear::WearLawParams law;
  law.creep = true;
  law.creep_ratio = 0.8;
  law.creep_time = 1000.0;
  const double d_el = 50e-6;
  CHECK(wear::creep_depth(law, d_el, 0.0) == 0.0);
  CHECK(rel(wear::creep_depth(law, d_el, 1000.0), 0.8 * d_el * (1.0 - std::exp(-1.0))) < 1e-14);
  CHECK(rel(wear::creep_depth(law, d_el, 1e6), 0.8 * d_el) < 1e-14);  // saturated
  double last = 0.0;  // grows monotonically with time
  for (double t : {1.0, 10.0, 100.0, 1e3, 1e4}) {
    const double c = wear::creep_depth(law, d_el, t);
    CHECK(c > last);
    last = c;
  }
  CHECK(wear::creep_depth(law, 2.0 * d_el, 500.0) == 2.0 * wear::creep_depth(law, d_el, 500.0));
  law.creep = false;
  CHECK(wear::creep_depth(law, d_el, 1e6) == 0.0);

  // the accumulator's cycle-mean penetration: half the cycle at d, half out of contact
  engine::Model model;
  model.dt = 1e-3;
  model.insert = flat_surface(2);
  law.creep = true;
  wear::WearAccumulator acc(model.insert.size(), law);
  engine::Data d = test::make_uniform_contact(model.insert, 2e6, 0.01);
  d.penetration.assign(model.insert.size(), 40e-6);
  engine::Data off = d;
  off.in_contact.clear();
  for (int i = 0; i < 100; ++i) acc.observe(model, engine::State{}, d);
  for (int i = 0; i < 100; ++i) acc.observe(model, engine::State{}, off);
  for (double m : acc.mean_penetration()) CHECK(rel(m, 20e-6) < 1e-12);
}

TEST_CASE("[wear] config and the --wear-law shorthands build the same law") {
  const models::Config a = models::load_config(
      "", {{"wear.law", "\"cross_shear\""}, {"wear.cross_shear_gain", "7.5"},
           {"wear.pressure_exponent", "0.3"}, {"wear.creep", "true"},
           {"wear.creep_time_s", "5000"}});
  std::vector<models::Override> o =
      wear::wear_law_overrides("cross_shear", {"beta=7.5", "alpha=0.3"});
  o.push_back({"wear.creep", "true"});
  o.push_back({"wear.creep_time_s", "5000"});
  const models::Config b = models::load_config("", o);
  const wear::WearLawParams la = wear::make_wear_law(a.wear, a.material, 0.07);
  const wear::WearLawParams lb = wear::make_wear_law(b.wear, b.material, 0.07);
  CHECK(la.law == wear::WearLaw::kCrossShear);
  CHECK(lb.law == la.law);
  CHECK(lb.beta == 7.5);
  CHECK(lb.alpha == 0.3);
  CHECK(lb.creep);
  CHECK(lb.creep_time == 5000.0);
  CHECK(la.beta == lb.beta);
  CHECK(la.wear_factor == 2.643e-10 * wear::kWearFactorSI);  // UHMWPE's k from the material
  for (const char* name : {"archard", "pressure_dependent_wear", "cross_shear", "contact_area",
                           "running_in", "incubation"}) {
    CHECK(wear::wear_law_name(wear::parse_wear_law(name, "test")) == name);
  }
}

TEST_CASE("bad wear-law input: one sentence naming key, value and the allowed values") {
  const auto message = [](const std::vector<models::Override>& o) {
    try {
      const models::Config c = models::load_config("", o);
      wear::make_wear_law(c.wear, c.material, 0.07);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // a law that does not exist
  std::string m = message({{"wear.law", "\"magic\""}});
  CHECK(m.find("wear.law") != std::string::npos);
  CHECK(m.find("magic") != std::string::npos);
  CHECK(m.find("cross_shear") != std::string::npos);
  // a parameter the law does not have
  m = message({{"wear.cross_shear_gain", "3"}});
  CHECK(m.find("wear.cross_shear_gain") != std::string::npos);
  CHECK(m.find("not a parameter of wear.law = \"archard\"") != std::string::npos);
  m = message(wear::wear_law_overrides("pressure_dependent_wear", {"beta=2"}));
  CHECK(m.find("wear.cross_shear_gain") != std::string::npos);
  // a parameter outside its range
  m = message({{"wear.law", "\"cross_shear\""}, {"wear.cross_shear_gain", "-1"}});
  CHECK(m.find("-1") != std::string::npos);
  CHECK(m.find("[0, 1000]") != std::string::npos);
  // creep with a non-positive time constant, and creep parameters without creep
  m = message({{"wear.creep", "true"}, {"wear.creep_time_s", "0"}});
  CHECK(m.find("wear.creep_time_s") != std::string::npos);
  CHECK(m.find("0.001") != std::string::npos);
  m = message({{"wear.creep_ratio", "0.5"}});
  CHECK(m.find("wear.creep = false") != std::string::npos);
  // the area law for a material without its coefficient
  m = message({{"wear.law", "\"contact_area\""}});
  CHECK(m.find("area_wear_coefficient") != std::string::npos);
  // a shorthand that is not name=number
  CHECK_THROWS_AS(wear::wear_law_overrides("cross_shear", {"beta"}), InputError);
  CHECK_THROWS_AS(wear::wear_law_overrides("cross_shear", {"beta=x"}), InputError);
}

TEST_CASE("material_pressure is the pressure-dependent law with the material's own n and p_ref") {
  // reference: k = k_ref (p / p_ref)^n is the kernel's k (p / p_ref)^-alpha with alpha = -n
  // (models/materials.toml: UHMWPE n = -1 at p_ref 10 MPa, PEEK n = +1)
  const models::Config u = models::load_config("", {{"wear.law", "\"material_pressure\""}});
  const wear::WearLawParams lu = wear::make_wear_law(u.wear, u.material, 0.07);
  CHECK(lu.law == wear::WearLaw::kPressureDependent);
  CHECK(lu.alpha == -u.material.wear_pressure_exponent);
  CHECK(lu.p_ref == u.material.wear_reference_pressure_MPa * 1e6);
  const models::Config p = models::load_config(
      "", {{"wear.law", "\"material_pressure\""}, {"material.name", "\"peek\""}});
  const wear::WearLawParams lp = wear::make_wear_law(p.wear, p.material, 0.06);
  CHECK(p.material.wear_pressure_exponent == 1.0);
  CHECK(lp.alpha == -1.0);
  CHECK(wear::parse_wear_law("material_pressure", "test") == wear::WearLaw::kPressureDependent);
  // its exponent is the material's: a [wear] exponent is refused, naming where it belongs
  try {
    models::load_config("", wear::wear_law_overrides("material_pressure", {"alpha=1"}));
    FAIL("accepted wear.pressure_exponent with material_pressure");
  } catch (const InputError& e) {
    const std::string m = e.what();
    CHECK(m.find("wear.pressure_exponent") != std::string::npos);
    CHECK(m.find("material_pressure") != std::string::npos);
    CHECK(m.find("wear_pressure_exponent") != std::string::npos);
  }
}
