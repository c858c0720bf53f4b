#include "analysis/diagnosis/kinematics_case.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "analysis/diagnosis/measured_csv.h"
#include "engine/errors.h"
#include "loads/iso14243/kinematics.h"

namespace kneesim::diagnosis {
namespace {

constexpr const char* kColumns = "gait_pct, ap_mm, ie_deg";
const char* const kQuantities[] = {"ap_mm", "ie_deg"};

}  // namespace

Eigen::Vector3d femoral_reference_point(const models::Config& c) {
  if (c.implant_kind != "mesh") return Eigen::Vector3d::Zero();
  return Eigen::Vector3d(c.femur_origin_mm[0], c.femur_origin_mm[1], c.femur_origin_mm[2]) * 1e-3;
}

MeasuredData read_kinematics_measured(const std::string& path, const Eigen::Vector3d& p_FR_F) {
  MeasuredData d;
  d.source = path;
  d.x_name = "gait_pct";
  const std::string group = std::filesystem::path(path).stem().string();  // plot legend
  if (std::filesystem::path(path).extension() == ".sto") {
    const loads::MeasuredKinematics k = loads::read_kinematics(path, p_FR_F);
    for (const char* q : kQuantities) {
      const std::vector<double>& v = std::string(q) == "ap_mm" ? k.ap_mm : k.ie_deg;
      for (size_t i = 0; i < k.size(); ++i) {
        d.rows.push_back({group, "", q, k.gait_pct[i], v[i], static_cast<int>(i) + 2});
      }
    }
    return d;
  }
  const CsvTable t = read_csv_table(path);
  const int c_pct = t.require("gait_pct", kColumns);
  const int c_ap = t.require("ap_mm", kColumns);
  const int c_ie = t.require("ie_deg", kColumns);
  double last = -1.0;
  for (const char* q : kQuantities) {
    const int col = std::string(q) == "ap_mm" ? c_ap : c_ie;
    for (size_t r = 0; r < t.cells.size(); ++r) {
      const double pct = t.number(r, c_pct, 0.0, 100.0);
      if (col == c_ap) {
        if (pct <= last) {
          throw InputError(path + ": row " + std::to_string(t.lines[r]) + ", column gait_pct: " +
                           std::to_string(pct) + " does not increase (previous row " +
                           std::to_string(last) + "); rows must be in increasing gait %.");
        }
        last = pct;
      }
      const double v = (col == c_ap) ? t.number(r, col, -100.0, 100.0) : t.number(r, col, -90.0, 90.0);
      d.rows.push_back({group, "", q, pct, v, t.lines[r]});
    }
  }
  if (t.cells.size() < 8) {
    throw InputError(path + ": rows 2-" + std::to_string(t.lines.back()) + ", column gait_pct: " +
                     std::to_string(t.cells.size()) + " samples are too few; the kinematics "
                     "diagnosis needs at least 8 samples over the cycle.");
  }
  return d;
}

DiagnosisCase make_kinematics_case(MeasuredData data, std::shared_ptr<KinematicsSimulator> sim,
                                   const KinematicsCaseOptions& options) {
  DiagnosisCase c;
  c.name = "kinematics";
  c.measured = std::move(data);
  const double split = options.stance_end_pct;
  int stance = 0, swing = 0;
  for (const auto& m : c.measured.rows) (m.x < split ? stance : swing) += 1;
  if (stance < 4 || swing < 4) {
    throw InputError(c.measured.source + ": column gait_pct: the samples do not cover both stance "
                     "(0-" + std::to_string(static_cast<int>(split)) + " %) and swing with at "
                     "least two samples each; the kinematics diagnosis holds one phase out.");
  }
  c.baseline_model =
      "force-controlled rig of " +
      (sim->config().file.empty() ? std::string("the built-in config") : sim->config().file.string()) +
      " as configured (rig " + sim->config().rig_preset + ", friction " +
      std::to_string(sim->config().friction_override >= 0 ? sim->config().friction_override
                                                          : sim->config().material.friction)
          .substr(0, 5) +
      "), measured reference frame registered by AP and IE offsets (mean difference over the "
      "training rows)";
  c.baseline_params = {
      {"ap_offset_mm", "AP offset of the measured reference frame [mm]", -30.0, 30.0, 0.0, false, {}},
      {"ie_offset_deg", "IE offset of the measured reference frame [deg]", -45.0, 45.0, 0.0, false, {}}};
  c.specimen_param = 0;
  // one measured curve against a rig model: the residuals are discrepancy, not measurement
  // noise, so AP and IE share one sd in RMS-ratio units (diagnosis_case.h, NoiseModel)
  c.noise_model = NoiseModel::pooled;
  c.candidates = {Effect::friction};
  bool has_restraint = sim->config().restraint != "none";
  if (has_restraint) c.candidates.push_back(Effect::restraint);
  c.candidates.push_back(Effect::load_convention);
  // the sign of the AP force (the open question of issue 14): starts at +1 and -1, since a
  // local fit does not cross zero; the IE torque starts at +1 only (two starts, not four: each
  // start costs up to 40 simulations)
  c.multi_start_effects = {Effect::load_convention};
  const double mu0 = sim->nominal_friction(), gap0 = sim->nominal_gap_mm();
  c.effect_params = [mu0, gap0](Effect e) {
    auto specs = effect_info(e).params;
    // above 0.3 the regularized Coulomb slope approaches the explicit stability limit
    if (e == Effect::friction) specs[0].upper = 0.3, specs[0].null_value = mu0;
    if (e == Effect::restraint) specs[1].null_value = gap0;
    return specs;
  };
  // the error model: residuals correlated along the gait cycle within each channel (a
  // fluoroscopic registration error is smooth over the cycle), and the coupling of the
  // measured AP to IE through a misplaced rotation centre: the AP of a reference point that
  // lies r mediolaterally from the rig's IE axis moves by r sin(IE) (prior sd
  // rotation_centre_sd_mm, default 5 mm: the reference point of the measured frame against
  // the rig's axis). The registration offsets are the baseline's own parameters.
  c.fit_control.refit_in_noise_profile = false;
  c.fit_control.noise_iterations = 3;
  c.expensive_forward = true;
  c.series_unit = "% of the gait cycle";
  c.error_model.correlation = Correlation::ou;
  {
    // the measured IE at each AP row's gait %, interpolated (the measured channel is the
    // regressor: its noise is small against its range)
    std::vector<double> ie_x, ie_v;
    for (const auto& m : c.measured.rows) {
      if (m.quantity == "ie_deg") ie_x.push_back(m.x), ie_v.push_back(m.value);
    }
    std::vector<double> sin_ie(c.measured.rows.size(), 0.0);
    for (size_t i = 0; i < c.measured.rows.size() && ie_x.size() >= 2; ++i) {
      const auto& m = c.measured.rows[i];
      if (m.quantity != "ap_mm") continue;
      size_t k = 1;
      while (k + 1 < ie_x.size() && ie_x[k] < m.x) ++k;
      const double t = std::clamp((m.x - ie_x[k - 1]) / (ie_x[k] - ie_x[k - 1]), 0.0, 1.0);
      sin_ie[i] = std::sin((ie_v[k - 1] + t * (ie_v[k] - ie_v[k - 1])) * M_PI / 180.0);
    }
    c.error_model.nuisance = {
        {"rotation_centre_mm",
         "mediolateral offset of the measured reference point from the rig's IE axis: AP += r "
         "sin(IE) [mm]",
         5.0, "rotation_centre_sd_mm",
         [sin_ie](const std::vector<int>& rows, const Eigen::VectorXd&) {
           Eigen::VectorXd v(static_cast<Eigen::Index>(rows.size()));
           for (size_t i = 0; i < rows.size(); ++i) v[static_cast<Eigen::Index>(i)] = sin_ie[static_cast<size_t>(rows[i])];
           return v;
         }}};
  }

  auto measured = std::make_shared<const MeasuredData>(c.measured);
  c.predict = [sim, measured](Effect e, const Eigen::VectorXd& b, const Eigen::VectorXd& ep,
                              const std::vector<int>& idx) {
    const auto trace = sim->run(e, ep);
    Eigen::VectorXd v(static_cast<Eigen::Index>(idx.size()));
    for (size_t i = 0; i < idx.size(); ++i) {
      const auto& m = measured->rows[static_cast<size_t>(idx[i])];
      const double offset = (m.quantity == "ie_deg") ? b[1] : b[0];
      v[static_cast<Eigen::Index>(i)] = trace->ok ? trace->at(m.quantity, m.x) + offset : NAN;
    }
    return v;
  };
  // registration: mean measured - model of each quantity over the training rows
  c.calibrate_baseline = [sim, measured](const std::vector<int>& train) {
    const auto trace = sim->run(Effect::none, Eigen::VectorXd());
    Eigen::Vector2d sum = Eigen::Vector2d::Zero(), n = Eigen::Vector2d::Zero();
    for (int i : train) {
      const auto& m = measured->rows[static_cast<size_t>(i)];
      const int q = (m.quantity == "ie_deg") ? 1 : 0;
      sum[q] += m.value - trace->at(m.quantity, m.x);
      n[q] += 1.0;
    }
    Eigen::VectorXd b(2);
    for (int q = 0; q < 2; ++q) b[q] = n[q] > 0.0 ? sum[q] / n[q] : 0.0;
    return b;
  };

  // every evaluation is a simulation: few iterations, stop at 0.01 % cost decrease
  c.fit_control.max_iterations = 8;
  c.fit_control.tolerance = 1e-4;
  // differences over 2 % of each parameter's range: the rig's friction is capped at Coulomb's
  // bound per step (engine/implicit_friction.h), so a change of 1e-6 in mu moves the trace by
  // the stick/slip branches it flips, not by its effect (fit.h)
  c.fit_control.coarse_jacobian = true;
  // fits side by side (the simulator limits the simulations running at a time)
  c.fit_control.threads = sim->threads();
  c.prefetch = [sim](Effect e, const std::vector<Eigen::VectorXd>& params) {
    sim->run_many(e, params);
  };
  c.split_rule = "2-fold cross-validation by gait phase (fit on stance 0-" +
                 std::to_string(static_cast<int>(split)) + " %, predict swing; fit on swing, "
                 "predict stance)";
  Fold to_swing{"stance -> swing", {}, {}}, to_stance{"swing -> stance", {}, {}};
  for (size_t i = 0; i < c.measured.rows.size(); ++i) {
    const bool in_stance = c.measured.rows[i].x < split;
    (in_stance ? to_swing.train : to_swing.test).push_back(static_cast<int>(i));
    (in_stance ? to_stance.test : to_stance.train).push_back(static_cast<int>(i));
  }
  c.folds = {to_swing, to_stance};

  const std::string group = c.measured.rows.front().group;
  c.curves = [sim, group](Effect e, const Eigen::VectorXd& b, const Eigen::VectorXd& ep) {
    const auto trace = sim->run(e, ep);
    std::vector<CurvePoint> out;
    for (size_t i = 0; trace->ok && i < trace->gait_pct.size(); ++i) {
      out.push_back({group, "ap_mm", trace->gait_pct[i], trace->ap_mm[i] + b[0]});
    }
    for (size_t i = 0; trace->ok && i < trace->gait_pct.size(); ++i) {
      out.push_back({group, "ie_deg", trace->gait_pct[i], trace->ie_deg[i] + b[1]});
    }
    return out;
  };
  c.model_notes[Effect::friction] =
      "forward: kneesim run CONFIG --set contact.friction=MU";
  c.model_notes[Effect::load_convention] =
      "forward: kneesim run CONFIG --set gait.ap_sign=-1 --set gait.ap_force_scale=|s| --set "
      "gait.ap_force_shift_pct=d ... (the command prints the exact list)";
  c.model_notes[Effect::restraint] =
      "forward: kneesim run CONFIG --set rig.restraint.k_..._N_per_mm=s k --set "
      "rig.restraint.gap_mm=g (the command prints the exact list)";
  return c;
}

}  // namespace kneesim::diagnosis
