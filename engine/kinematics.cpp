#include "engine/kinematics.h"

namespace kneesim::engine {

Eigen::Isometry3d calc_part_pose(const CarriageModel& carriage,
                                 const std::array<double, kNumDof>& q) {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.linear() = gimbal_rotation({q[3], q[4], q[5]});
  X_WB.translation() = carriage.pivot0_W + Eigen::Vector3d(q[0], q[1], q[2]);
  return X_WB * carriage.X_BP;
}

void update_kinematics(const Model& model, const State& state, Data& data) {
  for (int c = 0; c < 2; ++c) {
    const CarriageState& cs = state.carriages[c];
    const CarriageModel& cm = model.carriages[c];
    const Eigen::Vector3d t = cs.pivot_W - cm.pivot0_W;
    const GimbalAngles g = find_gimbal_angles(cs.R_WB);
    data.angles[c] = g;
    data.q[c] = {t.x(), t.y(), t.z(), g.vv, g.ie, g.fe};
    find_gimbal_axes(g, data.axes[c][0], data.axes[c][1], data.axes[c][2]);
  }
  for (int c = 0; c < 2; ++c) {
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    X_WB.linear() = state.carriages[c].R_WB;
    X_WB.translation() = state.carriages[c].pivot_W;
    (c == 0 ? data.X_WF : data.X_WT) = X_WB * model.carriages[c].X_BP;
  }
}

Eigen::Vector3d find_point_velocity(const State& state, const Data& data, int c,
                                    const Eigen::Vector3d& p_W) {
  const CarriageState& cs = state.carriages[c];
  const Eigen::Vector3d v(cs.rate[0], cs.rate[1], cs.rate[2]);
  const Eigen::Vector3d w = data.axes[c][0] * cs.rate[3] + data.axes[c][1] * cs.rate[4] +
                            data.axes[c][2] * cs.rate[5];
  return v + w.cross(p_W - cs.pivot_W);
}

}  // namespace kneesim::engine
