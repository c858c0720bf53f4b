// Config -> engine::Model: the implant meshes (generic or imported), the insert's articular
// elements with their layer thickness, the femoral distance field, the gait waveforms mapped
// onto carriage DOFs, the rig preset, the restraint, and the stable time step (measured, see
// engine/stable_step.h). Every conversion from I/O units to SI happens here.
#pragma once

#include <string>
#include <vector>

#include "engine/model.h"
#include "engine/stable_step.h"
#include "models/config.h"
#include "models/generic_tkr.h"
#include "models/hex_mesh.h"
#include "models/tri_mesh.h"

namespace kneesim::models {

struct Implant {
  TriMesh femur;                        // F frame [m]
  TriMesh insert;                       // T frame [m], closed when required
  std::vector<int> articular_to_insert; // insert triangle of each articular element
  std::vector<int> articular_vertex_to_insert;  // insert vertex of each articular vertex
  double insert_volume = 0.0;           // enclosed volume [m^3] (0 for an open mesh)
};

// the deformable insert's mesh as attach_deformable_insert made it
struct DeformableMeshReport {
  double element_size_x = 0.0, element_size_z = 0.0;  // refined spacing [m]
  int layers = 0;
  double grading = 0.0;              // top / bottom layer thickness [-]
  int elements = 0;
  double patch_width_x = 0.0, patch_width_z = 0.0;  // narrowest rigid patches (10th pct) [m]
  double layer_thickness = 0.0;      // median thickness under the rigid cycle's contact [m]
};

struct BuiltModel {
  engine::Model model;
  Implant implant;
  engine::StableStepReport stable_step;
  MaterialConfig material;
  double build_seconds = 0.0;           // wall time of the build [s]
  double sdf_seconds = 0.0;             // of which the distance field [s]
  double peak_load = 0.0;               // peak axial load of the gait [N]
  double damping_ratio = 0.0;           // contact damping ratio [-]
  double dt_safety = 0.8;               // fraction of the stability limit [-]
  std::string geometry_key;             // the config keys that shaped implant, elements, fields
  DeformableMeshReport deformable_mesh;  // the deformable insert's mesh as made (if any)
  // deformable insert with refine = "contact": the refined zone (T frame) and, per top-surface
  // contact node (model.insert_contact order), 1 when the node lies in it; empty otherwise
  std::vector<Interval> refined_x, refined_z;
  std::vector<unsigned char> refined_contact_node;
};

// builds everything; throws InputError for bad input (files named). With `same_geometry` (a
// model built from a config whose implant, mesh and distance-field keys are the same, e.g. the
// nominal model of a study whose trial varies the rig), its implant, articular elements and
// femoral distance fields are copied instead of rebuilt: the result is identical to a full
// build. A different geometry key falls back to the full build.
BuiltModel build_model(const Config& config, const BuiltModel* same_geometry = nullptr);

// the implant's meshes as build_model loads them (femur in F, insert in T with its base at
// y = 0), checked (models/implant_check.h); throws InputError naming the file
Implant load_implant(const Config& config);

// the insert's articular elements from a mesh in T: faces facing up more than min_normal_y
engine::InsertSurface make_insert_surface(const TriMesh& insert, double base_y,
                                          double min_normal_y, std::vector<int>* to_insert,
                                          std::vector<int>* vertex_to_insert);

GenericTkrParams generic_params(const Config& config);

// the model with its insert replaced by a worn copy of the same mesh (same triangles, moved
// vertices): the articular elements, their centroids, normals, areas and layer thickness are
// recomputed; the femoral field, the rig and the time step are kept. A pure function of
// (pristine, worn), so a resumed wear run rebuilds exactly the model it left.
engine::InsertSurface make_worn_insert_surface(const BuiltModel& pristine, const TriMesh& worn);



}  // namespace kneesim::models
