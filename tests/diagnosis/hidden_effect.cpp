#include "tests/diagnosis/hidden_effect.h"

#include <array>
#include <cmath>
#include <random>

#include "analysis/diagnosis/diagnose.h"

#include "analysis/diagnosis/bor_case.h"
#include "wear/bor/bor_simulation.h"

namespace kneesim::test {

SyntheticData make_synthetic_bor(diagnosis::Effect effect, std::uint64_t seed,
                                 const SyntheticOptions& o) {
  using diagnosis::Effect;
  std::mt19937_64 rng(seed);
  auto uniform = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::normal_distribution<double> normal(0.0, 1.0);

  const bor::BorRig rig;
  bor::BorWearParams p;
  p.k = 4.1e-16 * uniform(0.8, 1.25);
  p.reference_pressure = bor::solve_bor_contact(rig, 225.0, 0.0).mean_pressure;
  SyntheticData s;
  s.truth = effect;
  s.params["k_mm3_per_Nmm"] = p.k * 1e6;
  bor::BorWearLaw law = bor::BorWearLaw::archard;
  switch (effect) {
    case Effect::running_in: {
      law = bor::BorWearLaw::running_in;
      const double fraction = uniform(0.08, 0.30);
      p.running_in_cycles = uniform(5000.0, 20000.0);
      p.running_in_excess = fraction * 2e5 / p.running_in_cycles;
      s.params["running_in_excess"] = p.running_in_excess;
      s.params["running_in_cycles"] = p.running_in_cycles;
      break;
    }
    case Effect::pressure_dependent_wear:
      law = bor::BorWearLaw::pressure_dependent_wear;
      p.pressure_exponent = uniform(0.7, 1.5);
      s.params["pressure_exponent"] = p.pressure_exponent;
      break;
    case Effect::creep:
      law = bor::BorWearLaw::creep;
      p.creep_ratio = uniform(0.3, 1.0);
      p.creep_time = uniform(1800.0, 10800.0);
      s.params["creep_ratio"] = p.creep_ratio;
      s.params["creep_time_s"] = p.creep_time;
      break;
    case Effect::incubation:
      law = bor::BorWearLaw::incubation;
      p.incubation_cycles = uniform(10000.0, 40000.0);
      s.params["incubation_cycles"] = p.incubation_cycles;
      break;
    case Effect::none:
    case Effect::cross_shear:
    case Effect::friction:
    case Effect::restraint:
    case Effect::load_convention: break;
    case Effect::load_line:
    case Effect::vv_moment:
    case Effect::vv_alignment: break;
  }

  s.data.source = "synthetic-" + std::string(diagnosis::effect_name(effect)) + "-" +
                  std::to_string(seed) + ".csv";
  s.data.x_name = "cycles";
  const std::vector<double> cycles = {5e4, 1e5, 1.5e5, 2e5};
  int row = 2;
  std::vector<diagnosis::Measurement> depth_rows;
  for (double load : {225.0, 130.0}) {
    for (int sp = 0; sp < o.specimens_per_load; ++sp) {
      bor::BorWearParams ps = p;
      ps.k = p.k * std::exp(o.specimen_cv * normal(rng) - 0.5 * o.specimen_cv * o.specimen_cv);
      const auto sim = bor::simulate_bor(rig, load, law, ps, cycles);
      for (const auto& r : sim) {
        diagnosis::Measurement m;
        m.group = diagnosis::bor_load_label(load);
        m.specimen = "s" + std::to_string(sp + 1);
        m.x = r.cycles;
        m.row = row++;
        m.quantity = "volume_mm3";
        const double v = r.volume * 1e9;
        m.value = std::max(0.0, v + (o.volume_noise_mm3 + o.volume_noise_rel * v) * normal(rng));
        s.data.rows.push_back(m);
        if (o.with_depth) {
          const double d = r.depth * 1e3;
          m.quantity = "depth_mm";
          m.value = std::max(0.0, d + (o.depth_noise_mm + o.depth_noise_rel * d) * normal(rng));
          depth_rows.push_back(m);
        }
      }
    }
  }
  s.data.rows.insert(s.data.rows.end(), depth_rows.begin(), depth_rows.end());
  return s;
}

}  // namespace kneesim::test

namespace kneesim::test {

const char* wear_noise_name(WearNoise n) {
  switch (n) {
    case WearNoise::walk: return "walk";
    case WearNoise::soak_drift: return "soak_drift";
    case WearNoise::heavy: return "heavy";
    case WearNoise::lognormal: return "lognormal";
  }
  return "";
}

const std::vector<WearNoise>& all_wear_noises() {
  static const std::vector<WearNoise> all = {WearNoise::walk, WearNoise::soak_drift,
                                             WearNoise::heavy, WearNoise::lognormal};
  return all;
}

double solve_size(const std::function<double(double)>& signal, double target, double lo,
                  double hi, bool log) {
  auto mid = [log](double a, double b) { return log ? std::sqrt(a * b) : 0.5 * (a + b); };
  if (signal(hi) < target) return hi;
  for (int i = 0; i < 24; ++i) {
    const double m = mid(lo, hi);
    (signal(m) < target ? lo : hi) = m;
  }
  return mid(lo, hi);
}

RatioSet make_bor_at_ratio(diagnosis::Effect effect, double ratio, WearNoise kind,
                           std::uint64_t seed, bool with_depth) {
  using diagnosis::Effect;
  std::mt19937_64 rng(seed);
  auto uniform = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::normal_distribution<double> normal(0.0, 1.0);
  std::student_t_distribution<double> student(3.0);
  const bor::BorRig rig;
  bor::BorWearParams p;
  p.k = 4.1e-16 * uniform(0.8, 1.25);
  p.reference_pressure = bor::solve_bor_contact(rig, 225.0, 0.0).mean_pressure;
  p.running_in_cycles = uniform(5000.0, 20000.0);
  p.creep_time = uniform(1800.0, 10800.0);
  bor::BorWearLaw law = bor::BorWearLaw::archard;
  double lo = 0.0, hi = 1.0;
  bool log = false;
  auto set_size = [&](double v) {
    switch (effect) {
      case Effect::running_in: p.running_in_excess = v; break;
      case Effect::pressure_dependent_wear: p.pressure_exponent = v; break;
      case Effect::creep: p.creep_ratio = v; break;
      case Effect::incubation: p.incubation_cycles = v; break;
      default: break;
    }
  };
  switch (effect) {
    case Effect::running_in: law = bor::BorWearLaw::running_in, lo = 1e-3, hi = 1e3, log = true; break;
    case Effect::pressure_dependent_wear: law = bor::BorWearLaw::pressure_dependent_wear, lo = 0.0, hi = 4.0; break;
    case Effect::creep: law = bor::BorWearLaw::creep, lo = 1e-3, hi = 20.0, log = true; break;
    case Effect::incubation: law = bor::BorWearLaw::incubation, lo = 1e2, hi = 3e5, log = true; break;
    default: break;
  }
  // the draws of the set: specimen factors and per-measurement normals
  const std::vector<double> cycles = {5e4, 1e5, 1.5e5, 2e5};
  const int specimens = 6;
  std::vector<double> ks, soak;
  std::vector<std::array<double, 4>> zv, zd, tv;
  for (int s = 0; s < 2 * specimens; ++s) {
    ks.push_back(std::exp(0.05 * normal(rng) - 0.5 * 0.05 * 0.05));
    soak.push_back(0.04 * normal(rng));
    std::array<double, 4> a{}, b{}, c{};
    for (int j = 0; j < 4; ++j) a[static_cast<size_t>(j)] = normal(rng), b[static_cast<size_t>(j)] = normal(rng), c[static_cast<size_t>(j)] = student(rng);
    zv.push_back(a), zd.push_back(b), tv.push_back(c);
  }
  // the data for a size: values, and the noise (measured minus the population model)
  auto make = [&](double size, Eigen::VectorXd* population, Eigen::VectorXd* noise) {
    set_size(size);
    RatioSet out;
    out.s.truth = effect;
    out.s.data.source = std::string("synthetic-") + std::string(diagnosis::effect_name(effect)) + "-" +
                        wear_noise_name(kind) + "-" + std::to_string(seed) + ".csv";
    out.s.data.x_name = "cycles";
    std::vector<diagnosis::Measurement> depth_rows;
    std::vector<double> pop_v, pop_d, err_v, err_d;
    int row = 2, sp_index = 0;
    for (double load : {225.0, 130.0}) {
      const auto mean = bor::simulate_bor(rig, load, law, p, cycles);
      for (int sp = 0; sp < specimens; ++sp, ++sp_index) {
        bor::BorWearParams ps = p;
        ps.k = p.k * ks[static_cast<size_t>(sp_index)];
        const auto sim = bor::simulate_bor(rig, load, law, ps, cycles);
        double walk = 0.0;
        for (size_t j = 0; j < sim.size(); ++j) {
          const double v = sim[j].volume * 1e9, sd = 0.02 + 0.01 * v;
          const double z = zv[static_cast<size_t>(sp_index)][j];
          double e = 0.0;
          switch (kind) {
            case WearNoise::walk: walk += sd / std::sqrt(2.0) * z, e = walk; break;
            case WearNoise::soak_drift:
              e = soak[static_cast<size_t>(sp_index)] * std::sqrt(sim[j].cycles / 2e5) + 0.5 * sd * z;
              break;
            case WearNoise::heavy: e = sd * tv[static_cast<size_t>(sp_index)][j] / std::sqrt(3.0); break;
            case WearNoise::lognormal: e = v * (std::exp(0.03 * z) - 1.0) + 0.02 * zd[static_cast<size_t>(sp_index)][j]; break;
          }
          diagnosis::Measurement m;
          m.group = diagnosis::bor_load_label(load);
          m.specimen = "s" + std::to_string(sp + 1);
          m.x = sim[j].cycles;
          m.row = row++;
          m.quantity = "volume_mm3";
          m.value = std::max(0.0, v + e);
          out.s.data.rows.push_back(m);
          pop_v.push_back(mean[j].volume * 1e9);
          err_v.push_back(m.value - pop_v.back());
          if (with_depth) {
            const double d = sim[j].depth * 1e3;
            m.quantity = "depth_mm";
            m.value = std::max(0.0, d + (0.002 + 0.02 * d) * zd[static_cast<size_t>(sp_index)][j]);
            depth_rows.push_back(m);
            pop_d.push_back(mean[j].depth * 1e3);
            err_d.push_back(m.value - pop_d.back());
          }
        }
      }
    }
    out.s.data.rows.insert(out.s.data.rows.end(), depth_rows.begin(), depth_rows.end());
    pop_v.insert(pop_v.end(), pop_d.begin(), pop_d.end());
    err_v.insert(err_v.end(), err_d.begin(), err_d.end());
    if (population) *population = Eigen::Map<Eigen::VectorXd>(pop_v.data(), static_cast<Eigen::Index>(pop_v.size()));
    if (noise) *noise = Eigen::Map<Eigen::VectorXd>(err_v.data(), static_cast<Eigen::Index>(err_v.size()));
    return out;
  };
  const Eigen::VectorXd k_io = Eigen::VectorXd::Constant(1, p.k * 1e6);
  Eigen::VectorXd pop, noise;
  RatioSet set = make(effect == Effect::none ? 0.0 : std::sqrt(lo * std::max(hi, lo)), &pop, &noise);
  if (effect != Effect::none) {
    for (int pass = 0; pass < 2; ++pass) {
      const auto c = diagnosis::make_bor_case(set.s.data, diagnosis::BorCaseOptions{});
      const double target = ratio * diagnosis::rmse_measure(c, noise);
      auto signal = [&](double v) {
        Eigen::VectorXd population;
        make(v, &population, nullptr);
        return diagnosis::identifiable_rms_of(c, population, k_io);
      };
      const double size = solve_size(signal, target, lo, hi, log);
      set = make(size, &pop, &noise);
      set.s.params["size"] = size;
    }
  }
  const auto c = diagnosis::make_bor_case(set.s.data, diagnosis::BorCaseOptions{});
  set.noise_rms = diagnosis::rmse_measure(c, noise);
  set.signal_rms = effect == Effect::none ? 0.0 : diagnosis::identifiable_rms_of(c, pop, k_io);
  set.s.params["k_mm3_per_Nmm"] = p.k * 1e6;
  return set;
}

}  // namespace kneesim::test
