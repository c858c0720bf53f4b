#include "engine/joint_coordinates.h"

#include "engine/rotation.h"

namespace kneesim::engine {

JointCoordinates calc_joint_coordinates(const Eigen::Isometry3d& X_WF,
                                        const Eigen::Isometry3d& X_WT) {
  JointCoordinates j;
  // rotations: the gimbal decomposition of the relative rotation
  const Eigen::Matrix3d R_FT = X_WF.linear().transpose() * X_WT.linear();
  const GimbalAngles g = find_gimbal_angles(R_FT);
  j.flexion = -g.fe;
  j.vv = g.vv;
  j.ie = g.ie;
  // translations: F origin -> T origin on the joint axes (e2 is orthogonal to e1 and e3, so
  // the basis is invertible for |vv| < 90 deg)
  const Eigen::Vector3d e1 = X_WF.linear().col(2);
  const Eigen::Vector3d e3 = X_WT.linear().col(1);
  const Eigen::Vector3d e2 = e3.cross(e1).normalized();
  Eigen::Matrix3d basis;
  basis << e1, e2, e3;
  const Eigen::Vector3d q = basis.inverse() * (X_WT.translation() - X_WF.translation());
  j.ml = q.x();
  j.ap = q.y();
  j.is = q.z();
  return j;
}

}  // namespace kneesim::engine
