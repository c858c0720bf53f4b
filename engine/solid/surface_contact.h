// Contact of the deformable solid's surface nodes against a rigid body given by its signed
// distance (the femoral component's field, the block-on-ring ring, a test indenter)
// (physics.md section 4, "deformable insert").
//
// Node-to-surface penalty: a surface node at signed distance phi < 0 inside the rigid body
// feels p = k_n (-phi) / A_n along the body's outward normal, with its tributary area A_n (a
// quarter of each surface quad it touches), and the same regularized Coulomb friction as the
// rigid insert, t = -mu p v_s / sqrt(|v_s|^2 + eps^2), v_s the tangential velocity of the node
// relative to the body surface.
//
// Penalty stiffness: k_n = (lambda + 2 mu) A_n / L_n with L_n the height of the element under
// the node (its characteristic length). In one dimension a surface node carries half an
// element's mass and one element spring (lambda + 2 mu) A / L, so its own frequency with the
// penalty added, 2 (k_e + k_n) / m, stays at or below the interior limit 4 k_e / m exactly
// when k_n <= k_e: this choice does not lower the stable step. The penalty layer is as
// compliant as one surface element under uniaxial strain, so the mesh must resolve the
// contact (elements well below the contact half-width) for it to be accurate.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "engine/solid/solid.h"

namespace kneesim::engine::solid {

struct SurfaceContact {
  std::vector<int> nodes;            // surface nodes that can touch, ascending
  std::vector<int> index_of_node;    // position in `nodes` of each solid node, -1 if absent
  std::vector<double> area;          // tributary area [m^2], per surface node
  std::vector<double> stiffness;     // penalty k_n [N/m], per surface node
  double friction = 0.0;             // Coulomb coefficient [-]
  double slip_regularization = 1e-3; // eps [m/s]
  int size() const { return static_cast<int>(nodes.size()); }
};

// what the rigid body reports at a point: signed distance (negative inside) [m], outward unit
// normal, and the body's velocity there [m/s]
struct RigidSample {
  double phi = INFINITY;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

// per-step results of the surface contact, per surface node
struct SurfaceContactData {
  std::vector<double> pressure;            // [Pa]
  std::vector<Eigen::Vector3d> force;      // normal force on the node [N]
  std::vector<Eigen::Vector3d> friction_force;  // friction on the node, where the owner
                                                // computes it as a force (knee step) [N]
  std::vector<Eigen::Vector3d> body_velocity;   // of the rigid body at the node [m/s]
  std::vector<Eigen::Vector3d> position;   // of the node where its contact was evaluated [m]
  // the knee's sleep schedule of out-of-contact nodes (engine/insert_solid.cpp): the node is
  // sampled again once (wake_at - motion) sleep_scale <= |x - checked_position|. `sleep` off
  // samples every node every step (the test that the schedule changes no result)
  bool sleep = true;
  std::vector<double> wake_at;             // motion value [m]
  std::vector<double> sleep_scale;         // >= 1 [-]
  std::vector<Eigen::Vector3d> checked_position;  // x when last sampled [m]
  std::vector<double> slip_speed;          // tangential slip speed [m/s]
  Eigen::Vector3d total_force = Eigen::Vector3d::Zero();  // normal forces on the solid [N]
  double peak_pressure = 0.0;              // [Pa]
  double area = 0.0;                       // tributary area of the nodes in contact [m^2]
  int nodes_in_contact = 0;
};

// the surface of the given quads (node ids) with tributary areas and penalty stiffnesses from
// the reference configuration; `face_element` is the element under each quad
SurfaceContact make_surface_contact(const SolidModel& model,
                                    const std::vector<std::array<int, 4>>& faces,
                                    const std::vector<int>& face_element, double friction,
                                    double slip_regularization);

SurfaceContactData make_surface_contact_data(const SurfaceContact& contact);

// penalty pressure and regularized friction of one node (a pure kernel). Returns the normal
// force on the node [N]; the friction is a viscosity c = mu f_n / sqrt(|v_s|^2 + eps^2)
// [N s/m] on the tangential velocity relative to the body, which step_solid integrates
// implicitly (as the rigid path does: near stick its slope mu f_n / eps is far too stiff for
// an explicit damper on a light surface node).
inline Eigen::Vector3d calc_node_contact_force(const RigidSample& s, const Eigen::Vector3d& v,
                                               double k, double area, double mu, double eps,
                                               double& pressure, double& slip_speed,
                                               double& viscosity) {
  pressure = 0.0;
  slip_speed = 0.0;
  viscosity = 0.0;
  if (!(s.phi < 0.0)) return Eigen::Vector3d::Zero();
  const double fn = -k * s.phi;
  pressure = fn / area;
  const Eigen::Vector3d rel = v - s.velocity;
  slip_speed = (rel - rel.dot(s.normal) * s.normal).norm();
  viscosity = mu * fn / std::sqrt(slip_speed * slip_speed + eps * eps);
  return fn * s.normal;
}

// adds the normal contact forces of a rigid body to data.external_force and sets the friction
// viscosity of the surface nodes (data.friction_*): `sample(p)` gives the RigidSample at a
// node position p (any callable; a template so that it inlines). Deterministic: every node is
// independent, the totals are summed in node order.
template <class Sampler>
void apply_surface_contact(const SolidModel& model, const SurfaceContact& contact,
                           const SolidState& state, SolidData& data, SurfaceContactData& out,
                           const Sampler& sample) {
  const int n = contact.size();
#pragma omp parallel for num_threads(model.threads) schedule(static)
  for (int i = 0; i < n; ++i) {
    const int node = contact.nodes[i];
    const RigidSample s = sample(state.position[node]);
    double viscosity = 0.0;
    out.force[i] = calc_node_contact_force(s, state.velocity[node], contact.stiffness[i],
                                           contact.area[i], contact.friction,
                                           contact.slip_regularization, out.pressure[i],
                                           out.slip_speed[i], viscosity);
    data.friction_viscosity[node] = viscosity;
    data.friction_normal[node] = s.normal;
    data.friction_body_velocity[node] = s.velocity;
  }
  out.total_force.setZero();
  out.peak_pressure = 0.0;
  out.area = 0.0;
  out.nodes_in_contact = 0;
  for (int i = 0; i < n; ++i) {
    data.external_force[contact.nodes[i]] += out.force[i];
    if (out.pressure[i] <= 0.0) continue;
    out.total_force += out.force[i];
    out.peak_pressure = std::max(out.peak_pressure, out.pressure[i]);
    out.area += contact.area[i];
    ++out.nodes_in_contact;
  }
}

}  // namespace kneesim::engine::solid
