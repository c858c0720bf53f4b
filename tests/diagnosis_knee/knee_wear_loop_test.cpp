// The knee-wear diagnosis' approximation (wear linear in cycles on the pristine insert) against
// the full geometry-updating wear loop (wear::run_wear, `kneesim wear`), for the Archard and
// running-in laws. Reference: the loop; tolerance 3 % on volume (the sliding work sum A p ds =
// normal force x slip hardly depends on the worn conformity; measured 0.0-1.5 %), 10 % on the
// Archard maximum depth (measured 1 %). Plus the running-in cycle weighting in closed form.
#include <doctest/doctest.h>

#include <cmath>

#include "analysis/diagnosis/knee_wear_case.h"
#include "models/build_model.h"
#include "tests/diagnosis_knee/knee_hidden_effect.h"
#include "wear/archard.h"
#include "wear/wear_law.h"
#include "wear/wear_loop.h"

using namespace kneesim;

TEST_CASE("running-in cycle weighting: closed form and additivity over intervals") {
  wear::WearLawParams law;
  law.law = wear::WearLaw::kRunningIn;
  law.running_in_excess = 2.0;
  law.running_in_cycles = 1e5;
  // integral of 1 + a exp(-N/N_r) over [0, 3e5]
  const double exact = 3e5 + 2.0 * 1e5 * (1.0 - std::exp(-3.0));
  CHECK(wear::effective_cycles(law, 0.0, 3e5) == doctest::Approx(exact).epsilon(1e-12));
  CHECK(wear::effective_cycles(law, 0.0, 1e5) + wear::effective_cycles(law, 1e5, 2e5) ==
        doctest::Approx(exact).epsilon(1e-12));
  law.law = wear::WearLaw::kArchard;
  CHECK(wear::effective_cycles(law, 1e5, 2e5) == 2e5);
}

TEST_CASE("linear wear on the pristine insert agrees with the wear loop (archard, running-in)") {
  const auto& tables = test::knee_test_tables();
  diagnosis::MeasuredData d;
  d.source = "loop check";
  d.rows.push_back({"iso", "", "volume_mm3", 0.0, 0.0, 2});
  const auto configs = diagnosis::knee_condition_configs(d, test::knee_test_config(), {});
  const models::BuiltModel built = models::build_model(configs.at("iso"));
  for (const bool running_in : {false, true}) {
    wear::WearOptions o;
    o.total_cycles = 2'000'000;
    o.update_every = 500'000;
    o.law.wear_factor = 2.643e-16;
    o.law.friction = tables.at("iso")->friction();
    diagnosis::KneeWearParams p;
    p.k = o.law.wear_factor;
    if (running_in) {
      o.law.law = wear::WearLaw::kRunningIn;
      o.law.running_in_excess = 3.0;
      o.law.running_in_cycles = 2e5;
      p.effect = diagnosis::Effect::running_in;
      p.running_in_excess = 3.0;
      p.running_in_cycles = 2e5;
    }
    const wear::WearResult w = wear::run_wear(built, o);
    REQUIRE(w.status == engine::StepStatus::kOk);
    const double n = w.records.back().cycles;
    CAPTURE(running_in);
    CHECK(tables.at("iso")->volume(p, n) ==
          doctest::Approx(w.records.back().volume).epsilon(0.03).scale(0));
    if (!running_in) {
      CHECK(tables.at("iso")->max_depth(p, n) ==
            doctest::Approx(w.records.back().max_depth).epsilon(0.10).scale(0));
    }
  }
}

TEST_CASE("the diagnosis baseline is the config's wear law: equal to the wear loop's volume") {
  // Reference: wear::run_wear (`kneesim wear`) with the law wear::make_wear_law gives for the
  // same config, over one update on the pristine insert, where its volume is exactly the depth
  // per cycle times the cycles: the table's baseline (effect none) at the material's k must
  // give the same depth-integral volume (1e-9: the same accumulator on the same simulated
  // cycle; only the summation order differs). Cross-shear gain 15 moves the volume far from
  // Archard's, so an Archard baseline would fail this by tens of per cent.
  for (const char* law_name : {"cross_shear", "contact_area", "material_pressure"}) {
    CAPTURE(law_name);
    diagnosis::MeasuredData d;
    d.source = "law check";
    d.rows.push_back({"iso", "", "volume_mm3", 0.0, 0.0, 2});
    std::vector<std::string> sets = {"wear.law=\"" + std::string(law_name) + "\""};
    if (std::string(law_name) == "cross_shear") sets.push_back("wear.cross_shear_gain=15");
    if (std::string(law_name) == "contact_area") sets.push_back("material.area_wear_coefficient=1e-8");
    const auto configs = diagnosis::knee_condition_configs(d, test::knee_test_config(), sets);
    const models::Config& config = configs.at("iso");
    const diagnosis::KneeWearTable table("iso", config);
    const models::BuiltModel built = models::build_model(config);
    wear::WearOptions o;
    o.total_cycles = 100'000;
    o.update_every = 100'000;
    o.law = wear::make_wear_law(config.wear, built);
    CHECK(wear::wear_law_name(table.law().law) == wear::wear_law_name(o.law.law));
    const wear::WearResult w = wear::run_wear(built, o);
    REQUIRE(w.status == engine::StepStatus::kOk);
    diagnosis::KneeWearParams p;  // effect none: the baseline
    p.k = o.law.wear_factor;
    CHECK(table.volume(p, 100'000) ==
          doctest::Approx(w.records.back().volume_depth).epsilon(1e-9).scale(0));
    // and not Archard's (the law matters): gain 15 moves the volume by over 5 %
    if (std::string(law_name) == "cross_shear") {
      const double archard = wear::sarkar_factor(table.friction()) * table.work() * p.k * 1e5;
      CHECK(table.volume(p, 100'000) / archard - 1.0 > 0.05);
    }
  }
}

TEST_CASE("the diagnosis' geometry path and loop check follow the config's wear law") {
  // Reference: wear::run_wear (`kneesim wear`) with the law wear::make_wear_law gives for the
  // same config (cross-shear gain 15; contact area C 2e-9, about Archard's volume), 2 Mc with
  // an update every 0.25 Mc. The table follows its own wear loop under that law (4 worn
  // states, the command's default, to 1.5 times the loop's volume) and must predict the
  // loop's depth-integral volume within 3 % (the tolerance of the Archard case above; rates
  // interpolated in worn volume against the loop's rate held over each update; measured
  // +0.5 % and +1.8 %) and its maximum depth within 10 % (measured -6.8 % and -1.4 %: the
  // deepest vertex of a 3 mm mesh under the cross-shear law moves between states). The law
  // KneeWearTable::loop_law gives for the baseline (what the diagnosis' check against the
  // loop runs) is the config's, its coefficient scaled by the fitted k; an Archard loop would
  // differ from the cross-shear prediction by over 5 %, checked below.
  for (const char* law_name : {"cross_shear", "contact_area"}) {
    CAPTURE(law_name);
    diagnosis::MeasuredData d;
    d.source = "law path check";
    d.rows.push_back({"iso", "", "volume_mm3", 0.0, 0.0, 2});
    std::vector<std::string> sets = {"wear.law=\"" + std::string(law_name) + "\""};
    if (std::string(law_name) == "cross_shear") sets.push_back("wear.cross_shear_gain=15");
    if (std::string(law_name) == "contact_area") sets.push_back("material.area_wear_coefficient=2e-9");
    const auto configs = diagnosis::knee_condition_configs(d, test::knee_test_config(), sets);
    const models::Config& config = configs.at("iso");
    const models::BuiltModel built = models::build_model(config);
    wear::WearOptions o;
    o.total_cycles = 2'000'000;
    o.update_every = 250'000;
    o.law = wear::make_wear_law(config.wear, built);
    const wear::WearResult w = wear::run_wear(built, o);
    REQUIRE(w.status == engine::StepStatus::kOk);
    const double n = w.records.back().cycles;
    const double v_loop = w.records.back().volume_depth;

    diagnosis::KneeGeometryPath path;
    path.states = 4;
    path.target_volume = diagnosis::kPathVolumeMargin * v_loop;
    const diagnosis::KneeWearTable table("iso", config, path);
    REQUIRE(table.geometry_states() == 5);
    diagnosis::KneeWearParams p;  // the baseline at the material's k
    p.k = o.law.wear_factor;
    CHECK(table.volume(p, n) == doctest::Approx(v_loop).epsilon(0.03).scale(0));
    CHECK(table.max_depth(p, n) ==
          doctest::Approx(w.records.back().max_depth).epsilon(0.10).scale(0));
    // the path reached its target under the law (its last state beyond the loop's volume)
    CHECK(table.state_volume(4) > v_loop);

    // the check's loop law at another k: the config's law, its coefficient scaled by k
    p.k = 1.5 * o.law.wear_factor;
    const wear::WearLawParams check = table.loop_law(p);
    CHECK(wear::wear_law_name(check.law) == law_name);
    CHECK(wear::law_coefficient(check) ==
          doctest::Approx(1.5 * wear::law_coefficient(o.law)).epsilon(1e-12).scale(0));
    CHECK(check.beta == o.law.beta);
    CHECK_FALSE(check.creep);
    if (std::string(law_name) == "cross_shear") {
      const double archard = wear::sarkar_factor(table.friction()) * table.work() * p.k * 1e5;
      CHECK(table.volume(p, 1e5) / archard - 1.0 > 0.05);
    }
  }
}
