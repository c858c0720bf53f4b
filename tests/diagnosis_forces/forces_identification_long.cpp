// Long tallies of the forces diagnosis on four-cell synthetic data (forces_synthetic.h): per
// noise family, hidden effects sized to a multiple of the set's noise RMS (the identifiable
// signal, identifiable_signal_rms) and clean sets; and the agreement of the reported detection
// limit with the size at which the hidden effects start being named.
//
// The skipped test case "forces sweep" runs any family, effect and ratio over a seed range
// (environment: KNEESIM_FORCES_FAMILIES, KNEESIM_FORCES_EFFECTS, KNEESIM_FORCES_RATIOS,
// KNEESIM_FORCES_SEEDS, KNEESIM_FORCES_FIRST_SEED, KNEESIM_FORCES_DETECTION = replicates;
// KNEESIM_FORCES_VALUE = a fixed hidden value, its sign alternating by seed, with the ratio
// entry then the factor on the family's noise). The skipped test case "forces load-line
// collinearity" measures how much of each candidate the instrument's columns reproduce;
// "forces forward jitter" the simulated force's roughness in a parameter; "forces effect
// shape" how the generator's effect differs from the case's forward model of it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
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
          // KNEESIM_FORCES_VALUE: the hidden value itself (both signs alternate by seed), the
          // family's noise scaled by the ratio entry instead of sized to the signal
          const char* fixed = std::getenv("KNEESIM_FORCES_VALUE");
          const double fixed_value = fixed ? std::atof(fixed) * (k % 2 ? -1.0 : 1.0) : 0.0;
          ForcesSet s = fixed ? bench.make(truth, fixed_value, family_of(fam), seed, ratio)
                              : bench.make_at_ratio(truth, ratio, family_of(fam), seed);
          // a clean record (none) has no effect and no signal
          if (fixed) s.signal_rms = truth == Effect::none ? 0.0 : bench.signal(truth, fixed_value);
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

// The load line against the cells' calibration terms (skipped; run with --no-skip): on the
// clean synthetic record, the medial share change per unit of each candidate over stance, the
// part of its medial-force signal that the instrument's columns cannot reproduce with any
// coefficients, and the prior cost (sum of (coefficient / prior sd)^2) of the gain and crosstalk
// coefficients that reproduce the rest: what a noise-free record gives against none besides
// the unreproducible part. Two sets of columns: the fit's (forces_case.cpp: offset, drift free;
// gain difference s (1 - s) T, sd 0.02 sqrt 2, crosstalk (1 - s)^2 T and -s^2 T, sd 0.02) and
// the former ones that ignored that the total is read from the same cells (medial gain x
// predicted medial, crosstalk x predicted lateral, sd 0.02 each).
TEST_CASE("forces load-line collinearity" * doctest::skip()) {
  ForcesBench bench;
  const ForcesSet s = bench.make(Effect::none, 0.0, CellNoise::white_walk, 1, 0.0);
  auto sim = std::make_shared<ForcesSimulator>(bench.config(), s.measured.cycles);
  sim->set_threads(2);
  const auto& rows = s.measured.data.rows;
  const size_t n = rows.size();
  const double tau = 0.02;
  double tmax = 0.0;
  for (double t : s.measured.total_N) tmax = std::max(tmax, t);
  double tm = 0.0;
  for (double t : s.measured.time_s) tm += t / static_cast<double>(n);
  auto pred = [&](Effect e, double v) { return simulated_medial(*sim, s.measured, e, v); };
  const Eigen::VectorXd p0 = pred(Effect::none, 0.0);
  const auto ni = static_cast<Eigen::Index>(n);
  Eigen::VectorXd total(ni);
  for (size_t i = 0; i < n; ++i) total[static_cast<Eigen::Index>(i)] = s.measured.total_N[i];
  struct Columns {
    const char* name;
    Eigen::MatrixXd x;        // free columns first
    int free = 2;
    std::vector<double> sd;   // of the priored columns
  };
  Columns now{"propagated (gain difference, two crosstalks)", Eigen::MatrixXd(ni, 5), 2,
              {tau * std::sqrt(2.0), tau, tau}};
  Columns former{"former (medial gain, lateral crosstalk)", Eigen::MatrixXd(ni, 4), 2, {tau, tau}};
  for (Eigen::Index r = 0; r < ni; ++r) {
    const double t = total[r], p = p0[r], sh = t != 0.0 ? p / t : 0.5;
    now.x.row(r) << 1.0, s.measured.time_s[static_cast<size_t>(r)] - tm, sh * (1.0 - sh) * t,
        (1.0 - sh) * (1.0 - sh) * t, -sh * sh * t;
    former.x.row(r) << 1.0, s.measured.time_s[static_cast<size_t>(r)] - tm, p, t - p;
  }
  for (Effect e : {Effect::load_line, Effect::vv_moment, Effect::vv_alignment}) {
    for (double d : {-4.0, -2.0, -1.0, 1.0, 2.0, 4.0}) {
      const Eigen::VectorXd delta = pred(e, d) - p0;
      // share change per unit of d in stance (total above 20 % of peak)
      double s1 = 0, s2 = 0;
      int ns = 0;
      for (Eigen::Index i = 0; i < delta.size(); ++i) {
        if (total[i] < 0.2 * tmax) continue;
        const double ds = delta[i] / total[i] / d;
        s1 += ds, s2 += ds * ds, ++ns;
      }
      const double mean = s1 / ns, sd = std::sqrt(std::max(0.0, s2 / ns - mean * mean));
      std::printf("%s %+.1f: signal RMS %.1f N, dshare per unit %.5f (stance sd %.5f)\n",
                  std::string(effect_name(e)).c_str(), d, std::sqrt(delta.squaredNorm() / n), mean, sd);
      for (const Columns* c : {&now, &former}) {
        // least squares on every column: the part no coefficients reproduce
        const Eigen::VectorXd beta = c->x.colPivHouseholderQr().solve(delta);
        const Eigen::VectorXd rest = delta - c->x * beta;
        std::printf("   %-46s not reproducible %5.2f N RMS (%4.1f %%); chi-square of none at white "
                    "noise sd", c->name, std::sqrt(rest.squaredNorm() / n), 100.0 * rest.norm() / delta.norm());
        // none's chi-square against the exact effect at white noise sd sigma: min over the
        // coefficients of |delta - X beta|^2 / sigma^2 + sum (beta_prior / sd)^2 (the ridge the
        // fit solves; the free columns unpenalised)
        for (double sigma : {1.0, 10.0, 20.0, 40.0}) {
          const Eigen::Index m = c->x.cols();
          Eigen::MatrixXd a = Eigen::MatrixXd::Zero(ni + m, m);
          a.topRows(ni) = c->x / sigma;
          Eigen::VectorXd rhs = Eigen::VectorXd::Zero(ni + m);
          rhs.head(ni) = delta / sigma;
          for (size_t j = 0; j < c->sd.size(); ++j) {
            a(ni + c->free + static_cast<Eigen::Index>(j), c->free + static_cast<Eigen::Index>(j)) = 1.0 / c->sd[j];
          }
          const Eigen::VectorXd b = a.colPivHouseholderQr().solve(rhs);
          std::printf(" %.0f N: %.1f", sigma, (a * b - rhs).squaredNorm());
        }
        std::printf("\n");
      }
    }
  }
}

namespace {

// the case's grid from the environment (KNEESIM_FORCES_GRID; default the diagnosis' own)
ForcesCaseOptions case_options_from_env() {
  ForcesCaseOptions fo;
  if (const char* g = std::getenv("KNEESIM_FORCES_GRID")) fo.grid_points = std::atoi(g);
  return fo;
}

double env_or(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}

}  // namespace

// The forward model's jitter in a parameter (skipped; run with --no-skip): on a clean
// white_walk record (seed 1500, noise scale KNEESIM_FORCES_SCALE, default 1.5), the RMS over
// the rows of the simulated medial force's slope and second difference at step h about
// several values of each candidate. A smooth response has second differences ~ h^2 x its
// curvature; the simulation's stay at tenths of a newton to a few N however small h is:
// contact on the faceted insert switches discretely. KNEESIM_FORCES_INSTANT=1: samples at an
// instant instead of the means over their 1 % (the aliasing the means remove).
TEST_CASE("forces forward jitter" * doctest::skip()) {
  ForcesBench bench;
  const ForcesSet s0 = bench.make(Effect::none, 0.0, CellNoise::white_walk, 1500,
                                  env_or("KNEESIM_FORCES_SCALE", 1.5));
  auto sim = std::make_shared<ForcesSimulator>(bench.config(), s0.measured.cycles);
  sim->set_threads(2);
  sim->set_instant_samples(env_or("KNEESIM_FORCES_INSTANT", 0.0) != 0.0);
  const double root_n = std::sqrt(static_cast<double>(s0.measured.data.rows.size()));
  for (Effect e : {Effect::vv_alignment, Effect::load_line, Effect::vv_moment}) {
    auto curve = [&](double v) { return simulated_medial(*sim, s0.measured, e, v); };
    for (double h : {0.01, 0.1, 0.5}) {
      for (double v0 : {-2.0, -1.0, 1.0, 2.0}) {
        const Eigen::VectorXd a = curve(v0 - h), b = curve(v0), c = curve(v0 + h);
        std::printf("%s %+.1f h %.2f: slope RMS %.1f N/unit, second difference RMS %.2f N\n",
                    std::string(effect_name(e)).c_str(), v0, h, (c - a).norm() / root_n / (2.0 * h),
                    (a - 2.0 * b + c).norm() / root_n);
      }
    }
  }
}

// The hidden effect's shape against the forward model's (skipped; run with --no-skip): per
// seed (KNEESIM_FORCES_FIRST_SEED, KNEESIM_FORCES_SEEDS; value KNEESIM_FORCES_VALUE of
// KNEESIM_FORCES_EFFECTS, default vv_alignment 2, sign alternating) the generator's record
// with the effect and, with the SAME noise, the clean record plus the case's own predicted
// effect; both diagnosed. Also the RMS of the generator's effect minus the case's, and of the
// case's prediction minus a direct simulation at the value. The case's grid from
// KNEESIM_FORCES_GRID (default: the diagnosis' own).
TEST_CASE("forces effect shape" * doctest::skip()) {
  ForcesBench bench;
  const Effect eff = parse_effect(std::getenv("KNEESIM_FORCES_EFFECTS") ? std::getenv("KNEESIM_FORCES_EFFECTS")
                                                                       : "vv_alignment",
                                  "KNEESIM_FORCES_EFFECTS");
  const double value = env_or("KNEESIM_FORCES_VALUE", 2.0);
  const int seeds = static_cast<int>(env_or("KNEESIM_FORCES_SEEDS", 12));
  const auto first = static_cast<std::uint64_t>(env_or("KNEESIM_FORCES_FIRST_SEED", 1500));
  const double scale = env_or("KNEESIM_FORCES_SCALE", 1.5);
  DiagnosisOptions opt;
  opt.bootstrap = 0;
  opt.detection_replicates = 0;
  int named_generator = 0, named_model = 0;
  for (int k = 0; k < seeds; ++k) {
    const std::uint64_t seed = first + static_cast<std::uint64_t>(k);
    const double v = value * (k % 2 ? -1.0 : 1.0);
    const ForcesSet s0 = bench.make(Effect::none, 0.0, CellNoise::white_walk, seed, scale);
    const ForcesSet s1 = bench.make(eff, v, CellNoise::white_walk, seed, scale);
    auto sim = std::make_shared<ForcesSimulator>(bench.config(), s0.measured.cycles);
    sim->set_threads(2);
    const DiagnosisCase c0 = make_forces_case(s0.measured, sim, case_options_from_env());
    if (k == 0) {  // the detection replicates' forward-error realizations (forces_case.cpp)
      double lo = 1e300, hi = 0.0;
      for (const auto& d : c0.forward_error_draws) {
        const double rms = d.norm() / std::sqrt(static_cast<double>(d.size()));
        lo = std::min(lo, rms), hi = std::max(hi, rms);
      }
      std::printf("%zu forward-error realizations, %.1f-%.1f N RMS\n", c0.forward_error_draws.size(), lo, hi);
    }
    std::vector<int> rows(c0.measured.rows.size());
    for (size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<int>(i);
    const Eigen::VectorXd none, base, pv = Eigen::VectorXd::Constant(1, v);
    const Eigen::VectorXd f0 = c0.predict(Effect::none, base, none, rows);
    const Eigen::VectorXd model_effect = c0.predict(eff, base, pv, rows) - f0;
    const Eigen::VectorXd direct_effect =
        simulated_medial(*sim, s0.measured, eff, v) - simulated_medial(*sim, s0.measured, Effect::none, 0.0);
    double shape2 = 0.0;
    for (size_t i = 0; i < rows.size(); ++i) {
      const double gen = s1.measured.data.rows[i].value - s0.measured.data.rows[i].value;
      shape2 += std::pow(gen - model_effect[static_cast<Eigen::Index>(i)], 2);
    }
    const double direct2 = (direct_effect - model_effect).squaredNorm();
    DiagnosisCase swapped = c0;
    for (size_t i = 0; i < rows.size(); ++i) swapped.measured.rows[i].value += model_effect[static_cast<Eigen::Index>(i)];
    const DiagnosisResult with_model = diagnose(swapped, opt);
    const DiagnosisResult with_generator =
        diagnose_forces(make_forces_case(s1.measured, sim, case_options_from_env()), *sim,
                        s1.measured.total_N, opt).result;
    named_generator += with_generator.effect() == eff;
    named_model += with_model.effect() == eff;
    const double n = static_cast<double>(rows.size());
    std::printf("seed %llu value %+.2f: generator effect - model effect %.1f N RMS, model - direct "
                "simulation %.1f N RMS | generator's record named %s, model's effect named %s\n",
                static_cast<unsigned long long>(seed), v, std::sqrt(shape2 / n), std::sqrt(direct2 / n),
                std::string(effect_name(with_generator.effect())).c_str(),
                std::string(effect_name(with_model.effect())).c_str());
    std::fflush(stdout);
  }
  std::printf("== named: generator's effect %d, model's effect %d of %d\n", named_generator,
              named_model, seeds);
}
