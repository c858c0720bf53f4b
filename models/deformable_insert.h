// The deformable insert of a knee Model (config `insert = "deformable"`, issue 11): the hex8
// solid meshed from the insert's top surface (models/hex_mesh.h), its base nodes tied to the
// tibial carriage, its top nodes in contact with the femoral distance field, and the time
// step it sets (engine/insert_solid.h for the step itself).
//
// Time stepping: one global step for the carriages and the solid, the solid's stable step
// raised to deformable.dt_us by mass scaling. Subcycling the solid inside the rigid step was
// rejected by measurement: the rigid part of a step (kinematics, loads, restraint, carriage
// update) costs under 1 % of a step of a 10 000-element insert (docs/deformable.md), so running
// the carriages at the solid's step costs nothing measurable, while a subcycled femur would
// see the contact forces averaged over the substeps of a pose it holds fixed.
#pragma once

#include <vector>

#include "engine/state.h"
#include "models/build_model.h"

namespace kneesim::models {

// the layers through a column of `height` [m] whose top layer is `top` [m] thick: the fewest
// layers that reach the height when each is `growth` times the one above, with the growth then
// lowered (a geometric series still) so that the top layer is exactly `top`: {layers, grading}
// for InsertMeshOptions (grading = top / bottom thickness); {1, 1} when top >= height
std::pair<int, double> find_graded_layers(double height, double top, double growth);

// the solid material of the config's insert material (E, nu, density, yield from [material];
// hardening and model from [deformable])
engine::solid::SolidMaterial make_insert_solid_material(const Config& config);

// builds the deformable insert into built.model (mesh, contact, base nodes), sets the time step
// and reports the mesh it made (built.deformable_mesh). The mesh, from the [deformable] keys:
//  - refine = "contact": the footprint grid is refined where a rigid cycle's loaded contact
//    occurs (plus refine_margin_mm) and grows by 1.3 per element to outer_element_size_mm
//    away from it (models/contact_footprint.h); "none": one spacing everywhere;
//  - the refined spacing is element_size_mm, or with elements_across_contact = n > 0 the
//    narrowest patch width of that rigid cycle over n per direction (AP and ML apart: a line
//    contact is refined across the line), within [min_element_size_mm, element_size_mm];
//  - layers = 0: the top layer as thick as the finer refined spacing, each layer below 1.5
//    times thicker down to the base at the contact zone's median thickness; layers > 0: that
//    many, graded by `grading`.
// to the smaller of the rigid one and the solid's, and lifts the femur to first touch (the
// rigid law's static overlap removed); throws InputError for bad input (mesh options, an
// element inverted at the start, a material out of range)
void attach_deformable_insert(const Config& config, BuiltModel& built);

// Wear of the deformable insert (issue 11 item 4; wear/worn_insert.h drives it). The geometry
// that wears is the solid's reference configuration: the top nodes recede along the surface
// normal and each column of the structured mesh (its base node, the interior nodes, its top
// node: consecutive node ids, models/hex_mesh.h) is re-graded between its fixed base node and
// its new top node with the pristine layer fractions, so the interior follows the surface and
// the grading towards the surface is kept. Rejected: moving the top nodes only (the top layer
// alone would thin, inverting first) and a Laplacian smoothing of the interior (iterative, and
// the columns give the exact answer).

// unit normals of the top-surface contact nodes (model.insert_contact order) at the given
// reference node positions, area-weighted over the top quads around each node (+y up)
std::vector<Eigen::Vector3d> calc_top_node_normals(const engine::Model& model,
                                                   const std::vector<Eigen::Vector3d>& nodes);

// the nodes of `nodes` after each top node i (model.insert_contact.nodes[i]) moved by
// depth[i] [m] along -normal[i], every column re-graded with the layer fractions of the
// pristine model's column
std::vector<Eigen::Vector3d> recede_insert_columns(const engine::Model& pristine,
                                                   const std::vector<Eigen::Vector3d>& nodes,
                                                   const std::vector<Eigen::Vector3d>& normal,
                                                   const std::vector<double>& depth);

// elements inverted or collapsed at the given nodes: smallest corner Jacobian at or below
// 1 % of the same element's in the pristine model (the rigid path's 1 % face-area rule)
int count_collapsed_elements(const engine::Model& pristine, const std::vector<Eigen::Vector3d>& nodes);

// volume of the insert's hex mesh at the given node positions [m^3]
double calc_hex_volume(const engine::Model& model, const std::vector<Eigen::Vector3d>& nodes);

// `model`'s deformable insert rebuilt on the worn reference nodes: element geometry, lumped mass
// (mass-scaled to the pristine target step), top-node areas and penalty stiffnesses; material,
// constraints, friction and the rig are the pristine model's; the time step is shortened only
// if the worn solid's limit requires it. `state` (if not null) moves onto the new reference
// with its displacements, velocities and plastic state (x' = X' + (x - X)).
void apply_worn_deformable_insert(const engine::Model& pristine, double dt_safety,
                                  const std::vector<Eigen::Vector3d>& worn_nodes,
                                  engine::Model& model, engine::State* state);

}  // namespace kneesim::models
