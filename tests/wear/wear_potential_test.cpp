// The wear potential and the other figures that do not depend on the wear factor
// (wear/wear_accumulator.h, wear/wear_loop.h), against closed forms:
//  - a uniform contact on a flat box: potential = sarkar(mu) p A_total v dt steps (Archard),
//    the same times (p / p_ref)^-alpha (pressure-dependent), sliding distance = v dt steps,
//    cross-shear 0 for sliding along one direction;
//  - a whole run on the coarse default model with one geometry update, i.e. all its wear
//    computed on the pristine geometry: depth-integral volume = k x potential per cycle x
//    the law's effective cycles, to round-off, for every law (the definition of the potential:
//    what the law multiplies by its coefficient); and the run potential k x W_run equals it;
//  - the pressure-dependent law with exponent 0 reproduces the constant-factor run bit for bit.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "models/build_model.h"
#include "tests/wear/wear_fixtures.h"
#include "wear/archard.h"
#include "wear/wear_accumulator.h"
#include "wear/wear_loop.h"

using namespace kneesim;

namespace {

const models::BuiltModel& coarse_model() {
  static const models::BuiltModel built = models::build_model(test::coarse_config());
  return built;
}

wear::WearOptions one_update(const models::BuiltModel& built, wear::WearLaw law, long cycles) {
  wear::WearOptions o;
  o.total_cycles = cycles;
  o.update_every = cycles;
  o.law.law = law;
  o.law.wear_factor = built.material.wear_factor_mm3_per_Nmm * wear::kWearFactorSI;
  o.law.friction = built.model.contact.friction;
  o.law.alpha = 1.0;                 // pressure-dependent: k falls as 1/p
  o.law.p_ref = 10e6;
  o.law.beta = 5.0;                  // cross-shear gain
  o.law.running_in_excess = 2.0;     // running-in: 3x the rate at the start
  o.law.running_in_cycles = 1e5;
  o.identity = 0x9071;
  return o;
}

}  // namespace

TEST_CASE("wear potential of a uniform contact: closed form per law") {
  // a 20 x 10 mm flat box, every top element at p = 12 MPa sliding at 30 mm/s along x
  engine::Model m;
  const models::TriMesh box = test::make_flat_box(0.02, 0.01, 0.008, 6, 0.3, 7);
  std::vector<int> top;
  for (int t = 0; t < static_cast<int>(box.triangles.size()); ++t) {
    const auto& tri = box.triangles[t];
    if (box.vertices[tri[0]].y() > 0.0079 && box.vertices[tri[1]].y() > 0.0079 &&
        box.vertices[tri[2]].y() > 0.0079) {
      top.push_back(t);
    }
  }
  double area = 0.0;
  for (int t : top) {
    const auto& tri = box.triangles[t];
    const double a = 0.5 * (box.vertices[tri[1]] - box.vertices[tri[0]])
                               .cross(box.vertices[tri[2]] - box.vertices[tri[0]])
                               .norm();
    m.insert.area.push_back(a);
    area += a;
  }
  m.dt = 1e-4;
  const double p = 12e6, v = 0.03, mu = 0.07;
  const int steps = 200;
  const engine::Data d = test::make_uniform_contact(m.insert, p, v);
  REQUIRE(m.insert.size() == static_cast<int>(top.size()));
  for (const double alpha : {0.0, 1.0, -0.5}) {
    wear::WearLawParams law;
    law.law = alpha == 0.0 ? wear::WearLaw::kArchard : wear::WearLaw::kPressureDependent;
    law.wear_factor = 2.643e-16;
    law.friction = mu;
    law.alpha = alpha;
    law.p_ref = 10e6;
    wear::WearAccumulator acc(m.insert.size(), law);
    for (int s = 0; s < steps; ++s) acc.observe(m, engine::State{}, d);
    const double expected =
        wear::sarkar_factor(mu) * std::pow(p / law.p_ref, -alpha) * p * area * v * m.dt * steps;
    CHECK(acc.wear_potential() == doctest::Approx(expected).epsilon(1e-12).scale(0));
    CHECK(acc.sliding_distance() == doctest::Approx(v * m.dt * steps).epsilon(1e-12).scale(0));
    CHECK(acc.mean_cross_shear() == doctest::Approx(0.0));
    // volume of the cycle = k x potential: the accumulator's own depth field agrees
    double volume = 0.0;
    const std::vector<double> depth = acc.depth_per_cycle();
    for (int e = 0; e < m.insert.size(); ++e) volume += depth[e] * m.insert.area[e];
    CHECK(volume ==
          doctest::Approx(law.wear_factor * acc.wear_potential()).epsilon(1e-12).scale(0));
  }
}

TEST_CASE("k x wear potential = the run's volume on the pristine geometry, every law") {
  const models::BuiltModel& built = coarse_model();
  const long cycles = 200'000;
  for (const wear::WearLaw law :
       {wear::WearLaw::kArchard, wear::WearLaw::kPressureDependent, wear::WearLaw::kCrossShear,
        wear::WearLaw::kRunningIn, wear::WearLaw::kIncubation}) {
    CAPTURE(static_cast<int>(law));
    const wear::WearOptions o = one_update(built, law, cycles);
    const wear::WearResult r = wear::run_wear(built, o);
    REQUIRE(r.status == engine::StepStatus::kOk);
    REQUIRE(r.records.size() == 2);
    const wear::UpdateRecord& pristine = r.records.front();
    const wear::UpdateRecord& worn = r.records.back();
    CHECK(pristine.wear_potential > 0.0);
    CHECK(pristine.sliding_distance > 0.0);
    CHECK(pristine.cross_shear > 0.0);  // the knee's sliding path turns: CS above 0
    CHECK(pristine.cross_shear < 0.5);
    CHECK(pristine.stance_mean_pressure > 0.0);
    CHECK(pristine.stance_mean_pressure < pristine.mean_peak_pressure);
    const double n_eff = wear::effective_cycles(o.law, 0.0, static_cast<double>(cycles));
    // closed form: the whole depth field came from one cycle on the pristine geometry
    CHECK(worn.volume_depth ==
          doctest::Approx(o.law.wear_factor * pristine.wear_potential * n_eff)
              .epsilon(1e-9)
              .scale(0));
    CHECK(o.law.wear_factor * wear::calc_run_wear_potential(r.records, o.law) ==
          doctest::Approx(worn.volume_depth).epsilon(1e-9).scale(0));
    // and the geometry's enclosed-volume loss is the same recession (bookkeeping, 1 %)
    CHECK(worn.volume == doctest::Approx(worn.volume_depth).epsilon(0.01).scale(0));
  }
}

TEST_CASE("pressure-dependent law with exponent 0 reproduces the constant-factor run exactly") {
  const models::BuiltModel& built = coarse_model();
  wear::WearOptions archard = one_update(built, wear::WearLaw::kArchard, 500'000);
  archard.update_every = 250'000;
  wear::WearOptions flat = archard;
  flat.law.law = wear::WearLaw::kPressureDependent;
  flat.law.alpha = 0.0;
  const wear::WearResult a = wear::run_wear(built, archard);
  const wear::WearResult b = wear::run_wear(built, flat);
  REQUIRE(a.records.size() == b.records.size());
  for (size_t u = 0; u < a.records.size(); ++u) {
    CHECK(std::memcmp(&a.records[u].cycles, &b.records[u].cycles,
                      sizeof(double) * wear::UpdateRecord::kFields) == 0);
  }
  CHECK(std::memcmp(a.vertex_depth.data(), b.vertex_depth.data(),
                    sizeof(double) * a.vertex_depth.size()) == 0);
}
