#include "analysis/diagnosis/bor_case.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "analysis/diagnosis/measured_csv.h"
#include "engine/errors.h"
#include "wear/bor/bor_simulation.h"

namespace kneesim::diagnosis {
namespace {

constexpr const char* kColumns =
    "load_N, cycles, volume_mm3 (optional: depth_mm, specimen)";

bor::BorWearLaw law_of(Effect e) {
  switch (e) {
    case Effect::running_in: return bor::BorWearLaw::running_in;
    case Effect::pressure_dependent_wear: return bor::BorWearLaw::pressure_dependent_wear;
    case Effect::creep: return bor::BorWearLaw::creep;
    case Effect::incubation: return bor::BorWearLaw::incubation;
    case Effect::none:
    case Effect::cross_shear:
    case Effect::friction:
    case Effect::restraint:
    case Effect::load_convention: break;
    case Effect::load_line:
    case Effect::vv_moment:
    case Effect::vv_alignment: break;
  }
  return bor::BorWearLaw::archard;
}

double parse_load(const std::string& group) { return std::strtod(group.c_str(), nullptr); }

// shared state of the case's lambdas: one contact table per load
struct BorModel {
  bor::BorRig rig;
  double reference_pressure = 0.0;  // p_ref [Pa]
  double running_in_cycles = 0.0;   // N_r when it is not fitted [cycles]
  std::map<std::string, std::unique_ptr<bor::BorContactTable>> tables;
  MeasuredData measured;  // a copy, so the case can be moved or copied freely
};

// the practitioner's calibration data: the volumes of the calibration load (or the training
// load nearest to it) from the steady state on (from cycle 1 when fewer than two are there),
// and their least-squares slope
struct CalibrationSlope {
  double load = -1.0;   // [N]
  double slope = 0.0;   // [mm^3/cycle]
  std::string rows;     // the file rows used, "2, 3, 5"
};

CalibrationSlope calibration_slope(const MeasuredData& measured, const std::vector<int>& train,
                                   double cal_load, double ss_from) {
  CalibrationSlope out;
  for (int i : train) {
    const double l = parse_load(measured.rows[i].group);
    if (out.load < 0.0 || std::abs(l - cal_load) < std::abs(out.load - cal_load)) out.load = l;
  }
  std::vector<double> xs, ys;
  for (int pass = 0; pass < 2 && xs.size() < 2; ++pass) {
    xs.clear();
    ys.clear();
    out.rows.clear();
    for (int i : train) {
      const auto& m = measured.rows[i];
      if (m.quantity != "volume_mm3" || parse_load(m.group) != out.load) continue;
      if (pass == 0 ? m.x < ss_from : m.x <= 0.0) continue;
      xs.push_back(m.x);
      ys.push_back(m.value);
      out.rows += (out.rows.empty() ? "" : ", ") + std::to_string(m.row);
    }
  }
  const double n = static_cast<double>(xs.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < xs.size(); ++i) mx += xs[i] / n, my += ys[i] / n;
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < xs.size(); ++i) sxx += (xs[i] - mx) * (xs[i] - mx), sxy += (xs[i] - mx) * (ys[i] - my);
  out.slope = (sxx > 0.0) ? sxy / sxx : (mx > 0.0 ? my / mx : 0.0);
  return out;
}

}  // namespace

std::string bor_load_label(double load) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g N", load);
  return buf;
}

MeasuredData read_bor_measured(const std::string& path) {
  const CsvTable t = read_csv_table(path);
  const int c_load = t.require("load_N", kColumns);
  return read_wear_measurements(t, kColumns, "depth_mm", 1e3, [&](size_t r) {
    return bor_load_label(t.number(r, c_load, 1e-3, 1e4));
  });
}

DiagnosisCase make_bor_case(MeasuredData data, const BorCaseOptions& options) {
  DiagnosisCase c;
  c.name = "bor";
  c.measured = std::move(data);
  const auto& rows = c.measured.rows;
  std::set<std::string> loads;
  std::map<std::string, std::set<std::string>> specimens;
  bool has_depth = false;
  double max_volume = 0.0;
  for (const auto& m : rows) {
    loads.insert(m.group);
    specimens[m.group].insert(m.specimen);
    has_depth = has_depth || m.quantity == "depth_mm";
    if (m.quantity == "volume_mm3") max_volume = std::max(max_volume, m.value);
  }
  if (loads.size() < 2) {
    throw InputError(c.measured.source + ": rows " + std::to_string(rows.front().row) + "-" +
                     std::to_string(rows.back().row) + ", column load_N: every row has load " +
                     *loads.begin() + "; the block-on-ring diagnosis needs two or more loads (it "
                     "calibrates at one and judges the model at the others).");
  }

  // the running-in decay constant is identifiable only when the running-in was sampled;
  // otherwise it is fixed so that 95 % of the running-in is over at the steady-state start
  bool samples_running_in = false;
  for (const auto& m : rows) {
    samples_running_in = samples_running_in || (m.x > 0.0 && m.x < options.steady_state_from);
  }
  const double fixed_running_in_cycles = std::max(options.steady_state_from / 3.0, 1e3);

  auto model = std::make_shared<BorModel>();
  model->rig = options.rig;
  model->measured = c.measured;
  model->running_in_cycles = fixed_running_in_cycles;
  model->reference_pressure =
      bor::solve_bor_contact(options.rig, options.calibration_load, 0.0).mean_pressure;
  for (const auto& g : loads) {
    model->tables[g] = std::make_unique<bor::BorContactTable>(
        options.rig, parse_load(g), std::max(2.0 * max_volume, 0.1) * 1e-9);
  }

  c.baseline_model = "steady-state Archard V = k_D F S N, k_D from the steady-state slope "
                     "(cycles >= " + std::to_string(static_cast<long>(options.steady_state_from)) +
                     ") at " + bor_load_label(options.calibration_load);
  c.baseline_params = {{"k_mm3_per_Nmm", "steady-state wear factor k_D [mm^3/(N mm)]", 1e-13,
                        1e-5, 4.1e-10, true, {}}};
  // wear is measured gravimetrically or by profilometry: an absolute error plus a part
  // proportional to the amount (fluid uptake, soak-control correction, calibration)
  c.noise_model = NoiseModel::proportional;
  // the error model (error_model.h): with specimens, beside the scatter of each specimen's
  // wear factor, an offset per specimen on its volume rows (the soak-control correction of
  // that specimen's weighings); the gravimetric error growing with the volume is the
  // proportional noise line above
  c.error_model.specimen_offset = true;
  c.candidates = {Effect::running_in, Effect::incubation, Effect::pressure_dependent_wear};
  if (has_depth) c.candidates.push_back(Effect::creep);

  // forward model: one table-driven simulation per load for the requested rows
  const std::shared_ptr<const BorModel> shared = model;
  auto simulate = [model](Effect e, const Eigen::VectorXd& b, const Eigen::VectorXd& ep,
                          const std::string& group, const std::vector<double>& cycles) {
    bor::BorWearParams p;
    p.k = b[0] * 1e-6;
    p.reference_pressure = model->reference_pressure;
    p.running_in_cycles = model->running_in_cycles;
    const auto names = bor::wear_law_param_names(law_of(e));
    for (size_t i = 0, j = 0; i < names.size() && static_cast<Eigen::Index>(j) < ep.size(); ++i) {
      if (names[i] == "reference_pressure_MPa") continue;
      bor::set_wear_param(p, names[i], ep[static_cast<Eigen::Index>(j++)], "diagnosis fit");
    }
    return bor::simulate_bor_table(*model->tables.at(group), model->rig, law_of(e), p, cycles);
  };
  c.predict = [simulate, shared](Effect e, const Eigen::VectorXd& b, const Eigen::VectorXd& ep,
                                   const std::vector<int>& idx) {
    const MeasuredData* measured = &shared->measured;
    std::map<std::string, std::vector<int>> by_group;
    for (int i : idx) by_group[measured->rows[i].group].push_back(i);
    std::map<int, double> out;
    for (const auto& [g, members] : by_group) {
      std::vector<double> cycles;
      for (int i : members) cycles.push_back(measured->rows[i].x);
      std::vector<bor::BorRow> sim;
      try {
        sim = simulate(e, b, ep, g, cycles);
      } catch (const std::runtime_error&) {
        // parameters far outside the physical range (e.g. a scar deeper than the ring can
        // carry): no prediction, so the fit rejects the step
        return Eigen::VectorXd::Constant(static_cast<Eigen::Index>(idx.size()), NAN).eval();
      }
      for (size_t j = 0; j < members.size(); ++j) {
        const auto& m = measured->rows[members[j]];
        out[members[j]] = (m.quantity == "depth_mm") ? sim[j].depth * 1e3 : sim[j].volume * 1e9;
      }
    }
    Eigen::VectorXd v(static_cast<Eigen::Index>(idx.size()));
    for (size_t i = 0; i < idx.size(); ++i) v[static_cast<Eigen::Index>(i)] = out[idx[i]];
    return v.eval();
  };

  // practitioner's calibration: slope of volume over the steady-state points
  const bor::BorRig rig = options.rig;
  const double cal_load = options.calibration_load, ss_from = options.steady_state_from;
  c.calibrate_baseline = [shared, rig, cal_load, ss_from](const std::vector<int>& train) {
    const CalibrationSlope s = calibration_slope(shared->measured, train, cal_load, ss_from);
    const double k = s.slope / (s.load * bor::sliding_distance_per_cycle(rig) * 1e3);
    return Eigen::VectorXd::Constant(1, std::clamp(k, 1e-13, 1e-5));
  };
  // measured wear volume is cumulative: at the calibration load it must rise with cycles,
  // otherwise there is no wear factor to calibrate (and no fit to judge)
  {
    std::vector<int> all(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) all[i] = static_cast<int>(i);
    const CalibrationSlope s = calibration_slope(c.measured, all, cal_load, ss_from);
    if (s.rows.empty()) {
      // every volume row at that load is at cycle 0 (or none is a volume): nothing to fit
      throw InputError(c.measured.source + ": column cycles at the calibration load " +
                       bor_load_label(s.load) + ": no volume_mm3 row has cycles > 0; allowed: "
                       "at least two rows with cycles > 0 (cumulative volume against cycles).");
    }
    if (!(s.slope > 0.0)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "the volumes fall with cycles (slope %.3g mm^3 per 1000 "
                    "cycles); cumulative wear volume must rise (slope > 0)", s.slope * 1e3);
      throw InputError(c.measured.source + ": rows " + s.rows + ", column volume_mm3 at the " +
                       "calibration load " + bor_load_label(s.load) + ": " + buf + ".");
    }
  }

  // held-out split rule
  bool per_specimen = true;
  for (const auto& [g, s] : specimens) per_specimen = per_specimen && s.size() >= 2;
  c.split_rule = per_specimen ? "leave-one-specimen-out" : "leave-one-load-out";
  c.folds = make_leave_one_out_folds(rows, per_specimen, "load");

  // dense curves for plots
  double max_cycles = 0.0;
  for (const auto& m : rows) max_cycles = std::max(max_cycles, m.x);
  c.curves = [simulate, loads, has_depth, max_cycles](Effect e, const Eigen::VectorXd& b,
                                                      const Eigen::VectorXd& ep) {
    std::vector<double> cycles;
    for (int i = 0; i <= 100; ++i) cycles.push_back(max_cycles * 1.05 * i / 100.0);
    std::vector<CurvePoint> out;
    for (const auto& g : loads) {
      const auto sim = simulate(e, b, ep, g, cycles);
      for (const auto& r : sim) {
        out.push_back({g, "volume_mm3", r.cycles, r.volume * 1e9});
        if (has_depth) out.push_back({g, "depth_mm", r.cycles, r.depth * 1e3});
      }
    }
    return out;
  };

  c.effect_params = [samples_running_in](Effect e) {
    auto specs = effect_info(e).params;
    if (e == Effect::running_in && !samples_running_in) specs.resize(1);  // a only
    return specs;
  };
  if (!samples_running_in) {
    c.model_notes[Effect::running_in] =
        "N_r fixed at " + std::to_string(static_cast<long>(fixed_running_in_cycles)) +
        " cycles: no measurement falls inside the running-in (before " +
        std::to_string(static_cast<long>(options.steady_state_from)) +
        " cycles), so only the running-in volume a N_r k F S is identifiable";
  }
  c.model_notes[Effect::pressure_dependent_wear] =
      "p_ref = " + std::to_string(model->reference_pressure * 1e-6).substr(0, 5) +
      " MPa, the unworn mean pressure at " + bor_load_label(options.calibration_load);
  c.model_notes[Effect::creep] = "delta_el = unworn elastic penetration at each load";
  return c;
}

}  // namespace kneesim::diagnosis
