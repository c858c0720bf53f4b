// Long tallies of the forces diagnosis on four-cell synthetic data (forces_synthetic.h): per
// noise family, hidden effects sized to a multiple of the set's noise RMS (the identifiable
// signal, identifiable_signal_rms) and clean sets; and the agreement of the reported detection
// limit with the size at which the hidden effects start being named.
//
// The skipped test case "forces sweep" runs any family, effect and ratio over a seed range
// (environment: KNEESIM_FORCES_FAMILIES, KNEESIM_FORCES_EFFECTS, KNEESIM_FORCES_RATIOS,
// KNEESIM_FORCES_SEEDS, KNEESIM_FORCES_FIRST_SEED, KNEESIM_FORCES_DETECTION = replicates).
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "tests/diagnosis_forces/forces_synthetic.h"

using namespace kneesim;
using namespace kneesim::diagnosis;
using namespace kneesim::test;

namespace {

std::vector<std::string> split(const char* env, const std::string& fallback) {
  std::vector<std::string> out;
  std::stringstream ss(env ? env : fallback);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

CellNoise family_of(const std::string& name) {
  for (CellNoise n : all_cell_noises()) {
    if (name == cell_noise_name(n)) return n;
  }
  FAIL("unknown family " << name);
  return CellNoise::white_walk;
}

}  // namespace

TEST_CASE("forces sweep" * doctest::skip()) {
  ForcesBench bench;
  const auto families = split(std::getenv("KNEESIM_FORCES_FAMILIES"), "white_walk");
  const auto effects = split(std::getenv("KNEESIM_FORCES_EFFECTS"), "none,load_line,vv_moment,vv_alignment");
  const auto ratios = split(std::getenv("KNEESIM_FORCES_RATIOS"), "1.2");
  const int seeds = std::atoi(std::getenv("KNEESIM_FORCES_SEEDS") ? std::getenv("KNEESIM_FORCES_SEEDS") : "2");
  const std::uint64_t first = std::strtoull(
      std::getenv("KNEESIM_FORCES_FIRST_SEED") ? std::getenv("KNEESIM_FORCES_FIRST_SEED") : "1000", nullptr, 10);
  DiagnosisOptions opt;
  opt.bootstrap = 0;
  opt.rank_by_aicc = !std::getenv("KNEESIM_RANK_HELDOUT");
  opt.detection_replicates =
      std::atoi(std::getenv("KNEESIM_FORCES_DETECTION") ? std::getenv("KNEESIM_FORCES_DETECTION") : "0");
  for (const auto& fam : families) {
    for (const auto& eff : effects) {
      const Effect truth = parse_effect(eff, "KNEESIM_FORCES_EFFECTS");
      for (const auto& rs : ratios) {
        const double ratio = std::atof(rs.c_str());
        int named = 0;
        for (int k = 0; k < seeds; ++k) {
          const std::uint64_t seed = first + static_cast<std::uint64_t>(k);
          const ForcesSet s = bench.make_at_ratio(truth, ratio, family_of(fam), seed);
          double tmin = 1e300;
          for (double t : s.measured.total_N) tmin = std::min(tmin, t);
          std::printf("min measured total %.1f N, noise scale %.2f\n", tmin, s.noise_scale);
          auto sim = std::make_shared<ForcesSimulator>(bench.config(), s.measured.cycles);
          for (int k = 0; k < sim->cycles(); ++k) {
            const auto tr = sim->run(Effect::none, 0.0, k);
            if (!tr->ok) std::printf("  cycle %d baseline failed: %s\n", k, tr->failure.c_str());
          }
          const ForcesDiagnosisReport rep = bench.diagnose(s, opt);
          const DiagnosisResult& r = rep.result;
          named += r.effect() == truth;
          std::string cands;
          for (const auto& m : r.candidates) {
            char buf[160];
            std::snprintf(buf, sizeof buf, " %s:%.1f/%.3f/%.3f%s", std::string(effect_name(m.effect)).c_str(),
                          m.aicc - r.candidates.front().aicc, m.heldout_rmse / r.candidates.front().heldout_rmse,
                          m.params.size() ? m.params[m.params.size() - 1] : 0.0,
                          m.at_bound.empty() ? "" : "@bound");
            cands += buf;
          }
          std::printf("%s %s ratio %.2f seed %llu value %.3f noise %.1f N signal %.1f N: named %s | ell %.4f s, sigma %.1f, n_eff %.1f | base %.1f trivial %.1f none %.1f |%s\n",
                      fam.c_str(), eff.c_str(), ratio, static_cast<unsigned long long>(seed), s.value,
                      s.noise_rms, s.signal_rms, std::string(effect_name(r.effect())).c_str(),
                      r.candidates.front().noise.ell, r.candidates.front().noise.sigma,
                      r.candidates.front().noise.n_eff, r.baseline.heldout_rmse, r.trivial.heldout_rmse,
                      r.candidates.front().heldout_rmse, cands.c_str());
          for (const auto& d : r.detection.limits) {
            std::printf("   limit %s %s%+d: %s %.3f, signal %.1f N, ratio %.2f (noise %.1f N)\n",
                        std::string(effect_name(d.effect)).c_str(), d.param.c_str(), d.direction,
                        d.reached ? "at" : "beyond", d.value, d.signal_rms, d.ratio, r.detection.noise_rms);
          }
          std::fflush(stdout);
        }
        std::printf("== %s %s ratio %.2f: named %d of %d\n", fam.c_str(), eff.c_str(), ratio, named, seeds);
      }
    }
  }
}
