// Tibiofemoral joint coordinates in the Grood-Suntay sense (Grood & Suntay 1983, J Biomech Eng
// 105:136): the pose of the tibial insert T relative to the femoral component F, whatever DOFs
// the rig frees on either carriage. This is what every output reports as flexion, AP, IE, ML
// and VV; the carriage coordinates (Data::q) are rig coordinates and are not the joint's when
// the femoral carriage translates or tilts (the materials_study rig frees femoral AP, ML, VV).
//
// Axes: e1 the femoral flexion axis (F's +z, fixed in the femur), e3 the tibial long axis (T's
// +y, fixed in the tibia), e2 = e3 x e1 / |e3 x e1| the floating axis (anterior).
// Rotations: R_FT = Rz(-flexion) Rx(vv) Ry(ie), the gimbal order of engine/rotation.h, so
// flexion is the femur's rotation about e1 relative to the tibia, VV the rotation about e2 and
// IE the tibia's rotation about e3 (project signs: engine/frames.h).
// Translations: the vector from F's origin (on the flexion axis) to T's origin (the insert
// centre on its base plane) written on the non-orthogonal basis e1, e2, e3: ML along e1, AP
// along e2, IS along e3 (Grood-Suntay's q1, q2, q3). With no VV, AP and ML are the plain
// components along the tibial anterior and lateral axes. The insert centre, not a carriage
// pivot, is the tibial reference so that the figures do not depend on where a rig puts its
// IE/VV pivot (stanmore 5 mm medial, materials_study central).
#pragma once

#include <Eigen/Geometry>

namespace kneesim::engine {

struct JointCoordinates {
  double flexion = 0.0;  // femur about e1 relative to the tibia, + flexion [rad]
  double vv = 0.0;       // tibia about e2 relative to the femur, + varus [rad]
  double ie = 0.0;       // tibia about e3 relative to the femur, + internal [rad]
  double ap = 0.0;       // insert centre along e2 from the femoral origin, + anterior [m]
  double ml = 0.0;       // along e1, + lateral [m]
  double is = 0.0;       // along e3, + superior (negative: the insert is below the femur) [m]
};

// joint coordinates of the insert pose X_WT relative to the femoral pose X_WF (|vv| < 90 deg)
JointCoordinates calc_joint_coordinates(const Eigen::Isometry3d& X_WF,
                                        const Eigen::Isometry3d& X_WT);

}  // namespace kneesim::engine
