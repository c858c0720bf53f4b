// The default prediction of issue 3 (test_wear_long, label "long": ~6 s CPU): 5 million cycles
// of the default gait on the stanmore rig, built-in implant at its default 1 mm resolution,
// UHMWPE (k = 2.643e-10 mm^3/(N mm)), a geometry update every 250 000 cycles. References:
//  - volume bookkeeping at every update: enclosed-volume loss vs depth integral within 1 %
//    (issue 3 acceptance; the difference grows with depth as the dish's curvature matters);
//  - the wear rate against the measurement of the same rig with the same wear factor: Pal 2008
//    measured 78 and 97 mg after 5 Mc on the Stanmore simulator (NexGen CR), i.e. 16.8 and
//    20.9 mm^3/Mc at 0.93 mg/mm^3, mean 18.8 mm^3/Mc; the generic implant is not the NexGen, so
//    the band is that mean +-50 %: 9.4-28.2 mm^3/Mc (measured here: 14.1);
//  - the worn insert stays watertight, with no face inverted against the pristine one.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "models/build_model.h"
#include "models/config.h"
#include "wear/archard.h"
#include "wear/geometry_update.h"
#include "wear/wear_loop.h"

using namespace kneesim;

TEST_CASE("default 5 Mc UHMWPE prediction: bookkeeping within 1 %, rate within Pal 2008's band") {
  const auto t0 = std::chrono::steady_clock::now();
  const models::BuiltModel built = models::build_model(models::load_config("", {}));
  wear::WearOptions o;
  o.total_cycles = 5'000'000;
  o.update_every = 250'000;
  o.law.wear_factor = built.material.wear_factor_mm3_per_Nmm * wear::kWearFactorSI;
  o.law.friction = built.model.contact.friction;
  const wear::WearResult r = wear::run_wear(built, o);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  REQUIRE(r.status == engine::StepStatus::kOk);
  REQUIRE(r.records.size() == 21);
  double worst = 0.0;
  for (size_t i = 1; i < r.records.size(); ++i) {
    const wear::UpdateRecord& u = r.records[i];
    const double diff = (u.volume - u.volume_depth) / u.volume_depth;
    worst = std::max(worst, std::abs(diff));
    CHECK(std::abs(diff) < 0.01);
    CHECK(u.refinements == 0.0);
  }
  const wear::UpdateRecord& last = r.records.back();
  const double rate = last.volume * 1e9 / 5.0;  // mm^3 per million cycles, through the origin
  std::printf("[wear] default 5 Mc: volume %.2f mm^3, rate %.2f mm^3/Mc, max depth %.3f mm, "
              "medial %.2f / lateral %.2f mm^3, worst bookkeeping difference %.2e, %.1f s\n",
              last.volume * 1e9, rate, last.max_depth * 1e3, last.medial_volume * 1e9,
              last.lateral_volume * 1e9, worst, seconds);
  CHECK(rate > 0.5 * 18.82);
  CHECK(rate < 1.5 * 18.82);
  CHECK(models::check_mesh(r.worn).watertight());
  CHECK(wear::count_inverted_faces(built.implant.insert, r.worn) == 0);
}
