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

#include "models/build_model.h"

namespace kneesim::models {

// the solid material of the config's insert material (E, nu, density, yield from [material];
// hardening and model from [deformable])
engine::solid::SolidMaterial make_insert_solid_material(const Config& config);

// builds the deformable insert into built.model (mesh, contact, base nodes), sets the time step
// to the smaller of the rigid one and the solid's, and lifts the femur to first touch (the
// rigid law's static overlap removed); throws InputError for bad input (mesh options, an
// element inverted at the start, a material out of range)
void attach_deformable_insert(const Config& config, BuiltModel& built);

}  // namespace kneesim::models
