// Hidden-effect identification over many seeds (label "long"): 100 seeds per effect with
// depth (none, running_in, incubation, pressure_dependent_wear, creep) and 100 without depth
// (none, running_in, incubation, pressure_dependent_wear): 900 data sets. Required: no false
// positive, every gain above kMinGain, and at most 0.5 % of the effects missed. Measured: 898
// of 900; the two misses are incubation sets at the weakest end of its range (fitted N_i
// about 9 100 cycles, a deficit of about 5 % of the Archard volume) whose held-out RMSE is
// 4.6 % and 3.6 % below none's, short of the 5 % gate: identification is a significance
// test, and a rule that still keeps clean sets at none cannot name every weak effect
// (docs/diagnosis.md). Run: ctest -L long -R test_diagnosis_long.
//
// The "sweep" test case (skipped by default) measures the rates over other seed ranges, the
// way docs/diagnosis.md reports them:
//   KNEESIM_SWEEP_FIRST_SEED=300000 KNEESIM_SWEEP_SEEDS=1000 KNEESIM_SWEEP_DEPTH=1
//   KNEESIM_SWEEP_EFFECTS=none build/tests/diagnosis/test_diagnosis_long -tc=sweep --no-skip
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "tests/diagnosis/hidden_effect.h"
#include "tests/diagnosis/identification.h"

using kneesim::test::kMinGain;
using kneesim::test::run_identification;

namespace {

long env_long(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v ? std::strtol(v, nullptr, 10) : fallback;
}

void report(const kneesim::test::IdentificationTally& t, bool depth) {
  MESSAGE("depth " << depth << ": identification " << t.correct << "/" << t.runs
                   << ", false positives " << t.false_positives << ", smallest gain "
                   << t.min_gain << ", lowest dAICc on clean data " << t.clean_min_daicc
                   << ", highest dAICc of a true effect " << t.effect_max_daicc
                   << ", lowest held-out ratio on clean data " << t.clean_min_heldout_ratio
                   << ", highest held-out ratio of a true effect " << t.effect_max_heldout_ratio
                   << ", slowest "
                   << t.max_seconds << " s, total " << t.total_seconds << " s");
}

}  // namespace

TEST_CASE("hidden effects over 100 seeds each are all identified") {
  for (const bool depth : {true, false}) {
    const auto t = run_identification(100000, 100, depth);
    INFO(t.failures);
    CAPTURE(depth);
    CHECK(2 * 100 * (t.runs - t.correct) <= t.runs);  // at most 0.5 % missed
    CHECK(t.false_positives == 0);
    CHECK(t.low_gain == 0);
    report(t, depth);
  }
}

TEST_CASE("sweep" * doctest::skip()) {
  const auto first = static_cast<std::uint64_t>(env_long("KNEESIM_SWEEP_FIRST_SEED", 300000));
  const int seeds = static_cast<int>(env_long("KNEESIM_SWEEP_SEEDS", 100));
  const bool depth = env_long("KNEESIM_SWEEP_DEPTH", 1) != 0;
  std::vector<kneesim::diagnosis::Effect> effects;
  const char* names = std::getenv("KNEESIM_SWEEP_EFFECTS");
  if (names) {
    std::stringstream ss(names);
    for (std::string n; std::getline(ss, n, ',');) {
      effects.push_back(kneesim::diagnosis::parse_effect(n, "KNEESIM_SWEEP_EFFECTS"));
    }
  } else {
    effects = kneesim::test::bor_test_effects(depth);
  }
  const auto t = run_identification(first, seeds, depth, effects);
  MESSAGE(t.failures);
  report(t, depth);
  CHECK(t.correct == t.runs);
  CHECK(t.low_gain == 0);
}

// Writes a synthetic data set as a `kneesim diagnose bor` CSV (skipped by default); the creep
// example of docs/diagnosis.md is
//   KNEESIM_EXAMPLE_CSV=creep42.csv KNEESIM_EXAMPLE_EFFECT=creep KNEESIM_EXAMPLE_SEED=42
//   build/tests/diagnosis/test_diagnosis_long -tc="write example" --no-skip
TEST_CASE("write example" * doctest::skip()) {
  const char* path = std::getenv("KNEESIM_EXAMPLE_CSV");
  REQUIRE(path != nullptr);
  const char* effect = std::getenv("KNEESIM_EXAMPLE_EFFECT");
  const auto s = kneesim::test::make_synthetic_bor(
      kneesim::diagnosis::parse_effect(effect ? effect : "creep", "KNEESIM_EXAMPLE_EFFECT"),
      static_cast<std::uint64_t>(env_long("KNEESIM_EXAMPLE_SEED", 42)));
  // one line per specimen and cycle count: volume rows first, then the depth rows in the
  // same order (hidden_effect.cpp)
  std::map<std::tuple<std::string, std::string, double>, std::pair<double, double>> cells;
  for (const auto& m : s.data.rows) {
    auto& c = cells[{m.group, m.specimen, m.x}];
    (m.quantity == "volume_mm3" ? c.first : c.second) = m.value;
  }
  std::ofstream out(path);
  out << "# synthetic block-on-ring data, tests/diagnosis/hidden_effect.h, " << s.data.source;
  for (const auto& [name, value] : s.params) out << ", " << name << " " << value;
  out << "\nload_N,specimen,cycles,volume_mm3,depth_mm\n";
  for (const auto& [key, v] : cells) {
    out << std::strtod(std::get<0>(key).c_str(), nullptr) << "," << std::get<1>(key) << ","
        << std::get<2>(key) << "," << v.first << "," << v.second << "\n";
  }
  CHECK(out.good());
}
