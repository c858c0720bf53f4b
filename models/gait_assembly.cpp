#include "models/gait_assembly.h"

#include <algorithm>
#include <cmath>

#include "engine/errors.h"
#include "loads/iso14243/conventions.h"
#include "loads/iso14243/kinematics.h"

namespace kneesim::models {
namespace {

constexpr double kMm = 1e-3;

std::string config_name(const Config& c) {
  return c.file.empty() ? std::string("built-in config") : c.file.string();
}

// the stance shape of the VV torque: half-cosine key points (gait %, fraction of the peak),
// zero at heel strike and from toe-off (62 %) on; peaks at 15 % (loading response) and 47 %
// (terminal stance) with a dip at 30 % like the external knee adduction moment of walking.
// An assumed shape: the diagnosis fits only its amplitude.
const loads::Waveform& stance_shape() {
  static const loads::Waveform w = loads::Waveform::from_keypoints(
      {{"shape", {0.0, 15.0, 30.0, 47.0, 62.0}, {0.0, 1.0, 0.6, 0.85, 0.0}}}, "stance VV shape");
  return w;
}

}  // namespace

const std::vector<std::string>& measured_rig_channels() {
  static const std::vector<std::string> names = {
      "flexion_deg", "axial_force_N", "ap_force_N", "ie_torque_Nm", "vv_torque_Nm",
      "ap_mm",       "ie_deg",        "ml_mm",      "vv_deg"};
  return names;
}

loads::MeasuredLoadSpec measured_load_spec(const Config& c) {
  loads::MeasuredLoadSpec s;
  s.file = resolve_path(c, c.measured_file);
  s.origin = config_name(c) + " [gait.measured]";
  s.time_column = c.measured_time_column;
  s.time_unit = c.measured_time_unit;
  s.window = c.measured_window;
  s.units = {{"force", c.measured_force_unit},
             {"moment", c.measured_moment_unit},
             {"angle", c.measured_angle_unit},
             {"length", c.measured_length_unit}};
  s.channels = c.measured_channels;
  s.channels.insert(s.channels.end(), c.measured_compare.begin(), c.measured_compare.end());
  return s;
}

// gait waveform with the sign conventions applied; in displacement mode with a measured
// kinematics file, the measured channels are merged in (sampled every 0.25 %); a measured
// load table's rig channels replace the file's
loads::Waveform make_gait(const Config& c, const loads::Waveform* measured_cycle) {
  const std::filesystem::path gait_path = resolve_path(c, c.gait_file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(gait_path, ec)) {
    throw InputError((c.file.empty() ? std::string("built-in config") : c.file.string()) +
                     ": gait.file = \"" + c.gait_file + "\": " +
                     (std::filesystem::is_directory(gait_path, ec) ? "'" + gait_path.string() +
                                                                       "' is a folder"
                                                                 : "no file '" +
                                                                       gait_path.string() + "'") +
                     "; allowed: a gait waveform table (CSV) or key-point file, relative to the "
                     "config or with ${KNEESIM_SOURCE} / ${KNEESIM_DATA}.");
  }
  loads::Waveform gait = loads::load_waveform(gait_path);
  loads::WaveformConventions conv;
  conv.ap_sign = c.ap_sign;
  conv.ie_sign = c.ie_sign;
  gait = loads::apply_conventions(gait, conv);
  gait = loads::delay_channels(gait, {{"ap_force_N", c.ap_force_shift_pct},
                                      {"ie_torque_Nm", c.ie_torque_shift_pct}});
  if (!c.kinematics_file.empty()) {
    // the measured pose about the femoral reference point the engine uses (the FE axis centre)
    const Eigen::Vector3d p_FR_F =
        c.implant_kind == "mesh"
            ? Eigen::Vector3d(Eigen::Vector3d(c.femur_origin_mm[0], c.femur_origin_mm[1],
                                              c.femur_origin_mm[2]) * kMm)
            : Eigen::Vector3d::Zero();
    const loads::Waveform measured =
        loads::to_waveform(loads::read_kinematics(resolve_path(c, c.kinematics_file), p_FR_F));
    std::vector<std::string> names;
    std::vector<std::vector<double>> columns;
    std::vector<double> pct;
    for (int i = 0; i <= 400; ++i) pct.push_back(0.25 * i);
    pct.back() = 100.0;
    auto add = [&](const loads::Waveform& w, int ch) {
      names.push_back(w.channel_name(ch));
      std::vector<double> col;
      for (double p : pct) col.push_back(w.value(ch, p));
      columns.push_back(col);
    };
    for (int ch = 0; ch < measured.channel_count(); ++ch) {
      add(measured, ch);
      // a measured cycle rarely closes: remove the linear drift between 0 and 100 % so that a
      // prescribed DOF does not jump at the cycle boundary (a jump is an infinite velocity)
      std::vector<double>& col = columns.back();
      const double drift = col.back() - col.front();
      for (size_t i = 0; i < col.size(); ++i) col[i] -= drift * pct[i] / 100.0;
    }
    for (int ch = 0; ch < gait.channel_count(); ++ch) {
      if (measured.channel(gait.channel_name(ch)) < 0) add(gait, ch);
    }
    gait = loads::Waveform::from_table(names, pct, columns,
                                       gait.source() + " + " + measured.source());
  }
  if (measured_cycle) {
    gait.merge(*measured_cycle);
  } else if (!c.measured_file.empty()) {
    for (const std::string& text : c.measured_channels) {
      const std::string target = text.substr(0, text.find('='));
      const auto& rig = measured_rig_channels();
      const auto t = target.substr(0, target.find_last_not_of(" \t") + 1);
      if (std::find(rig.begin(), rig.end(), t) == rig.end()) {
        std::string allowed;
        for (const auto& n : rig) allowed += (allowed.empty() ? "" : ", ") + n;
        throw InputError(config_name(c) + ": gait.measured.channels entry \"" + text +
                         "\" drives '" + t + "', which is not a rig channel (allowed: " +
                         allowed + "; measured outputs go in gait.measured.compare).");
      }
    }
    const loads::MeasuredLoads loads = loads::read_measured_loads(measured_load_spec(c));
    std::vector<std::string> rig_names;
    for (const std::string& n : loads.names) {
      const auto& rig = measured_rig_channels();
      if (std::find(rig.begin(), rig.end(), n) != rig.end()) rig_names.push_back(n);
    }
    gait.merge(loads::cycle_waveform(loads, rig_names));
  }
  return with_vv_torque(gait, c.vv_torque_axial_arm_mm, c.vv_torque_stance_arm_mm,
                        c.axial_force_scale);
}

double stance_vv_shape(double gait_pct) {
  return gait_pct >= 62.0 ? 0.0 : stance_shape().value(0, gait_pct);
}

loads::Waveform with_vv_torque(const loads::Waveform& gait, double arm_mm, double stance_arm_mm,
                               double axial_force_scale) {
  if (arm_mm == 0.0 && stance_arm_mm == 0.0) return gait;
  const int axial = gait.channel("axial_force_N");
  const int existing = gait.channel("vv_torque_Nm");
  if (axial < 0) {
    throw InputError(gait.source() + ": a VV torque following the axial force needs an "
                     "axial_force_N channel.");
  }
  std::vector<double> pct, torque;
  for (int i = 0; i <= 400; ++i) {
    const double p = 0.25 * i;
    const double lever_mm = arm_mm + stance_arm_mm * stance_vv_shape(p);
    double m = lever_mm * kMm * axial_force_scale * gait.value(axial, p);
    if (existing >= 0) m += gait.value(existing, p);
    pct.push_back(p);
    torque.push_back(m);
  }
  loads::Waveform out = gait;
  out.merge(loads::Waveform::from_table({"vv_torque_Nm"}, pct, {torque}, "VV torque"));
  return out;
}

}  // namespace kneesim::models
