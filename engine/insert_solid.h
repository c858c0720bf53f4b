// The deformable insert in the rig's step (physics.md sections 4 and 5, issue 11): the hex8
// solid of engine/solid carried by the tibial carriage.
//
// Frame: the solid is integrated in the insert frame T, its base nodes fixed there (tied to
// the tray). The tray's own acceleration then puts no inertial force on the insert. Physically
// that force is m_insert a_tray, about 0.05 N for a 25 g insert at the rig's few m/s^2, and it
// is neglected; with mass scaling (engine/solid/solid_build.h) the scaled mass would turn it
// into an artefact of hundreds of newtons on the tibial carriage, which this frame avoids.
//
// Contact: each top-surface node is carried into the femoral frame F and sampled in the
// femoral signed distance field; the penalty and the regularized Coulomb friction are those of
// engine/solid/surface_contact.h, with the femoral surface's velocity relative to T. The
// friction viscosity near stick (mu f_n / eps on a node of a few grams) is far too stiff for
// an explicit damper, so the friction force is computed here as the implicit update would
// apply it: with the node's predicted velocity v* (internal, normal and damping forces) the
// friction changes the tangential velocity relative to the femur by -a/(1+a) of it,
// a = dt c / m. That force is applied to the node as an external force and its opposite to the
// femur, so the exchange conserves momentum exactly.
//
// Loads on the carriages: the femur carries the opposite of every node's contact force (normal
// and friction) at the node; the tibial carriage carries the reaction of the base nodes, the
// force the solid exerts on the tray, -f_int at each base node. In a quasi-static run the two
// balance; their difference is the insert's own inertia and damping.
#pragma once

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

// internal forces of the solid at the current nodes (flags an inverted element in
// data.insert_solid), the contact forces of its top nodes (data.insert_contact, the nodes'
// external forces), the contact summary in data.contact, and the generalized forces of both
// carriages added into data.generalized. Allocation-free; bit-identical for any thread count.
void calc_insert_solid_forces(const Model& model, const State& state, Data& data);

}  // namespace kneesim::engine
