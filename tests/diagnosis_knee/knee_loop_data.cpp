#include "tests/diagnosis_knee/knee_loop_data.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "models/build_model.h"
#include "wear/wear_loop.h"

namespace kneesim::test {
namespace {

using diagnosis::Effect;

const double kCycles[] = {2.5e5, 5e5, 1e6, 1.5e6, 2e6, 3e6};
constexpr long kLoopCycles = 6'000'000;  // beyond 3 Mc x the fastest specimen and running-in
constexpr long kLoopUpdate = 400'000;

double uniform(std::mt19937_64& rng, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(rng);
}

std::map<std::string, models::Config> test_configs() {
  diagnosis::MeasuredData d;
  d.source = "knee test conditions";
  for (const auto& c : knee_test_conditions()) d.rows.push_back({c, "", "volume_mm3", 0.0, 0.0, 2});
  return diagnosis::knee_condition_configs(d, knee_test_config(), {});
}

const models::BuiltModel& built_model(const std::string& condition) {
  static const std::map<std::string, models::BuiltModel> built = [] {
    std::map<std::string, models::BuiltModel> out;
    for (const auto& [name, config] : test_configs()) out.emplace(name, models::build_model(config));
    return out;
  }();
  return built.at(condition);
}

}  // namespace

const std::vector<std::string>& knee_test_conditions() {
  static const std::vector<std::string> c = {"iso", "low_ie", "high_load", "low_load"};
  return c;
}

double LoopCurve::at(double n) const {
  const auto it = std::upper_bound(cycles.begin(), cycles.end(), n);
  size_t j = static_cast<size_t>(std::clamp<long>(it - cycles.begin(), 1,
                                                  static_cast<long>(cycles.size()) - 1));
  const double f = (n - cycles[j - 1]) / (cycles[j] - cycles[j - 1]);
  return volume[j - 1] + f * (volume[j] - volume[j - 1]);
}

LoopTruth make_loop_truth(Effect effect, std::uint64_t seed) {
  const auto t0 = std::chrono::steady_clock::now();
  std::mt19937_64 rng(seed);
  const auto& tables = knee_test_tables();
  LoopTruth t;
  t.truth = effect;
  t.k = 2.643e-16 * uniform(rng, 0.8, 1.25);
  t.params["k_mm3_per_Nmm"] = t.k * 1e6;
  wear::WearLawParams law;
  law.law = wear::WearLaw::kArchard;
  law.wear_factor = t.k;
  switch (effect) {
    case Effect::running_in:
      t.running_in_cycles = uniform(rng, 1e5, 4e5);
      t.running_in_excess = uniform(rng, 0.10, 0.30) * 3e6 / t.running_in_cycles;
      t.params["running_in_excess"] = t.running_in_excess;
      t.params["running_in_cycles"] = t.running_in_cycles;
      break;  // the Archard loop, scaled by the effective cycles per specimen
    case Effect::pressure_dependent_wear:
      law.law = wear::WearLaw::kPressureDependent;
      law.alpha = uniform(rng, 0.7, 1.5);
      law.p_ref = tables.at("iso")->mean_pressure();
      t.params["pressure_exponent"] = law.alpha;
      break;
    case Effect::cross_shear:
      law.law = wear::WearLaw::kCrossShear;
      law.beta = uniform(rng, 0.4, 1.0) / tables.at("iso")->mean_cross_shear();
      t.params["cross_shear_gain"] = law.beta;
      break;
    default: break;
  }
  for (const auto& c : knee_test_conditions()) {
    const models::BuiltModel& built = built_model(c);
    wear::WearOptions o;
    o.total_cycles = kLoopCycles;
    o.update_every = kLoopUpdate;
    o.law = law;
    o.law.friction = built.model.contact.friction;
    const wear::WearResult w = wear::run_wear(built, o);
    if (w.status != engine::StepStatus::kOk) {
      throw std::runtime_error("loop data, condition " + c + ": " + w.message);
    }
    LoopCurve curve;
    for (const auto& r : w.records) {
      curve.cycles.push_back(r.cycles);
      curve.volume.push_back(r.volume_depth * 1e9);
    }
    t.curves[c] = curve;
  }
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

KneeSynthetic make_loop_knee_wear(const LoopTruth& t, std::uint64_t seed, double specimen_cv,
                                  int specimens) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  KneeSynthetic s;
  s.truth = t.truth;
  s.params = t.params;
  s.data.source = "loop-made knee wear seed " + std::to_string(seed);
  s.data.x_name = "cycles";
  int row = 2;
  for (const auto& c : knee_test_conditions()) {
    for (int sp = 0; sp < specimens; ++sp) {
      const double scale = std::exp(specimen_cv * normal(rng));  // k_s / k
      for (double n : kCycles) {
        double x = n;
        if (t.truth == Effect::running_in) {
          x = n + t.running_in_excess * t.running_in_cycles * -std::expm1(-n / t.running_in_cycles);
        }
        const double v = t.curves.at(c).at(x * scale);
        std::string specimen = "s";
        specimen += std::to_string(sp);
        diagnosis::Measurement m{c, specimen, "volume_mm3", n, 0.0, row++};
        m.value = std::max(0.0, v + (0.2 + 0.02 * v) * normal(rng));
        s.data.rows.push_back(m);
      }
    }
  }
  return s;
}

const diagnosis::KneeWearTables& knee_test_path_tables() {
  static const diagnosis::KneeWearTables tables = [] {
    // the path reaches kPathVolumeMargin times these volumes: the Archard volume at 3 Mc of
    // the largest k of the tests (1.25 k0) times a fast specimen (1.4) and a running-in or
    // cross-shear excess (x 2)
    const auto& pristine = knee_test_tables();
    diagnosis::MeasuredData d;
    d.source = "knee test envelope";
    for (const auto& c : knee_test_conditions()) {
      diagnosis::KneeWearParams p;
      p.k = 2.643e-16 * 1.25 * 1.4 * 2.0;
      d.rows.push_back({c, "", "volume_mm3", 3e6, pristine.at(c)->volume(p, 3e6) * 1e9, 2});
    }
    return diagnosis::make_knee_wear_tables(test_configs(), d, kKneePathStates);
  }();
  return tables;
}

}  // namespace kneesim::test
