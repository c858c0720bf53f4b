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

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "tests/diagnosis/hidden_effect.h"
#include "analysis/diagnosis/bor_case.h"
#include "analysis/diagnosis/diagnose.h"
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

// Hidden effects under measurement errors that are not the fit's error model (issue 27):
// families of hidden_effect.h (walk, soak_drift, heavy, lognormal), effects sized to a ratio
// of the set's noise RMS. Skipped by default; environment: KNEESIM_BOR_FAMILIES,
// KNEESIM_BOR_EFFECTS, KNEESIM_BOR_RATIOS, KNEESIM_BOR_SEEDS, KNEESIM_BOR_FIRST_SEED,
// KNEESIM_BOR_DEPTH (0/1), KNEESIM_BOR_DETECTION (replicates), KNEESIM_NOISE_MODEL.
TEST_CASE("correlated sweep" * doctest::skip()) {
  using namespace kneesim::diagnosis;
  using namespace kneesim::test;
  auto split = [](const char* env, const std::string& fallback) {
    std::vector<std::string> out;
    std::stringstream ss(env ? env : fallback);
    for (std::string item; std::getline(ss, item, ',');) {
      if (!item.empty()) out.push_back(item);
    }
    return out;
  };
  const auto families = split(std::getenv("KNEESIM_BOR_FAMILIES"), "walk");
  const auto effects = split(std::getenv("KNEESIM_BOR_EFFECTS"), "none,running_in,incubation,pressure_dependent_wear");
  const auto ratios = split(std::getenv("KNEESIM_BOR_RATIOS"), "1.2");
  const int seeds = static_cast<int>(env_long("KNEESIM_BOR_SEEDS", 3));
  const auto first = static_cast<std::uint64_t>(env_long("KNEESIM_BOR_FIRST_SEED", 800000));
  const bool depth = env_long("KNEESIM_BOR_DEPTH", 0) != 0;
  DiagnosisOptions opt;
  opt.bootstrap = 0;
  opt.rank_by_aicc = !std::getenv("KNEESIM_RANK_HELDOUT");
  opt.detection_replicates = static_cast<int>(env_long("KNEESIM_BOR_DETECTION", 0));
  if (const char* nm = std::getenv("KNEESIM_NOISE_MODEL")) opt.noise_model = nm;
  for (const auto& fam : families) {
    WearNoise kind = WearNoise::walk;
    for (WearNoise n : all_wear_noises()) {
      if (fam == wear_noise_name(n)) kind = n;
    }
    for (const auto& eff : effects) {
      const Effect truth = parse_effect(eff, "KNEESIM_BOR_EFFECTS");
      for (const auto& rs : ratios) {
        const double ratio = std::atof(rs.c_str());
        int named = 0;
        for (int k = 0; k < seeds; ++k) {
          const std::uint64_t seed = first + static_cast<std::uint64_t>(k);
          const RatioSet s = make_bor_at_ratio(truth, ratio, kind, seed, depth);
          const auto c = make_bor_case(s.s.data, BorCaseOptions{});
          const DiagnosisResult r = diagnose(c, opt);
          named += r.effect() == truth;
          std::string cands;
          for (const auto& m : r.candidates) {
            char buf[200];
            std::snprintf(buf, sizeof buf, " %s:%.1f/%.3f%s", std::string(effect_name(m.effect)).c_str(),
                          m.aicc - r.candidates.front().aicc,
                          m.heldout_rmse / r.candidates.front().heldout_rmse,
                          m.at_bound.empty() ? "" : "@bound");
            cands += buf;
          }
          std::printf("%s %s ratio %.2f seed %llu size %.4g noise %.4f signal %.4f: named %s | rho %.3g rho_o %.3g | %.2f s |%s\n",
                      fam.c_str(), eff.c_str(), ratio, static_cast<unsigned long long>(seed),
                      s.s.params.count("size") ? s.s.params.at("size") : 0.0, s.noise_rms,
                      s.signal_rms, std::string(effect_name(r.effect())).c_str(),
                      r.candidates.front().noise.rho, r.candidates.front().noise.rho_offset,
                      r.seconds, cands.c_str());
          for (const auto& d : r.detection.limits) {
            std::printf("   limit %s %s%+d: %s %.4g, signal %.4f, ratio %.2f (noise %.4f)\n",
                        std::string(effect_name(d.effect)).c_str(), d.param.c_str(), d.direction,
                        d.reached ? "at" : "beyond", d.value, d.signal_rms, d.ratio,
                        r.detection.noise_rms);
          }
          std::fflush(stdout);
        }
        std::printf("== %s %s ratio %.2f: named %d of %d\n", fam.c_str(), eff.c_str(), ratio, named, seeds);
      }
    }
  }
}
