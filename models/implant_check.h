// One's own implant meshes, checked and described before any simulation. Every command that
// builds a mesh implant calls check_implant() (through build_model) so that a mesh the rig
// cannot use is refused with one sentence (InputError, exit 2) instead of simulating to a
// runaway or to a wrong "complete" result; `kneesim implant check` calls describe_implant() as
// well and prints what the run will use (sizes, articular area, flexion axis, gaps) with
// warnings about the frame.
//
// Frames: the femur arrives in F (the rotated mesh frame minus implant.mesh.femur_origin_mm,
// so F's origin is the flexion-extension axis) and the insert in T (the rotated mesh frame
// minus implant.mesh.insert_base_y_mm in y). The run puts F's origin at (0, y, 0) over T's
// origin, so x and z of both frames coincide in the rig; only the height is chosen by the run
// (the femur starts 1 mm above the insert's highest articular point and is lowered under the
// first axial load). "As given in the files" means both meshes in the rotated mesh frame.
//
// The geometric tests use features every knee implant has and which do not depend on the
// design: the insert's flat base (the largest flat downward area at its bottom; an upside-down
// insert shows it at the top instead), the femoral condyles' distal sagittal arcs (a circle
// fitted to a 3 mm wide sagittal slice through each condyle's lowest point, its lowest 6 mm),
// and the anterior flange (the femoral component's highest point lies anterior).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/model.h"
#include "models/build_model.h"
#include "models/config.h"

namespace kneesim::models {

// a circle fitted to a condyle's distal sagittal profile, in F [mm]
struct CondyleArc {
  bool found = false;      // enough points for a fit
  double x_mm = 0.0;       // centre, anterior-posterior, F [mm]
  double y_mm = 0.0;       // centre, superior-inferior, F [mm]
  double z_mm = 0.0;       // the slice's z (the condyle's lowest point), F [mm]
  double radius_mm = 0.0;  // [mm]
  double rms_mm = 0.0;     // RMS distance of the profile points from the circle [mm]
  int points = 0;          // profile points fitted [-]
};

struct ImplantFacts {
  Eigen::Vector3d femur_min_mm, femur_max_mm;    // bounding box, rotated mesh frame [mm]
  Eigen::Vector3d insert_min_mm, insert_max_mm;  // bounding box, rotated mesh frame [mm]
  int femur_triangles = 0, insert_triangles = 0;
  bool femur_closed = false, insert_closed = false;
  double femur_volume_mm3 = 0.0;   // enclosed volume, 0 when open [mm^3]
  double insert_volume_mm3 = 0.0;  // enclosed volume, 0 when open [mm^3]
  int articular_elements = 0;
  double articular_area_mm2 = 0.0;          // the insert's articular faces [mm^2]
  double medial_area_mm2 = 0.0;             // of which z < 0 (medial) [mm^2]
  double lateral_area_mm2 = 0.0;            // of which z >= 0 (lateral) [mm^2]
  Eigen::Vector3d articular_min_mm, articular_max_mm;  // articular faces' box, T [mm]
  CondyleArc arcs[2];                       // medial (z < 0), lateral (z > 0) condyle
  Eigen::Vector3d suggested_origin_mm;      // the arcs' mean centre, rotated mesh frame [mm]
  double flange_x_mm = 0.0;  // x of the femur's highest point from its box centre, F [mm]
  // gaps between the femur and the insert's articular surface under it [mm]; negative is an
  // overlap; NaN where the femur is over no articular face
  double files_gap_mm = 0.0;           // as placed in the files (rotated mesh frame)
  double start_gap_medial_mm = 0.0;    // as the run starts (before the first load)
  double start_gap_lateral_mm = 0.0;
  std::vector<std::string> warnings;   // one sentence each: frame, axis, base plane
};

// refuses (InputError, one sentence naming the file, the key, the value and what is allowed)
// the same mesh given twice, an inside-out insert or femur, an upside-down insert, a femur
// without distal condylar arcs (upside down), a femur whose condyles are not over the insert,
// and a flexion axis outside the femoral component. Meshes in F and T as make_implant builds
// them. A generic implant passes.
void check_implant(const Config& config, const Implant& implant);

// the facts `kneesim implant check` prints, with warnings; `insert` is the model's articular
// surface (make_insert_surface)
ImplantFacts describe_implant(const Config& config, const Implant& implant,
                              const engine::InsertSurface& insert);

// the frame and flexion-axis part of describe_implant() (flange, condylar arcs, suggested
// origin, and the warnings "frame: ..." and "flexion axis: ..."), cheap enough for every run
ImplantFacts describe_frame(const Config& config, const Implant& implant);

// prints describe_frame()'s warnings to stderr ("warning: CONFIG: frame: ..."), each once per
// process (a study builds many models of one config); every command that builds a mesh
// implant calls it, so that a run with anterior and posterior reversed does not end silently
void warn_about_frame(const Config& config, const Implant& implant);

}  // namespace kneesim::models
