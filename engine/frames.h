// The project's frames and sign conventions, named once (design.md "Frames").
//
// Axes, for every frame below: +x anterior, +y superior, +z lateral of a RIGHT knee (so medial
// is -z). Right-handed, OpenSim-like. Left-knee data is mirrored at input (z -> -z), so the
// engine only ever sees a right knee.
//
//   W  world (simulator frame, fixed).
//   F  femoral component: origin at the centre of the distal sagittal arc; the
//      flexion-extension axis is F's z-axis through that origin. At zero flexion the lowest
//      distal point of the generic femur is at y = -R_distal in F.
//   T  tibial insert / tibial carriage: origin at the insert centre on its base plane (base at
//      y = 0); the dwell points (lowest points) of the two dishes are at x = 0,
//      z = -s/2 (medial) and z = +s/2 (lateral), s = condyle spacing.
//   J  the simulator joint axes (FE, IE, VV, AP, ML, IS), aligned with W.
//
// Rotations (right-hand rule about the named axis):
//   flexion  > 0: femur rotates about +z relative to the tibia (the posterior condyles come
//                 down onto the insert);
//   IE       > 0: tibia rotates about +y relative to the femur (internal for a right knee);
//   VV       > 0: tibia rotates about +x relative to the femur (varus for a right knee).
// Translations of the tibial carriage are reported as the insert relative to the femur:
//   AP > 0 anterior (+x), ML > 0 lateral (+z), IS > 0 superior (+y).
// Loads on the tibia: AP force > 0 anterior, IE torque > 0 internal (about +y).
//
// Notation (Drake monogram, small subset): X_WF is the pose of F in W, p_TP_W the position of
// point P relative to T's origin expressed in W.
#pragma once

#include <Eigen/Core>

namespace kneesim::frames {

inline const Eigen::Vector3d kAnteriorAxis{1.0, 0.0, 0.0};  // unit, +x [-]
inline const Eigen::Vector3d kSuperiorAxis{0.0, 1.0, 0.0};  // unit, +y [-]
inline const Eigen::Vector3d kLateralAxis{0.0, 0.0, 1.0};   // unit, +z of a right knee [-]

// condyle indices used wherever medial/lateral arrays appear
constexpr int kMedial = 0;   // the condyle at z < 0
constexpr int kLateral = 1;  // the condyle at z > 0

// z sign of a condyle: -1 medial, +1 lateral
constexpr double condyle_z_sign(int condyle) { return condyle == kLateral ? 1.0 : -1.0; }

}  // namespace kneesim::frames
