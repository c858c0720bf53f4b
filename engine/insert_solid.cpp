#include "engine/insert_solid.h"

#include <algorithm>
#include <cmath>

#include "engine/contact.h"
#include "engine/contact_law.h"
#include "engine/kinematics.h"
#include "engine/rig_coupling.h"
#include "engine/solid/solid_step.h"

namespace kneesim::engine {
namespace {

// force and moment about the world origin, added into a carriage's generalized forces
void apply_wrench(const State& state, Data& data, int c, const Eigen::Vector3d& force,
                  const Eigen::Vector3d& moment_O) {
  const Eigen::Vector3d torque = moment_O - state.carriages[c].pivot_W.cross(force);
  auto& Q = data.generalized[c];
  for (int i = 0; i < 3; ++i) {
    Q[i] += force[i];
    Q[3 + i] += torque.dot(data.axes[c][i]);
  }
}

// dp/dd of the rigid insert's elastic-foundation law at pressure p over a layer h [Pa/m]:
// the stiffness the rigid path's contact damper would see there
double ef_stiffness_at_pressure(const ContactModel& c, double p, double h) {
  if (c.exponent != 1.0) {
    // p = K g^n (or the linear run-in below kExponentLinearStrain): g from p, then dp/dg dg/dd
    const double K = c.foundation_modulus, n = c.exponent;
    const double p_run_in = K * std::pow(kExponentLinearStrain, n);
    const double g = (n < 1.0 && p < p_run_in) ? p / (K * std::pow(kExponentLinearStrain, n - 1.0))
                                               : std::pow(std::max(p, 0.0) / K, 1.0 / n);
    const double g_rate = c.law == ContactLaw::kLinear ? 1.0 / h : std::exp(std::min(g, 4.6)) / h;
    return ef_pressure_slope(K, n, g) * g_rate;
  }
  switch (c.law) {
    case ContactLaw::kLinear:
      return c.foundation_modulus / h;
    case ContactLaw::kNonlinear:  // p = -K ln(1 - d/h): dp/dd = K / (h - d) = (K/h) e^(p/K)
      return c.foundation_modulus / h * std::exp(std::min(p / c.foundation_modulus, 4.6));
  }
  return 0.0;
}

// fraction of a node's sampled distance it may sleep for: the trilinear field of a distance
// function is 1-Lipschitz per axis, so at most sqrt(3) in any direction (not the rigid path's
// 0.7, which allows for it only along the axes: a node that sleeps too long would change the
// result, an element of the rigid path only its schedule)
constexpr double kNodeSleepLipschitz = 0.57;

}  // namespace

void calc_insert_solid_forces(const Model& model, const State& state, Data& data,
                              solid::SolidState* advance) {
  const solid::SolidModel& solid = model.insert_solid;
  const solid::SolidState& nodes = state.insert_solid;
  solid::SolidData& sd = data.insert_solid;
  const solid::SurfaceContact& contact = model.insert_contact;
  solid::SurfaceContactData& out = data.insert_contact;
  // internal forces at x(n): the contact's friction needs them (predicted velocity)
  solid::run_element_loop(solid, nodes, sd, advance == nullptr);
  const bool move = advance && sd.status == solid::SolidStatus::kOk;

  const Eigen::Isometry3d X_WT = data.X_WT;
  const Eigen::Isometry3d X_FT = data.X_WF.inverse() * X_WT;
  const Eigen::Matrix3d R_TW = X_WT.linear().transpose();
  const Eigen::Matrix3d R_FT = X_FT.linear();
  const double dt = model.dt;
  const double c_damp = 0.5 * dt * solid.damping_alpha;
  std::vector<Eigen::Vector3d>& femur_velocity_T = out.body_velocity;
  // the sleep schedule of the top nodes (file comment): the relative motion of the femur
  // since the last step, measured as the rigid path's
  if (!data.schedule_valid || model.femur_radius <= 0.0 || !out.sleep) {
    std::fill(out.wake_at.begin(), out.wake_at.end(), data.motion);
    data.X_FT_prev = X_FT;
    data.schedule_valid = true;
  } else {
    accumulate_contact_motion(model, data);
  }
  const double motion = data.motion, radius = model.femur_radius;
  const Eigen::Vector3d o_T = X_FT.inverse().translation();  // the femoral origin in T
  // the contact of a top node at x(n), before the node moves; each node writes only its own
  // slots
  const auto contact_node = [&](int i, int node) {
    const Eigen::Vector3d& x_T = nodes.position[node];
    out.position[i] = x_T;
    // asleep: out of contact when last sampled, and neither the femur's motion since then nor
    // the node's own can have closed the gap (its outputs are still the zeros of that sample)
    const double allowance = (out.wake_at[i] - motion) * out.sleep_scale[i];
    if (allowance > 0.0 && (x_T - out.checked_position[i]).squaredNorm() < allowance * allowance) {
      return;
    }
    Eigen::Vector3d gradient_F;
    const double phi = model.femur_sdf.sample(X_FT * x_T, &gradient_F);
    if (!(phi < 0.0)) {
      out.pressure[i] = 0.0;
      out.slip_speed[i] = 0.0;
      out.force[i].setZero();
      out.friction_force[i].setZero();
      sd.external_force[node].setZero();
      if (radius > 0.0) {
        // a point r from the femoral origin moves up to max(1, r / R) times `motion`
        const double r = (x_T - o_T).norm() + phi;
        const double scale = r > radius ? r / radius : 1.0;
        out.sleep_scale[i] = scale;
        out.wake_at[i] = motion + kNodeSleepLipschitz * std::max(0.0, phi - 1e-9) / scale;
        out.checked_position[i] = x_T;
      }
      return;
    }
    out.wake_at[i] = motion;  // in contact: sampled every step
    const double g = gradient_F.norm();
    const Eigen::Vector3d normal_T =
        g > 0.0 ? Eigen::Vector3d(R_FT.transpose() * gradient_F / g) : Eigen::Vector3d::UnitY();
    // the femoral surface's velocity relative to the insert frame at the node
    const Eigen::Vector3d p_W = X_WT * x_T;
    const Eigen::Vector3d body_T = R_TW * (find_point_velocity(state, data, 0, p_W) -
                                           find_point_velocity(state, data, 1, p_W));
    femur_velocity_T[i] = body_T;
    const solid::RigidSample sample{phi, normal_T, body_T};
    double viscosity = 0.0;
    const Eigen::Vector3d f_normal = solid::calc_node_contact_force(
        sample, nodes.velocity[node], contact.stiffness[i], contact.area[i], contact.friction,
        contact.slip_regularization, out.pressure[i], out.slip_speed[i], viscosity);
    // friction as the implicit update applies it (see the file comment)
    const double m_inv = solid.inverse_mass[node];
    const Eigen::Vector3d v_pred =
        ((1.0 - c_damp) * nodes.velocity[node] +
         dt * m_inv * (f_normal - sd.internal_force[node].head<3>())) / (1.0 + c_damp);
    const Eigen::Vector3d rel = v_pred - body_T;
    const Eigen::Vector3d rel_t = rel - rel.dot(normal_T) * normal_T;
    const double a = dt * m_inv * viscosity;
    const Eigen::Vector3d f_friction = -(a / (1.0 + a)) / (dt * m_inv) * rel_t;
    out.force[i] = f_normal;
    out.friction_force[i] = f_friction;
    sd.friction_normal[node] = normal_T;
    sd.external_force[node] = f_normal + f_friction;
  };
  // the node loop: each node's contact (top nodes), then its update when the step moves
  auto node_work = [&](int node) {
    // only top nodes carry an external force (the contact's), and no node a friction
    // viscosity (the friction is an explicit force above): the update reads neither otherwise
    const int i = contact.index_of_node[node];
    if (i >= 0) {
      contact_node(i, node);
      return move ? solid::advance_node<true, false>(solid, *advance, sd, node, dt, c_damp) : 0.0;
    }
    return move ? solid::advance_node<false, false>(solid, *advance, sd, node, dt, c_damp) : 0.0;
  };
  solid::run_node_loop(solid, move ? advance : nullptr, sd, node_work);

  // fixed-order reductions: loads on the femur, summary, stiffness for the stability monitor
  ContactSummary sum;
  sum.cop_T = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Eigen::Vector3d femur_force = Eigen::Vector3d::Zero(), femur_moment = Eigen::Vector3d::Zero();
  std::array<double, 2> weight{};
  std::array<std::array<double, kNumDof>, 2> stiffness{};
  const CoupledDofs coupled_dofs =
      model.coupled_rig_step ? find_coupled_dofs(model) : CoupledDofs{};
  const std::array<Eigen::Vector3d, 2> pivots{state.carriages[0].pivot_W,
                                              state.carriages[1].pivot_W};
  std::array<double, 144> coupling{};
  out.total_force.setZero();
  out.peak_pressure = 0.0;
  out.area = 0.0;
  out.nodes_in_contact = 0;
  const int n = contact.size();
  for (int i = 0; i < n; ++i) {
    if (!(out.pressure[i] > 0.0)) continue;
    const int node = contact.nodes[i];
    const Eigen::Vector3d& x_T = out.position[i];  // x(n): the node may have moved since
    const Eigen::Vector3d p_W = X_WT * x_T;
    const double p = out.pressure[i], area = contact.area[i];
    // the rig's contact damper (see the file comment): the rigid law's stiffness at this
    // pressure over the node's layer, on the femur's closing speed towards the tray
    const Eigen::Vector3d& normal_T = sd.friction_normal[node];
    const double h = solid.reference_positions[node].y();
    const double k_ef = area * ef_stiffness_at_pressure(model.contact, p, h);
    const double closing = femur_velocity_T[i].dot(normal_T);
    const double f_damp = std::clamp(model.contact.damping_beta * k_ef * closing, -p * area,
                                     p * area);
    const Eigen::Vector3d damp_W = X_WT.linear() * (f_damp * normal_T);  // on the tray
    const Eigen::Vector3d f_W = X_WT.linear() * (out.force[i] + out.friction_force[i]) + damp_W;
    femur_force -= f_W;
    femur_moment -= p_W.cross(f_W);
    const int side = solid.reference_positions[node].z() < 0.0 ? 0 : 1;  // medial: z < 0
    sum.normal_force[side] += p * area;
    sum.area[side] += area;
    sum.cop_T[side] += (p * area) * x_T;
    weight[side] += p * area;
    sum.peak_pressure = std::max(sum.peak_pressure, p);
    sum.max_penetration = std::max(sum.max_penetration, p * area / contact.stiffness[i]);
    ++sum.elements_in_contact;
    out.total_force += out.force[i];
    out.peak_pressure = std::max(out.peak_pressure, p);
    out.area += area;
    ++out.nodes_in_contact;
    const Eigen::Vector3d n_W = X_WT.linear() * sd.friction_normal[node];
    const double k = contact.stiffness[i];
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector3d rxn = (p_W - state.carriages[c].pivot_W).cross(n_W);
      for (int j = 0; j < 3; ++j) {
        stiffness[c][j] += k * n_W[j] * n_W[j];
        const double jr = data.axes[c][j].dot(rxn);
        stiffness[c][3 + j] += k * jr * jr;
      }
    }
    if (model.coupled_rig_step) {
      // friction is on the nodes (data.friction is zero), not in the rig's rows; the node's
      // contact normal stands for both surfaces'
      add_contact_coupling(coupled_dofs, k, 0.0, p_W, n_W, n_W, data.axes, pivots, coupling,
                           nullptr);
    }
  }
  if (model.coupled_rig_step) {
    data.contact_coupling = coupling;
    data.friction_coupling = {};
  }
  sum.force_W = femur_force;
  finish_contact_summary(model, weight, stiffness, sum);
  data.contact = sum;
  data.friction = {};  // friction is on the nodes

  // the tray carries the contact forces the insert receives (the opposite of the femur's
  // load), not the reaction of the base nodes (see the file comment: the insert's scaled mass
  // must not be coupled to the tray)
  const Eigen::Vector3d tray_force = -femur_force, tray_moment = -femur_moment;
  data.contact.tray_force_W = tray_force;
  apply_wrench(state, data, 0, femur_force, femur_moment);
  apply_wrench(state, data, 1, tray_force, tray_moment);
}

}  // namespace kneesim::engine
