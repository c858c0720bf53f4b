#include "loads/iso14243/kinematics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/errors.h"
#include "loads/iso14243/text_table.h"

namespace kneesim::loads {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;  // [rad/deg]

Eigen::Matrix3d rot(int axis, double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

int require_column(const TextTable& t, const std::string& name, const std::string& required) {
  int c = t.column(name);
  if (c < 0) {
    throw InputError(display_path(t.file) + ": column '" + name +
                     "' is missing; required columns are " + required + ".");
  }
  return c;
}

// reads and checks the gait_pct column (range, strictly increasing, at least 2 rows)
std::vector<double> read_pct(const TextTable& t, int col) {
  if (t.cells.size() < 2) {
    throw InputError(display_path(t.file) + ": " + std::to_string(t.cells.size()) +
                     " data row(s); at least 2 are needed.");
  }
  std::vector<double> pct;
  for (std::size_t r = 0; r < t.cells.size(); ++r) {
    double p = t.number(r, col);
    const std::string where = display_path(t.file) + ": line " + std::to_string(t.line[r]) +
                              ", column '" + t.header[col] + "': " + t.cells[r][col];
    if (p < 0.0 || p > 100.0) throw InputError(where + " is outside the allowed range 0..100 %.");
    if (!pct.empty() && p <= pct.back()) {
      throw InputError(where + " does not increase over the previous row (" + t.cells[r - 1][col] +
                       ").");
    }
    pct.push_back(p);
  }
  return pct;
}

std::vector<double> read_column(const TextTable& t, int col) {
  std::vector<double> v;
  for (std::size_t r = 0; r < t.cells.size(); ++r) v.push_back(t.number(r, col));
  return v;
}

// fills the channels from the poses (inverse of pose_from_channels)
void channels_from_pose(const Eigen::Isometry3d& X_TF, const Eigen::Vector3d& p_FR_F,
                        MeasuredKinematics& k) {
  // R = Rx(a) Ry(b) Rz(c): R(0,2) = sin b, R(1,2) = -sin a cos b, R(2,2) = cos a cos b,
  // R(0,1) = -cos b sin c, R(0,0) = cos b cos c
  const Eigen::Matrix3d& R = X_TF.linear();
  const double a = std::atan2(-R(1, 2), R(2, 2));
  const double b = std::asin(std::clamp(R(0, 2), -1.0, 1.0));
  const double c = std::atan2(-R(0, 1), R(0, 0));
  const Eigen::Vector3d p_TR_T = X_TF * p_FR_F;
  k.flexion_deg.push_back(c / kDeg);
  k.ie_deg.push_back(-b / kDeg);
  k.vv_deg.push_back(-a / kDeg);
  k.ap_mm.push_back(-1000.0 * p_TR_T.x());
  k.is_mm.push_back(-1000.0 * p_TR_T.y());
  k.ml_mm.push_back(-1000.0 * p_TR_T.z());
}

MeasuredKinematics read_sto(const std::filesystem::path& file, const Eigen::Vector3d& p_FR_F) {
  TextTable t = read_text_table(file, TextFormat::sto);
  const std::string required =
      "time, knee_ant_r, knee_sup_r, knee_lat_r, knee_flex_r, knee_add_r, knee_rot_r";
  const int c_time = require_column(t, "time", required);
  int cols[6];
  const char* names[6] = {"knee_ant_r",  "knee_sup_r", "knee_lat_r",
                          "knee_flex_r", "knee_add_r", "knee_rot_r"};
  for (int i = 0; i < 6; ++i) cols[i] = require_column(t, names[i], required);

  MeasuredKinematics k;
  k.source = display_path(file);
  k.gait_pct = read_pct(t, c_time);
  // the DM frame is the project frame turned 180 deg about y: S = diag(-1, 1, -1)
  const Eigen::Matrix3d S = Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal();
  for (std::size_t r = 0; r < t.cells.size(); ++r) {
    const Eigen::Vector3d t_dm(t.number(r, cols[0]), t.number(r, cols[1]), t.number(r, cols[2]));
    const Eigen::Matrix3d R_dm =
        rot(0, t.number(r, cols[3])) * rot(1, t.number(r, cols[4])) * rot(2, t.number(r, cols[5]));
    Eigen::Isometry3d X_TF = Eigen::Isometry3d::Identity();
    X_TF.linear() = S * R_dm * S;
    X_TF.translation() = S * t_dm;
    k.X_TF.push_back(X_TF);
    channels_from_pose(X_TF, p_FR_F, k);
  }
  return k;
}

MeasuredKinematics read_csv(const std::filesystem::path& file) {
  TextTable t = read_text_table(file, TextFormat::csv);
  const std::string required = "gait_pct, ap_mm, ie_deg (optional flexion_deg, ml_mm, vv_deg, is_mm)";
  MeasuredKinematics k;
  k.source = display_path(file);
  k.gait_pct = read_pct(t, require_column(t, "gait_pct", required));
  if (int c = t.column("flexion_deg"); c >= 0) k.flexion_deg = read_column(t, c);
  k.ap_mm = read_column(t, require_column(t, "ap_mm", required));
  k.ie_deg = read_column(t, require_column(t, "ie_deg", required));
  if (int c = t.column("ml_mm"); c >= 0) k.ml_mm = read_column(t, c);
  if (int c = t.column("vv_deg"); c >= 0) k.vv_deg = read_column(t, c);
  if (int c = t.column("is_mm"); c >= 0) k.is_mm = read_column(t, c);
  auto at = [](const std::vector<double>& v, std::size_t i) { return v.empty() ? 0.0 : v[i]; };
  // without flexion the pose is undefined: a comparison needs only AP and IE
  for (std::size_t i = 0; i < (k.flexion_deg.empty() ? 0 : k.size()); ++i) {
    k.X_TF.push_back(pose_from_channels(k.flexion_deg[i], k.ap_mm[i], k.ie_deg[i], at(k.ml_mm, i),
                                        at(k.vv_deg, i), at(k.is_mm, i)));
  }
  return k;
}

}  // namespace

Eigen::Isometry3d pose_from_channels(double flexion_deg, double ap_mm, double ie_deg, double ml_mm,
                                     double vv_deg, double is_mm) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = rot(0, -vv_deg * kDeg) * rot(1, -ie_deg * kDeg) * rot(2, flexion_deg * kDeg);
  X.translation() = -1e-3 * Eigen::Vector3d(ap_mm, is_mm, ml_mm);
  return X;
}

MeasuredKinematics read_kinematics(const std::filesystem::path& file,
                                   const Eigen::Vector3d& p_FR_F) {
  if (file.extension() == ".sto") return read_sto(file, p_FR_F);
  return read_csv(file);
}

Waveform to_waveform(const MeasuredKinematics& k) {
  std::vector<std::string> names = {"ap_mm", "ie_deg"};
  std::vector<std::vector<double>> cols = {k.ap_mm, k.ie_deg};
  if (!k.flexion_deg.empty()) names.insert(names.begin(), "flexion_deg"), cols.insert(cols.begin(), k.flexion_deg);
  if (!k.ml_mm.empty()) names.push_back("ml_mm"), cols.push_back(k.ml_mm);
  if (!k.vv_deg.empty()) names.push_back("vv_deg"), cols.push_back(k.vv_deg);
  if (!k.is_mm.empty()) names.push_back("is_mm"), cols.push_back(k.is_mm);
  return Waveform::from_table(names, k.gait_pct, cols, k.source);
}

}  // namespace kneesim::loads
