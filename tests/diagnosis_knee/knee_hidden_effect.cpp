#include "tests/diagnosis_knee/knee_hidden_effect.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <random>
#include <tuple>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/kinematics_case.h"

#include "models/config.h"

namespace kneesim::test {
namespace {

using diagnosis::Effect;

// the experiment: the ISO gait, a low IE torque (cross-shear contrast) and two load levels
// bracketing the ISO load (pressure contrast) (knee_conditions.toml), kKneeSpecimens each
const char* const kConditions[] = {"iso", "low_ie", "high_load", "low_load"};
const double kCycles[] = {2.5e5, 5e5, 1e6, 1.5e6, 2e6, 3e6};

double uniform(std::mt19937_64& rng, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(rng);
}

// a value from one of two ranges, chosen with equal chance
double either(std::mt19937_64& rng, double a, double b, double c, double d) {
  return uniform(rng, 0.0, 1.0) < 0.5 ? uniform(rng, a, b) : uniform(rng, c, d);
}

}  // namespace

std::string knee_test_config() {
  const char* src = std::getenv("KNEESIM_SOURCE_DIR");
  return std::string(src ? src : ".") + "/tests/diagnosis_knee/knee_conditions.toml";
}

const diagnosis::KneeWearTables& knee_test_tables() {
  static const diagnosis::KneeWearTables tables = [] {
    diagnosis::MeasuredData d;
    d.source = "knee test conditions";
    for (const char* c : kConditions) d.rows.push_back({c, "", "volume_mm3", 0.0, 0.0, 2});
    return diagnosis::make_knee_wear_tables(
        diagnosis::knee_condition_configs(d, knee_test_config(), {}));
  }();
  return tables;
}

KneeSynthetic make_synthetic_knee_wear(Effect effect, std::uint64_t seed, bool with_depth,
                                       int specimens) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto& tables = knee_test_tables();
  KneeSynthetic s;
  s.truth = effect;
  s.data.source = "synthetic knee wear seed " + std::to_string(seed);
  s.data.x_name = "cycles";
  const double p_ref = tables.at("iso")->mean_pressure();
  diagnosis::KneeWearParams p;
  p.effect = effect;
  p.reference_pressure = p_ref;
  p.k = 2.643e-16 * uniform(rng, 0.8, 1.25);
  s.params["k_mm3_per_Nmm"] = p.k * 1e6;
  switch (effect) {
    case Effect::running_in:
      p.running_in_cycles = uniform(rng, 1e5, 4e5);
      p.running_in_excess = uniform(rng, 0.10, 0.30) * 3e6 / p.running_in_cycles;
      s.params["running_in_excess"] = p.running_in_excess;
      s.params["running_in_cycles"] = p.running_in_cycles;
      break;
    case Effect::pressure_dependent_wear:
      p.pressure_exponent = uniform(rng, 0.7, 1.5);
      s.params["pressure_exponent"] = p.pressure_exponent;
      break;
    case Effect::cross_shear:
      p.cross_shear_gain = uniform(rng, 0.4, 1.0) / tables.at("iso")->mean_cross_shear();
      s.params["cross_shear_gain"] = p.cross_shear_gain;
      break;
    case Effect::creep:
      p.creep_ratio = uniform(rng, 0.5, 1.5);
      p.creep_time = uniform(rng, 2e4, 2e5);
      s.params["creep_ratio"] = p.creep_ratio;
      s.params["creep_time_s"] = p.creep_time;
      break;
    case Effect::incubation:
      p.incubation_cycles = uniform(rng, 1e5, 4e5);
      s.params["incubation_cycles"] = p.incubation_cycles;
      break;
    case Effect::none:
    case Effect::friction:
    case Effect::restraint:
    case Effect::load_convention: break;
    case Effect::load_line:
    case Effect::vv_moment:
    case Effect::vv_alignment: break;
  }
  int row = 2;
  std::vector<diagnosis::Measurement> depth_rows;
  for (const char* c : kConditions) {
    for (int sp = 0; sp < specimens; ++sp) {
      diagnosis::KneeWearParams ps = p;
      ps.k = p.k * std::exp(0.05 * normal(rng));
      const auto rates = tables.at(c)->rates(ps);
      for (double n : kCycles) {
        std::string specimen = "s";  // appended, not "s" + ...: GCC 12 -Wrestrict false alarm
        specimen += std::to_string(sp);
        diagnosis::Measurement m{c, specimen, "volume_mm3", n, 0.0, row++};
        const double v = tables.at(c)->volume(ps, rates, n) * 1e9;
        m.value = std::max(0.0, v + (0.2 + 0.02 * v) * normal(rng));
        s.data.rows.push_back(m);
        if (with_depth) {
          const double d = tables.at(c)->max_depth(ps, rates, n) * 1e3;
          m.quantity = "max_depth_mm";
          m.value = std::max(0.0, d + (0.003 + 0.03 * d) * normal(rng));
          depth_rows.push_back(m);
        }
      }
    }
  }
  s.data.rows.insert(s.data.rows.end(), depth_rows.begin(), depth_rows.end());
  return s;
}

std::shared_ptr<diagnosis::KinematicsSimulator> kinematics_test_simulator() {
  static const std::shared_ptr<diagnosis::KinematicsSimulator> sim = [] {
    // one cycle per evaluation: the generator and the fit share the model, so the start-up
    // transient of the first cycle is part of both
    const models::Config c =
        models::load_config("", {{"implant.edge_length_mm", "3.0"}, {"solver.cycles", "1"}});
    return std::make_shared<diagnosis::KinematicsSimulator>(c);
  }();
  return sim;
}

KneeSynthetic make_synthetic_kinematics(Effect effect, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  KneeSynthetic s;
  s.truth = effect;
  s.data.source = "synthetic kinematics seed " + std::to_string(seed);
  s.data.x_name = "gait_pct";
  Eigen::VectorXd ep;
  if (effect == Effect::friction) {
    ep = Eigen::VectorXd::Constant(1, either(rng, 0.02, 0.035, 0.14, 0.22));
    s.params["friction_coefficient"] = ep[0];
  } else if (effect == Effect::restraint) {
    ep.resize(2);
    ep << either(rng, 0.25, 0.5, 2.5, 5.0), uniform(rng, 1.0, 5.0);
    s.params["restraint_stiffness_scale"] = ep[0];
    s.params["restraint_gap_mm"] = ep[1];
  }
  const auto trace = kinematics_test_simulator()->run(effect, ep);
  const double offset[2] = {uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0)};
  const double noise[2] = {0.15, 0.25};
  int row = 2;
  for (int q = 0; q < 2; ++q) {
    const std::string quantity = q == 0 ? "ap_mm" : "ie_deg";
    for (int pct = 0; pct < 100; pct += 2) {
      const double v = trace->at(quantity, pct) + offset[q] + noise[q] * normal(rng);
      s.data.rows.push_back({"measured", "", quantity, static_cast<double>(pct), v, row++});
    }
  }
  return s;
}

KneeRatioSet make_knee_wear_at_ratio(Effect effect, double ratio, WearNoise kind,
                                     std::uint64_t seed, bool with_depth) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::student_t_distribution<double> student(3.0);
  const auto& tables = knee_test_tables();
  diagnosis::KneeWearParams p;
  p.effect = effect;
  p.reference_pressure = tables.at("iso")->mean_pressure();
  p.k = 2.643e-16 * uniform(rng, 0.8, 1.25);
  p.running_in_cycles = uniform(rng, 1e5, 4e5);
  p.creep_time = uniform(rng, 2e4, 2e5);
  double lo = 0.0, hi = 1.0;
  bool log = false;
  switch (effect) {
    case Effect::running_in: lo = 1e-3, hi = 1e3, log = true; break;
    case Effect::pressure_dependent_wear: lo = 0.0, hi = 4.0; break;
    case Effect::cross_shear: lo = 0.0, hi = 50.0; break;
    case Effect::creep: lo = 1e-3, hi = 20.0, log = true; break;
    default: break;
  }
  auto set_size = [&](double v) {
    switch (effect) {
      case Effect::running_in: p.running_in_excess = v; break;
      case Effect::pressure_dependent_wear: p.pressure_exponent = v; break;
      case Effect::cross_shear: p.cross_shear_gain = v; break;
      case Effect::creep: p.creep_ratio = v; break;
      default: break;
    }
  };
  const int n_sp = kKneeSpecimens * 4;
  std::vector<double> ks, soak;
  std::vector<std::array<double, 6>> zv, zd, tv;
  for (int s = 0; s < n_sp; ++s) {
    ks.push_back(std::exp(0.05 * normal(rng)));
    soak.push_back(0.8 * normal(rng));
    std::array<double, 6> a{}, b{}, c{};
    for (size_t j = 0; j < 6; ++j) a[j] = normal(rng), b[j] = normal(rng), c[j] = student(rng);
    zv.push_back(a), zd.push_back(b), tv.push_back(c);
  }
  auto make = [&](double size, Eigen::VectorXd* population, Eigen::VectorXd* noise) {
    set_size(size);
    KneeRatioSet out;
    out.s.truth = effect;
    out.s.data.source = "synthetic knee wear (" + std::string(wear_noise_name(kind)) + ") seed " +
                        std::to_string(seed);
    out.s.data.x_name = "cycles";
    std::vector<diagnosis::Measurement> depth_rows;
    std::vector<double> pop_v, pop_d, err_v, err_d;
    int row = 2, index = 0;
    for (const char* c : kConditions) {
      const auto mean_rates = tables.at(c)->rates(p);
      for (int sp = 0; sp < kKneeSpecimens; ++sp, ++index) {
        diagnosis::KneeWearParams ps = p;
        ps.k = p.k * ks[static_cast<size_t>(index)];
        const auto rates = tables.at(c)->rates(ps);
        double walk = 0.0;
        for (size_t j = 0; j < 6; ++j) {
          const double n = kCycles[j];
          std::string specimen = "s";
          specimen += std::to_string(sp);
          diagnosis::Measurement m{c, specimen, "volume_mm3", n, 0.0, row++};
          const double v = tables.at(c)->volume(ps, rates, n) * 1e9, sd = 0.2 + 0.02 * v;
          const double z = zv[static_cast<size_t>(index)][j];
          double e = 0.0;
          switch (kind) {
            case WearNoise::walk: walk += sd / std::sqrt(2.0) * z, e = walk; break;
            case WearNoise::soak_drift: e = soak[static_cast<size_t>(index)] * std::sqrt(n / 3e6) + 0.5 * sd * z; break;
            case WearNoise::heavy: e = sd * tv[static_cast<size_t>(index)][j] / std::sqrt(3.0); break;
            case WearNoise::lognormal: e = v * (std::exp(0.03 * z) - 1.0) + 0.2 * zd[static_cast<size_t>(index)][j]; break;
          }
          m.value = std::max(0.0, v + e);
          out.s.data.rows.push_back(m);
          pop_v.push_back(tables.at(c)->volume(p, mean_rates, n) * 1e9);
          err_v.push_back(m.value - pop_v.back());
          if (with_depth) {
            const double d = tables.at(c)->max_depth(ps, rates, n) * 1e3;
            m.quantity = "max_depth_mm";
            m.value = std::max(0.0, d + (0.003 + 0.03 * d) * zd[static_cast<size_t>(index)][j]);
            depth_rows.push_back(m);
            pop_d.push_back(tables.at(c)->max_depth(p, mean_rates, n) * 1e3);
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
  KneeRatioSet set = make(0.0, &pop, &noise);
  auto case_of = [&](const KneeRatioSet& s) {
    return diagnosis::make_knee_wear_case(s.s.data, tables, {});
  };
  if (effect != Effect::none) {
    for (int pass = 0; pass < 2; ++pass) {
      const auto c = case_of(set);
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
  const auto c = case_of(set);
  set.noise_rms = diagnosis::rmse_measure(c, noise);
  set.signal_rms = effect == Effect::none ? 0.0 : diagnosis::identifiable_rms_of(c, pop, k_io);
  set.s.params["k_mm3_per_Nmm"] = p.k * 1e6;
  return set;
}

const char* kinematics_noise_name(KinematicsNoise n) {
  switch (n) {
    case KinematicsNoise::registration: return "registration";
    case KinematicsNoise::smooth: return "smooth";
    case KinematicsNoise::walk: return "walk";
  }
  return "";
}

const std::vector<KinematicsNoise>& all_kinematics_noises() {
  static const std::vector<KinematicsNoise> all = {KinematicsNoise::registration,
                                                   KinematicsNoise::smooth, KinematicsNoise::walk};
  return all;
}

KinematicsSet make_kinematics_at_ratio(Effect effect, double ratio, KinematicsNoise kind,
                                       std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto sim = kinematics_test_simulator();
  Eigen::VectorXd ep;
  Effect sized = effect;
  if (effect == Effect::friction || effect == Effect::none) {
    ep = Eigen::VectorXd::Constant(1, effect == Effect::none ? 0.035 : either(rng, 0.025, 0.045, 0.11, 0.18));
    sized = Effect::friction;
  } else if (effect == Effect::restraint) {
    ep.resize(2);
    ep << either(rng, 0.35, 0.6, 1.7, 3.0), uniform(rng, 1.0, 5.0);
  }
  const auto truth = sim->run(effect, effect == Effect::none ? Eigen::VectorXd() : ep);
  const double offset[2] = {uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0)};
  // the family's noise at unit scale, per row (AP rows first, then IE, every 2 %)
  std::vector<double> noise;
  const double white[2] = {kind == KinematicsNoise::registration ? 0.1 : 0.05,
                           kind == KinematicsNoise::registration ? 0.15 : 0.08};
  const double r = (uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0) * uniform(rng, 3.0, 8.0);
  for (int q = 0; q < 2; ++q) {
    const std::string quantity = q == 0 ? "ap_mm" : "ie_deg";
    double phase[3], walk = 0.0;
    for (double& p : phase) p = uniform(rng, 0.0, 2.0 * M_PI);
    for (int pct = 0; pct < 100; pct += 2) {
      double e = white[q] * normal(rng);
      switch (kind) {
        case KinematicsNoise::registration:
          if (q == 0) e += r * std::sin(truth->at("ie_deg", pct) * M_PI / 180.0);
          break;
        case KinematicsNoise::smooth:
          for (int h = 1; h <= 3; ++h) {
            e += (q == 0 ? 0.15 : 0.25) / h * std::sin(2.0 * M_PI * h * pct / 100.0 + phase[h - 1]);
          }
          break;
        case KinematicsNoise::walk:
          walk += (q == 0 ? 0.05 : 0.08) * normal(rng);
          e += walk;
          break;
      }
      noise.push_back(e);
    }
  }
  auto make = [&](double scale, bool twin = false) {
    const auto source = twin ? sim->run(Effect::none, Eigen::VectorXd()) : truth;
    KneeSynthetic s;
    s.truth = twin ? Effect::none : effect;
    s.data.source = std::string("synthetic kinematics (") + kinematics_noise_name(kind) +
                    ") seed " + std::to_string(seed);
    s.data.x_name = "gait_pct";
    int row = 2;
    size_t k = 0;
    for (int q = 0; q < 2; ++q) {
      const std::string quantity = q == 0 ? "ap_mm" : "ie_deg";
      for (int pct = 0; pct < 100; pct += 2, ++k) {
        const double v = source->at(quantity, pct) + offset[q] + scale * noise[k];
        s.data.rows.push_back({"measured", "", quantity, static_cast<double>(pct), v, row++});
      }
    }
    return s;
  };
  KinematicsSet out;
  out.s = make(1.0);
  // the identifiable signal of the effect (or of friction 0.035 for none) and the noise, in
  // the diagnosis' measure of these data
  auto signal_and_noise = [&](const KneeSynthetic& s) {
    const auto c = diagnosis::make_kinematics_case(s.data, sim, {});
    const Eigen::VectorXd base = Eigen::Vector2d(offset[0], offset[1]);
    const double sig = diagnosis::identifiable_signal_rms(c, sized, base, ep);
    const double nz = diagnosis::rmse_measure(c, Eigen::Map<const Eigen::VectorXd>(noise.data(), static_cast<Eigen::Index>(noise.size())));
    return std::make_pair(sig, nz);
  };
  auto [sig, nz] = signal_and_noise(out.s);
  out.scale = sig / (effect == Effect::none ? 1.2 : ratio) / nz;
  out.s = make(out.scale);
  std::tie(sig, nz) = signal_and_noise(out.s);  // units move a little with the noise
  out.scale *= sig / (effect == Effect::none ? 1.2 : ratio) / (nz * out.scale);
  out.s = make(out.scale);
  out.twin = make(out.scale, true);
  out.noise_rms = nz * out.scale;
  out.signal_rms = effect == Effect::none ? 0.0 : sig;
  if (effect == Effect::friction) out.s.params["friction_coefficient"] = ep[0];
  if (effect == Effect::restraint) {
    out.s.params["restraint_stiffness_scale"] = ep[0];
    out.s.params["restraint_gap_mm"] = ep[1];
  }
  return out;
}

}  // namespace kneesim::test
