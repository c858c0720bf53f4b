// One explicit step of the deformable solid: element stresses and internal forces (one
// OpenMP loop over batches of kBatchLanes elements, hex8_batch.h, into batch-local force
// buffers), the gather to the nodes in the fixed CSR order (a second loop over nodes), and
// the central-difference update of the nodes with their lumped masses. The result is
// bit-identical for any thread count: no element writes to a node, every nodal sum is taken
// in ascending element order and every total in batch order. No allocation.
//
// calc_hex8_response is the one-element form of the same element (hex8.h's FB vectors, Eigen
// algebra): the reference the batched kernel is tested against, not used in the step.
#pragma once

#include "engine/solid/solid.h"

namespace kneesim::engine::solid {

// the response of one element at current node positions x: internal nodal forces, stress,
// the plastic state it leaves, energies (a pure kernel)
struct Hex8Response {
  std::array<Eigen::Vector3d, kHexNodes> force;  // internal force on each node [N]
  StressUpdate update;            // S, plastic state after the update
  double det_F = 1.0;             // volume ratio [-]
  double strain_energy = 0.0;     // elastic [J]
  double hourglass_energy = 0.0;  // [J]
};
void calc_hex8_response(const Hex8Reference& ref, const SolidMaterial& material,
                        const HexPoints& x, const Sym6& plastic_strain, double alpha,
                        Hex8Response& out);

// element and nodal internal forces, stresses and energies at state.position; flags the
// lowest-numbered element with det F <= 0 (data.status, data.inverted_element)
void calc_solid_forces(const SolidModel& model, const SolidState& state, SolidData& data);

// advances the solid by dt: forces at x(n), v(n+1/2) = v(n-1/2) + dt (f_ext - f_int) / m
// (with mass-proportional damping, implicit in its own term, and the contact friction
// viscosity of data.friction_*, implicit on the tangential velocity), constrained DOFs at the
// prescribed velocity, x(n+1) = x(n) + dt v(n+1/2), and the plastic state committed. Returns
// kInverted without moving anything when an element has inverted.
SolidStatus step_solid(const SolidModel& model, SolidState& state, SolidData& data, double dt);

// the update half of step_solid: the central-difference update of the nodes with the forces
// already in data (calc_solid_forces at the current positions, external and friction terms),
// and the plastic state committed. For owners that need the internal forces before the update
// (the knee step takes the base reaction from them).
void update_solid_nodes(const SolidModel& model, SolidState& state, SolidData& data, double dt);

}  // namespace kneesim::engine::solid
