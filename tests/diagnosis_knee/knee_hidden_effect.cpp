#include "tests/diagnosis_knee/knee_hidden_effect.h"

#include <cstdlib>
#include <random>

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

}  // namespace kneesim::test
