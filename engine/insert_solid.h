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
// Loads on the carriages: the femur carries the opposite of every node's contact force
// (normal, friction and the rig's contact damper) at the node, and the tibial carriage exactly
// those forces, at the same points: to the carriages the insert is massless, as it is in this
// frame, where the tray's motion puts no inertial force on it. The reaction of the base nodes
// (-f_int, the force the solid exerts on the tray) is not what the tray carries: it differs
// from the contact forces by the insert's inertia and damping, and coupling the tray to the
// insert's mass in one direction only is not energy-consistent. For a tray of mass M on the
// insert's shear stiffness k, the insert's surface (mass m) held by friction c to the femur:
// with the base reaction, M X'' = k u and m u'' = -k u - c (u' + X') (the m X'' of an
// inertial frame is missing), so the spring's power k u X' on the tray is returned by no term
// of the insert's equation; with the contact forces, M X'' = -c (u' + X') and the exchange
// sums to -c (u' + X')^2 <= 0. For the physical 35 g insert the difference is immeasurable;
// mass-scaled to the default 20 us step the insert weighs 27 kg (2 mm elements) against the
// tray's 2 kg, and the base reaction drove a friction-excited oscillation of the tibial
// carriage's ML and VV DOFs at about 455 Hz (75 mm/s and 36 um RMS in ML) that added
// 37 % to the sliding work and the wear volume of the default run (CHANGELOG.md, the
// tray-coupling fix; tools/bench/wear_sliding.cpp measures it).
#pragma once

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

// internal forces of the solid at the current nodes (flags an inverted element in
// data.insert_solid), the contact forces of its top nodes (data.insert_contact, the nodes'
// external forces), the contact summary in data.contact, and the generalized forces of both
// carriages added into data.generalized. With `advance` (state.insert_solid itself, from
// step()) each node also takes its central-difference step in the same loop, right after its
// contact, unless an element inverted (then nothing moves); the carriages' update does not
// depend on it. Allocation-free; bit-identical for any thread count.
void calc_insert_solid_forces(const Model& model, const State& state, Data& data,
                              solid::SolidState* advance = nullptr);

}  // namespace kneesim::engine
