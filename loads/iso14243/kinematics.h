// Measured tibiofemoral kinematics over one gait cycle, in the project's frame and sign
// conventions (engine/frames.h), for comparison with simulations and for displacement-control
// runs.
//
// Convention of the channels (the same for every source):
//   flexion_deg  rotation of the femur about the z-axis, positive flexed;
//   ie_deg       rotation of the tibia about y relative to the femur, positive internal;
//   vv_deg       rotation of the tibia about x relative to the femur, positive varus;
//   ap_mm, is_mm, ml_mm   position of the insert origin relative to the femoral reference
//                point, in insert axes: + anterior, + superior, + lateral. This is the tibial
//                carriage translation that the engine reports (insert relative to femur).
// They define the pose of the femoral frame F in the insert frame T as
//   R_TF = Rx(-vv) * Ry(-ie) * Rz(flexion),   p_TF_T = -(ap, is, ml),
// a Cardan x-y-z sequence with the flexion axis fixed in the femur and the VV axis fixed in the
// tibia: exactly the sequence of the Grand Challenge .sto files, so no information is lost.
//
// Sources:
//  (a) CSV with columns gait_pct, ap_mm, ie_deg and optional flexion_deg, ml_mm, vv_deg, is_mm,
//      already in this convention (without flexion_deg there is no pose X_TF, and displacement
//      mode keeps the gait file's flexion);
//  (b) OpenSim .sto of the Grand Challenge DM subject (see the data README): despite the
//      column names, knee_ant_r/sup_r/lat_r are the x/y/z translation in metres and
//      knee_flex_r/add_r/rot_r the rotations about x/y/z in radians, with
//      p_insert = Rx*Ry*Rz*p_femoral + t in a frame with +X posterior, +Y superior, +Z medial,
//      i.e. the project frame turned 180 deg about y (x -> -x, z -> -z; a right knee).
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "loads/iso14243/waveform.h"

namespace kneesim::loads {

struct MeasuredKinematics {
  std::string source;                   // file it was read from
  std::vector<double> gait_pct;         // [%] strictly increasing in 0..100, n
  std::vector<double> flexion_deg;      // [deg] n, or empty when a CSV has none
  std::vector<double> ap_mm;            // [mm] n
  std::vector<double> ie_deg;           // [deg] n
  std::vector<double> ml_mm;            // [mm] n, or empty when the source has none
  std::vector<double> vv_deg;           // [deg] n, or empty when the source has none
  std::vector<double> is_mm;            // [mm] n, or empty when the source has none
  std::vector<Eigen::Isometry3d> X_TF;  // pose of F in T [m], project axes, n (absent
                                        // channels taken as zero); empty without flexion
  std::size_t size() const { return gait_pct.size(); }
};

// reads (a) a CSV or (b) an OpenSim .sto file (chosen by the extension .sto). For .sto files
// `p_FR_F` is the femoral reference point whose translation is reported, in the source's
// femoral frame but project axes [m] (default: the source's femoral origin; e.g. the distal
// arc centre to match the engine's frame F). Throws InputError naming the file, line and
// column for a missing file, a missing column, non-numbers, ragged rows, gait_pct outside
// 0..100 or not increasing, and fewer than 2 rows.
MeasuredKinematics read_kinematics(const std::filesystem::path& file,
                                   const Eigen::Vector3d& p_FR_F = Eigen::Vector3d::Zero());

// the pose of F in T from the channels (see the convention above)
Eigen::Isometry3d pose_from_channels(double flexion_deg, double ap_mm, double ie_deg, double ml_mm,
                                     double vv_deg, double is_mm);

// a table waveform (linear periodic interpolation) with the channels present in `k`
// (flexion_deg, ap_mm, ie_deg, then ml_mm, vv_deg, is_mm when present), so displacement mode
// can prescribe them
Waveform to_waveform(const MeasuredKinematics& k);

}  // namespace kneesim::loads
