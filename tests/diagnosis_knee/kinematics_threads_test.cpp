// Determinism of the kinematics diagnosis (design.md: the same inputs give bit-identical results
// for any thread count): the candidates, multi-starts, held-out folds and detection-limit
// replicates run side by side and the simulator runs several rig simulations at a time
// (kinematics_sim.h); every fitted number, AICc, held-out error and detection limit must equal
// the sequential run's exactly, and so must the number of simulations (the cache serves each
// parameter set once whatever the order).
#include <doctest/doctest.h>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/kinematics_case.h"
#include "models/config.h"
#include "tests/diagnosis_knee/knee_hidden_effect.h"

using namespace kneesim;
using namespace kneesim::diagnosis;
using namespace kneesim::test;

TEST_CASE("kinematics diagnosis: bit-identical for 1 and 2 simulation threads") {
  const KneeSynthetic s = make_synthetic_kinematics(Effect::restraint, 7301);
  DiagnosisOptions opt;
  opt.bootstrap = 2;
  opt.detection_replicates = 4;
  auto run = [&](int threads) {
    // the test simulator's config (generic implant, 3 mm elements, one cycle per evaluation)
    const models::Config c =
        models::load_config("", {{"implant.edge_length_mm", "3.0"}, {"solver.cycles", "1"}});
    auto sim = std::make_shared<KinematicsSimulator>(c);
    sim->set_threads(threads);
    const auto kc = make_kinematics_case(s.data, sim, {});
    CHECK(kc.fit_control.threads == threads);
    auto r = diagnose(kc, opt);
    return std::make_pair(r, sim->simulations());
  };
  const auto [a, sims_a] = run(1);
  const auto [b, sims_b] = run(2);
  CHECK(sims_a == sims_b);
  CHECK(a.effect() == b.effect());
  REQUIRE(a.candidates.size() == b.candidates.size());
  for (size_t i = 0; i < a.candidates.size(); ++i) {
    INFO(effect_name(a.candidates[i].effect));
    CHECK(a.candidates[i].params == b.candidates[i].params);
    CHECK(a.candidates[i].aicc == b.candidates[i].aicc);
    CHECK(a.candidates[i].heldout_rmse == b.candidates[i].heldout_rmse);
    CHECK(a.candidates[i].nuisance == b.candidates[i].nuisance);
    CHECK(a.candidates[i].noise.ell == b.candidates[i].noise.ell);
  }
  CHECK(a.extended().ci_low == b.extended().ci_low);
  CHECK(a.extended().ci_high == b.extended().ci_high);
  REQUIRE(a.detection.limits.size() == b.detection.limits.size());
  for (size_t i = 0; i < a.detection.limits.size(); ++i) {
    CHECK(a.detection.limits[i].value == b.detection.limits[i].value);
    CHECK(a.detection.limits[i].signal_rms == b.detection.limits[i].signal_rms);
  }
  MESSAGE("named " << effect_name(a.effect()) << ", " << sims_a << " simulations");
}
