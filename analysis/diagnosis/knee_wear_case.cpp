#include "analysis/diagnosis/knee_wear_case.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "analysis/diagnosis/text_format.h"
#include "analysis/diagnosis/measured_csv.h"
#include "analysis/run/calibrate_contact_law.h"
#include "engine/errors.h"

namespace kneesim::diagnosis {
namespace {

constexpr const char* kColumns = "condition, cycles, volume_mm3 (optional: max_depth_mm, specimen)";

// shared state of the case's lambdas
struct KneeModel {
  KneeWearTables tables;
  MeasuredData measured;
  double reference_pressure = 10e6;  // p_ref [Pa]
};

// least-squares slope of volume against cycles [mm^3/cycle]
double slope_of(const std::vector<double>& xs, const std::vector<double>& ys) {
  const double n = static_cast<double>(xs.size());
  if (xs.empty()) return 0.0;
  double mx = 0, my = 0;
  for (size_t i = 0; i < xs.size(); ++i) mx += xs[i] / n, my += ys[i] / n;
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < xs.size(); ++i) {
    sxx += (xs[i] - mx) * (xs[i] - mx);
    sxy += (xs[i] - mx) * (ys[i] - my);
  }
  return sxx > 0.0 ? sxy / sxx : (mx > 0.0 ? my / mx : 0.0);
}

std::string first_condition(const MeasuredData& d) {
  return d.rows.empty() ? std::string() : d.rows.front().group;
}

}  // namespace

MeasuredData read_knee_wear_measured(const std::string& path) {
  const CsvTable t = read_csv_table(path);
  const int c_cond = t.require("condition", kColumns);
  return read_wear_measurements(t, kColumns, "max_depth_mm", 100.0, [&](size_t r) {
    const std::string& group = t.cells[r][static_cast<size_t>(c_cond)];
    if (group.empty()) {
      throw InputError(path + ": row " + std::to_string(t.lines[r]) +
                       ", column condition: the condition name is empty; name a "
                       "[conditions.<name>] of the config.");
    }
    return group;
  });
}

std::map<std::string, models::Config> knee_condition_configs(const MeasuredData& data,
                                                             const std::string& config_path,
                                                             const std::vector<std::string>& sets) {
  std::vector<models::Override> common;
  for (const auto& s : sets) common.push_back(models::parse_override(s));
  const models::Config base = models::load_config(config_path, common);
  std::map<std::string, models::Config> out;
  for (const auto& m : data.rows) {
    if (out.count(m.group)) continue;
    const auto it = base.conditions.find(m.group);
    if (it == base.conditions.end()) {
      std::string defined;
      for (const auto& [name, list] : base.conditions) defined += (defined.empty() ? "" : ", ") + name;
      throw InputError(data.source + ": row " + std::to_string(m.row) + ", column condition: '" +
                       m.group + "' is not a condition of " + config_path + " (defined: " +
                       (defined.empty() ? std::string("none; add [conditions.<name>] tables")
                                        : defined) + ").");
    }
    std::vector<models::Override> overrides = common;
    for (const auto& s : it->second) overrides.push_back(models::parse_override(s));
    out[m.group] = models::load_config(config_path, overrides);
    // a condition that changes the implant or the material has a law of its own: calibrated on
    // first use as every command's (contact.calibration; --no-calibrate keeps the law as specified)
    run::ensure_contact_law(out[m.group]);
  }
  return out;
}

KneeWearTables make_knee_wear_tables(const std::map<std::string, models::Config>& configs,
                                     const MeasuredData& data, int geometry_states) {
  std::map<std::string, double> max_volume;  // [m^3]
  for (const auto& m : data.rows) {
    if (m.quantity == "volume_mm3") max_volume[m.group] = std::max(max_volume[m.group], m.value * 1e-9);
  }
  KneeWearTables tables;
  for (const auto& [name, config] : configs) {
    KneeGeometryPath path;
    if (geometry_states > 0 && max_volume[name] > 0.0) {
      path.states = geometry_states;
      path.target_volume = kPathVolumeMargin * max_volume[name];
    }
    tables[name] = std::make_shared<const KneeWearTable>(name, config, path);
  }
  return tables;
}

std::vector<ParamSpec> knee_wear_effect_params(Effect effect) {
  auto specs = effect_info(effect).params;
  for (auto& s : specs) {
    // a knee simulator runs in for 0.1-1 Mc, and creeps over days (1 Hz: 1 Mc = 11.6 days)
    if (s.name == "running_in_cycles") {
      s.lower = 1e4, s.upper = 5e6, s.initial = 2e5, s.starts = {5e4, 1e6};
    }
    if (s.name == "incubation_cycles") {
      s.lower = 1e4, s.upper = 5e6, s.initial = 2e5, s.starts = {5e4, 1e6};
    }
    if (s.name == "creep_time_s") {
      s.lower = 1e3, s.upper = 1e8, s.initial = 1e5, s.starts = {1e4, 1e6};
    }
  }
  return specs;
}

KneeWearParams knee_wear_params(Effect effect, const Eigen::VectorXd& b, const Eigen::VectorXd& ep,
                                double reference_pressure) {
  KneeWearParams p;
  p.effect = effect;
  p.k = b[0] * 1e-6;
  p.reference_pressure = reference_pressure;
  switch (effect) {
    case Effect::running_in:
      p.running_in_excess = ep[0];
      if (ep.size() > 1) p.running_in_cycles = ep[1];
      break;
    case Effect::pressure_dependent_wear: p.pressure_exponent = ep[0]; break;
    case Effect::cross_shear: p.cross_shear_gain = ep[0]; break;
    case Effect::creep:
      p.creep_ratio = ep[0];
      p.creep_time = ep[1];
      break;
    case Effect::incubation: p.incubation_cycles = ep[0]; break;
    case Effect::none:
    case Effect::friction:
    case Effect::restraint:
    case Effect::load_convention: break;
    case Effect::load_line:
    case Effect::vv_moment:
    case Effect::vv_alignment: break;
  }
  return p;
}

double knee_reference_pressure(const KneeWearTables& tables, const MeasuredData& data,
                               const KneeWearCaseOptions& options) {
  const std::string cal = options.calibration_condition.empty() ? first_condition(data)
                                                                 : options.calibration_condition;
  const auto it = tables.find(cal);
  return (it != tables.end() && it->second->mean_pressure() > 0.0) ? it->second->mean_pressure()
                                                                  : 10e6;
}

DiagnosisCase make_knee_wear_case(MeasuredData data, const KneeWearTables& tables,
                                  const KneeWearCaseOptions& options) {
  DiagnosisCase c;
  c.name = "knee-wear";
  c.measured = std::move(data);
  const auto& rows = c.measured.rows;
  std::set<std::string> conditions;
  std::map<std::string, std::set<std::string>> specimens;
  bool has_depth = false;
  for (const auto& m : rows) {
    conditions.insert(m.group);
    specimens[m.group].insert(m.specimen);
    has_depth = has_depth || m.quantity == "max_depth_mm";
    if (!tables.count(m.group)) {
      throw InputError(c.measured.source + ": row " + std::to_string(m.row) +
                       ", column condition: condition '" + m.group + "' was not simulated.");
    }
  }
  const std::string cal = options.calibration_condition.empty() ? first_condition(c.measured)
                                                                 : options.calibration_condition;
  if (!conditions.count(cal)) {
    throw InputError("command line: --calibration-condition '" + cal + "' is not a condition of " +
                     c.measured.source + ".");
  }

  auto model = std::make_shared<KneeModel>();
  model->measured = c.measured;
  for (const auto& g : conditions) model->tables[g] = tables.at(g);
  model->reference_pressure = knee_reference_pressure(tables, c.measured, options);

  int states = tables.at(cal)->geometry_states();
  for (const auto& g : conditions) states = std::min(states, tables.at(g)->geometry_states());
  const wear::WearLawParams& law = tables.at(cal)->law();
  c.baseline_model =
      (law.law == wear::WearLaw::kArchard
           ? std::string("Sarkar-corrected Archard V = k sqrt(1 + 3 mu^2) sum(A p ds) N, ")
           : "the config's wear law " + std::string(wear::wear_law_name(law.law)) +
                 " (wear.law and its parameters, as `kneesim wear` runs it; k scales its "
                 "coefficient), ") +
      (states > 1
           ? "following the geometry update (each condition's wear loop under that law recorded at " +
                 std::to_string(states) + " geometry states, pristine included, rates "
                 "interpolated in worn volume)"
           : std::string("wear linear in cycles on the pristine insert (one simulated cycle per "
                         "condition; the geometry update of `kneesim wear` is neglected)")) +
      ", k from the steady-state slope (cycles >= " + fmt("%.0f", options.steady_state_from) +
      ") of condition " + cal;
  c.baseline_params = {{"k_mm3_per_Nmm", "wear factor k [mm^3/(N mm)]", 1e-13, 1e-5, 2.643e-10,
                        true, {}}};

  // candidates from what the conditions vary
  double p_lo = 1e300, p_hi = 0, cs_lo = 1e300, cs_hi = 0;
  for (const auto& g : conditions) {
    const auto& t = *model->tables.at(g);
    p_lo = std::min(p_lo, t.mean_pressure()), p_hi = std::max(p_hi, t.mean_pressure());
    cs_lo = std::min(cs_lo, t.mean_cross_shear()), cs_hi = std::max(cs_hi, t.mean_cross_shear());
  }
  // wear is measured gravimetrically or by profilometry: an absolute error plus a part
  // proportional to the amount (fluid uptake, soak-control correction, calibration)
  c.noise_model = NoiseModel::proportional;
  // the error model (error_model.h): with specimens, beside the scatter of each specimen's
  // wear factor, an offset per specimen on its volume rows (the soak-control correction of
  // that specimen's weighings); the gravimetric error growing with the volume is the
  // proportional noise line above
  c.error_model.specimen_offset = true;
  c.candidates = {Effect::running_in, Effect::incubation};
  if (p_hi > 1.05 * p_lo) c.candidates.push_back(Effect::pressure_dependent_wear);
  if (cs_hi > 1.10 * cs_lo && cs_hi > 0.0) c.candidates.push_back(Effect::cross_shear);
  if (has_depth) c.candidates.push_back(Effect::creep);
  c.effect_params = knee_wear_effect_params;

  const std::shared_ptr<const KneeModel> shared = model;
  c.predict = [shared](Effect e, const Eigen::VectorXd& b, const Eigen::VectorXd& ep,
                       const std::vector<int>& idx) {
    const KneeWearParams p = knee_wear_params(e, b, ep, shared->reference_pressure);
    std::map<std::string, KneeWearTable::Rates> rates;  // once per condition
    Eigen::VectorXd v(static_cast<Eigen::Index>(idx.size()));
    for (size_t i = 0; i < idx.size(); ++i) {
      const auto& m = shared->measured.rows[static_cast<size_t>(idx[i])];
      const KneeWearTable& t = *shared->tables.at(m.group);
      auto it = rates.find(m.group);
      if (it == rates.end()) it = rates.emplace(m.group, t.rates(p)).first;
      v[static_cast<Eigen::Index>(i)] = (m.quantity == "max_depth_mm")
                                            ? t.max_depth(p, it->second, m.x) * 1e3
                                            : t.volume(p, it->second, m.x) * 1e9;
    }
    return v;
  };

  // practitioner's calibration: slope of volume over the steady-state points of one condition
  const double ss_from = options.steady_state_from;
  c.calibrate_baseline = [shared, cal, ss_from](const std::vector<int>& train) {
    const auto& rows = shared->measured.rows;
    std::string cond;
    for (int i : train) {
      if (rows[static_cast<size_t>(i)].group == cal) cond = cal;
    }
    if (cond.empty() && !train.empty()) cond = rows[static_cast<size_t>(train.front())].group;
    std::vector<double> xs, ys;
    for (int pass = 0; pass < 2 && xs.size() < 2; ++pass) {
      xs.clear(), ys.clear();
      for (int i : train) {
        const auto& m = rows[static_cast<size_t>(i)];
        if (m.quantity != "volume_mm3" || m.group != cond) continue;
        if (pass == 0 ? m.x < ss_from : m.x <= 0.0) continue;
        xs.push_back(m.x);
        ys.push_back(m.value);
      }
    }
    KneeWearParams unit;
    unit.k = 1e-6;  // 1 mm^3/(N mm)
    // mm^3 per cycle on the pristine insert at k = 1 mm^3/(N mm)
    const double per_k = shared->tables.at(cond)->rates(unit).volume[0] * 1e9;
    const double k = per_k > 0.0 ? slope_of(xs, ys) / per_k : 2.643e-10;
    return Eigen::VectorXd::Constant(1, std::clamp(k, 1e-13, 1e-5)).eval();
  };

  // held-out split rule
  bool per_specimen = conditions.size() >= 1;
  for (const auto& [g, s] : specimens) per_specimen = per_specimen && s.size() >= 2;
  if (!per_specimen && conditions.size() < 2) {
    throw InputError(c.measured.source + ": rows " + std::to_string(rows.front().row) + "-" +
                     std::to_string(rows.back().row) + ", column condition: every row has "
                     "condition " + cal + " and no condition has two specimens; the knee-wear "
                     "diagnosis needs two conditions or two specimens per condition to hold "
                     "data out.");
  }
  c.split_rule = per_specimen ? "leave-one-specimen-out" : "leave-one-condition-out";
  c.folds = make_leave_one_out_folds(rows, per_specimen, "condition");

  double max_cycles = 0.0;
  for (const auto& m : rows) max_cycles = std::max(max_cycles, m.x);
  c.curves = [shared, has_depth, max_cycles](Effect e, const Eigen::VectorXd& b,
                                             const Eigen::VectorXd& ep) {
    const KneeWearParams p = knee_wear_params(e, b, ep, shared->reference_pressure);
    std::vector<CurvePoint> out;
    for (const auto& [g, t] : shared->tables) {
      const KneeWearTable::Rates r = t->rates(p);
      for (int i = 0; i <= 100; ++i) {
        const double n = max_cycles * 1.05 * i / 100.0;
        out.push_back({g, "volume_mm3", n, t->volume(p, r, n) * 1e9});
        if (has_depth) out.push_back({g, "max_depth_mm", n, t->max_depth(p, r, n) * 1e3});
      }
    }
    return out;
  };

  std::string pressures, shears;
  for (const auto& [g, t] : model->tables) {
    pressures += (pressures.empty() ? "" : ", ") + g + " " + fmt("%.2f", t->mean_pressure() * 1e-6);
    shears += (shears.empty() ? "" : ", ") + g + " " + fmt("%.4f", t->mean_cross_shear());
  }
  c.model_notes[Effect::pressure_dependent_wear] =
      "p = local contact pressure of each step, p_ref = " +
      fmt("%.3f", model->reference_pressure * 1e-6) + " MPa (work-weighted geometric mean "
      "pressure of " + cal + "; per condition, MPa: " + pressures +
      "); forward: kneesim wear --wear-law pressure_dependent_wear";
  c.model_notes[Effect::cross_shear] =
      "CS per element from the frictional-work tensor of the cycle (Kang 2008; work-weighted "
      "mean CS: " + shears + "); forward: kneesim wear --wear-law cross_shear";
  c.model_notes[Effect::running_in] = "running-in as in the block-on-ring case, on every condition";
  c.model_notes[Effect::incubation] = "incubation as in the block-on-ring case, on every condition";
  c.model_notes[Effect::creep] =
      "delta_el = largest elastic penetration of each condition's cycle, t = cycles x period";
  return c;
}

}  // namespace kneesim::diagnosis
