// One explicit step of the deformable solid in two loops, each cut into the model's ranges
// (solid.h) and run by the data's WorkTeam (engine/work_team.h), one task per range:
//
// 1. the element loop: every batch of kBatchLanes elements (hex8_batch.h) evaluated and its
//    nodal forces added straight into the nodes (a node shared with another range into its
//    slots instead); each batch's totals (energies, plastic work, the lowest inverted element)
//    and the plastic state it would leave;
// 2. the node loop: each shared node's slots summed in ascending element order, then whatever
//    the owner does per node (the central-difference update here; the knee adds the contact
//    of its top nodes, engine/insert_solid.cpp), the kinetic energy summed per kNodeBlock nodes,
//    and the plastic state committed where it changed.
//
// The result is bit-identical for any thread and range count and for any assignment of tasks
// to threads: no element writes where another range writes, every nodal force is the sum over
// its elements in ascending element order from 0.0, and every total is summed in a fixed order
// (batches in batch order, node blocks in block order). No allocation.
//
// calc_hex8_response is the one-element form of the same element (hex8.h's FB vectors, Eigen
// algebra): the reference the batched kernel is tested against, not used in the step.
#pragma once

#include <algorithm>

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

// element and nodal internal forces, stresses and energies at state.position, with every
// per-element field of SolidData; flags the lowest-numbered element with det F <= 0
// (data.status, data.inverted_element)
void calc_solid_forces(const SolidModel& model, const SolidState& state, SolidData& data);

// advances the solid by dt: forces at x(n), v(n+1/2) = v(n-1/2) + dt (f_ext - f_int) / m
// (with mass-proportional damping, implicit in its own term, and the contact friction
// viscosity of data.friction_*, implicit on the tangential velocity), constrained DOFs at the
// prescribed velocity, x(n+1) = x(n) + dt v(n+1/2), and the plastic state committed. Returns
// kInverted without moving anything when an element has inverted.
SolidStatus step_solid(const SolidModel& model, SolidState& state, SolidData& data, double dt);

// --- the two loops, for owners that add work per node (engine/insert_solid.cpp) ---

// loop 1: internal forces at state.position (shared nodes' still in their slots), von Mises,
// the totals and data.status; the per-element stress, energies and det F only if
// element_fields
void run_element_loop(const SolidModel& model, const SolidState& state, SolidData& data,
                      bool element_fields);

// the total internal force of node n once loop 1 has run (a shared node's slots summed)
inline void finish_node_force(const SolidModel& model, SolidData& data, int n) {
  const int k0 = model.slot_start[n], k1 = model.slot_start[n + 1];
  if (k0 == k1) return;
  double fx = 0.0, fy = 0.0, fz = 0.0;
  const double* f = data.slot_force.data() + 3 * static_cast<long>(k0);
  for (int k = k0; k < k1; ++k, f += 3) {
    fx += f[0];
    fy += f[1];
    fz += f[2];
  }
  data.internal_force[n] = Eigen::Vector4d(fx, fy, fz, 0.0);
}

// the central-difference update of node n with the forces in data; returns its kinetic energy
// at t(n) from the mean of the half-step velocities [J]. c = dt damping_alpha / 2. An owner
// that knows the node has no external force (kExternal false: data.external_force[n] is zero)
// or no node has a friction viscosity (kFriction false) skips reading them: the same bits
// (0.0 - f is what f_ext - f gives for f_ext = 0.0), fewer bytes per node.
// advance_node_inlined is the body, always inlined (step_solid's node loop, see there);
// advance_node leaves the choice to the compiler (the knee's node loop, whose gait cycle ran
// 17.1 -> 18.4 s on one thread with the body forced inline)
template <bool kExternal = true, bool kFriction = true>
[[gnu::always_inline]] inline double advance_node_inlined(const SolidModel& model,
                                                          SolidState& state,
                                                          const SolidData& data, int n,
                                                          double dt, double c) {
  // component by component in scalars (the Eigen form wrote v to the stack in halves and
  // read it back whole around the constraint: a store-forwarding stall per fixed node); the
  // same operations in the same order, so the same bits
  const double* v_old = state.velocity[n].data();
  const double* f_int = data.internal_force[n].data();
  const double s = dt * model.inverse_mass[n];
  double f[3];
  for (int i = 0; i < 3; ++i) f[i] = (kExternal ? data.external_force[n][i] : 0.0) - f_int[i];
  double v[3];
  for (int i = 0; i < 3; ++i) v[i] = ((1.0 - c) * v_old[i] + s * f[i]) / (1.0 + c);
  if (kFriction && data.friction_viscosity[n] > 0.0) {
    // friction implicit: (I + a P)(v_new - v_body) = v - v_body with P the tangential
    // projector, solved by (I + a P)^-1 = I - a / (1 + a) P
    const double a = dt * model.inverse_mass[n] * data.friction_viscosity[n];
    const Eigen::Vector3d& nb = data.friction_normal[n];
    const Eigen::Vector3d rel = Eigen::Vector3d(v[0], v[1], v[2]) - data.friction_body_velocity[n];
    const Eigen::Vector3d dv = (a / (1.0 + a)) * (rel - rel.dot(nb) * nb);
    for (int i = 0; i < 3; ++i) v[i] -= dv[i];
  }
  if (const uint8_t fixed = model.constraint[n]) {
    for (int i = 0; i < 3; ++i) {
      if (fixed & (1u << i)) v[i] = data.prescribed_velocity[n][i];
    }
  }
  double* x = state.position[n].data();
  double* v_new = state.velocity[n].data();
  const double w0 = v[0] + v_old[0], w1 = v[1] + v_old[1], w2 = v[2] + v_old[2];
  for (int i = 0; i < 3; ++i) {
    v_new[i] = v[i];
    x[i] += dt * v[i];
  }
  return 0.125 * model.nodal_mass[n] * (w0 * w0 + w1 * w1 + w2 * w2);
}
template <bool kExternal = true, bool kFriction = true>
inline double advance_node(const SolidModel& model, SolidState& state, const SolidData& data,
                           int n, double dt, double c) {
  return advance_node_inlined<kExternal, kFriction>(model, state, data, n, dt, c);
}

// commits the plastic state loop 1 computed for the batches [b0, b1)
void commit_plastic_state(const SolidModel& model, SolidState& state, const SolidData& data,
                          int b0, int b1);

// runs task(r) for every range r on the data's team (or inline with one range)
template <class Task>
void for_each_range(const SolidModel& model, SolidData& data, Task& task) {
  if (WorkTeam* team = data.team.get(); team && model.ranges > 1) {
    team->run(model.ranges, task);
  } else {
    for (int r = 0; r < model.ranges; ++r) task(r);
  }
}

// loop 2: per range, for each node in order finish_node_force and then node_work(n), which
// returns the node's kinetic energy (advancing) or 0; with `advance` (state not null) the
// kinetic energy total goes to data.kinetic_energy and the plastic state is committed
template <class NodeWork>
void run_node_loop(const SolidModel& model, SolidState* advance, SolidData& data,
                   NodeWork& node_work) {
  auto task = [&](int r) {
    const int n0 = model.range_node[r], n1 = model.range_node[r + 1];
    for (int block = n0; block < n1; block += kNodeBlock) {
      const int end = std::min(block + kNodeBlock, n1);
      double kinetic = 0.0;
      for (int n = block; n < end; ++n) {
        finish_node_force(model, data, n);
        kinetic += node_work(n);
      }
      data.block_kinetic_energy[block / kNodeBlock] = kinetic;
    }
    if (advance) {
      commit_plastic_state(model, *advance, data, model.range_batch[r], model.range_batch[r + 1]);
    }
  };
  for_each_range(model, data, task);
  if (!advance) return;
  double kinetic = 0.0;
  for (double k : data.block_kinetic_energy) kinetic += k;
  data.kinetic_energy = kinetic;
}

}  // namespace kneesim::engine::solid
