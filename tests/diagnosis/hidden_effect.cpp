#include "tests/diagnosis/hidden_effect.h"

#include <random>

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
