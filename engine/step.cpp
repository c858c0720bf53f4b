#include "engine/step.h"

#include <cmath>
#include <cstring>

#include "engine/contact.h"
#include "engine/contact_law.h"
#include "engine/implicit_friction.h"
#include "engine/insert_solid.h"
#include "engine/kinematics.h"
#include "engine/rig_coupling.h"
#include "engine/solid/solid_build.h"
#include "engine/solid/solid_step.h"

namespace kneesim::engine {
namespace {

double gait_pct_at(const Model& model, double t) {
  double pct = std::fmod(100.0 * t / model.period, 100.0);
  if (pct < 0.0) pct += 100.0;
  return pct;
}

// prescribed or locked value of a DOF at time t [m or rad]
double target_value(const Model& model, const DofModel& dof, double t) {
  if (dof.mode == DofMode::kPrescribed && dof.channel >= 0) {
    return dof.initial + dof.scale * model.gait.value(dof.channel, gait_pct_at(model, t));
  }
  return dof.initial;
}

// stage: waveform loads at the current time, into data.applied and data.generalized
void apply_loads(const Model& model, const State& state, Data& data) {
  data.gait_pct = gait_pct_at(model, state.time);
  for (int c = 0; c < 2; ++c) {
    const CarriageModel& cm = model.carriages[c];
    auto& Q = data.generalized[c];
    const Eigen::Vector3d r_W = state.carriages[c].R_WB * cm.load_point_B;
    for (int i = 0; i < kNumDof; ++i) {
      const DofModel& dof = cm.dofs[i];
      double f = 0.0;
      if (dof.mode == DofMode::kForce && dof.channel >= 0) {
        f = dof.scale * model.gait.value(dof.channel, data.gait_pct);
      }
      data.applied[c][i] = f;
      if (f == 0.0) continue;
      Q[i] += f;
      if (!is_rotation(i)) {
        // a force along axis i through the load point also produces a moment about the pivot
        Eigen::Vector3d F = Eigen::Vector3d::Zero();
        F[i] = f;
        const Eigen::Vector3d torque = r_W.cross(F);
        for (int r = 0; r < 3; ++r) Q[3 + r] += torque.dot(data.axes[c][r]);
      }
    }
  }
}

// stage: spring-gap soft-tissue restraint on the tibial carriage (physics.md section 2)
void apply_restraint(const Model& model, Data& data) {
  auto& Q = data.generalized[1];
  const double ap = data.q[1][0], ie = data.q[1][4];
  double force_ap = 0.0, torque_ie = 0.0, k_ap = 0.0, k_ie = 0.0;
  for (const RestraintSpring& s : model.restraint) {
    switch (s.kind) {
      case RestraintKind::kTranslational: {
        // a spring attached at z_arm: the IE rotation moves its end by z sin(ie) along x
        const double x = ap + s.z_arm * std::sin(ie);
        const double f = spring_gap_force(s, x), k = spring_gap_stiffness(s, x);
        const double arm = s.z_arm * std::cos(ie);
        force_ap += f;
        torque_ie += arm * f;
        k_ap += k;
        k_ie += k * arm * arm;
        break;
      }
      case RestraintKind::kRotational:
        torque_ie += spring_gap_force(s, ie);
        k_ie += spring_gap_stiffness(s, ie);
        break;
    }
  }
  Q[0] += force_ap;
  Q[4] += torque_ie;
  data.restraint_stiffness[0] = k_ap;
  data.restraint_stiffness[4] = k_ie;
  data.restraint_force = Eigen::Vector3d(force_ap, torque_ie, 0.0);
}

// stage: central-difference update of one carriage (velocity half step, SO(3) rotation)
void integrate_carriage(const Model& model, int c, State& state, const Data& data) {
  const CarriageModel& cm = model.carriages[c];
  CarriageState& cs = state.carriages[c];
  const double dt = model.dt, t1 = state.time + dt;
  bool project_rotation = false;
  for (int i = 0; i < kNumDof; ++i) {
    const DofModel& dof = cm.dofs[i];
    double& rate = cs.rate[i];
    switch (dof.mode) {
      case DofMode::kLocked:
        rate = 0.0;
        project_rotation |= is_rotation(i);
        break;
      case DofMode::kPrescribed:
        rate = (target_value(model, dof, t1) - data.q[c][i]) / dt;
        project_rotation |= is_rotation(i);
        break;
      case DofMode::kFree:
      case DofMode::kForce: {
        if (model.coupled_rig_step) break;  // rate set by update_coupled_rates
        // the regularized friction is a stiff damper near stick (slope mu p A / eps): it is
        // taken at the new rate (engine/implicit_friction.h), which keeps the update stable
        // for any eps; the rest of the force, as in any central-difference step, at the old one
        const FrictionTerms& f = data.friction[c];
        if (!dof.implicit && !(f.secant[i] > 0.0)) {
          // no friction on an explicit DOF: the plain central-difference update
          rate += dt * (data.generalized[c][i] - dof.damping * rate) / dof.mass;
          break;
        }
        double a = dof.mass / dt;  // a (u - v) = G + F(u)
        double other = data.generalized[c][i] - f.force[i] - dof.damping * rate;
        if (dof.implicit) {
          // a light DOF: its stiffness k (the elastic force at x(n+1) = x(n) + dt u, linear),
          // the contact damper beta k_contact and the carriage damper at the new rate u too
          const double k_contact = data.contact.stiffness[c][i];
          const double k = k_contact + (c == 1 ? data.restraint_stiffness[i] : 0.0);
          a += dof.damping + model.contact.damping_beta * k_contact + k * dt;
          other -= k * dt * rate;
        }
        rate = find_implicit_friction_rate(rate, a, other, f.force[i], f.secant[i],
                                           f.capacity[i]);
        break;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    const DofModel& dof = cm.dofs[i];
    if (dof.mode == DofMode::kLocked || dof.mode == DofMode::kPrescribed) {
      cs.pivot_W[i] = cm.pivot0_W[i] + target_value(model, dof, t1);
    } else {
      cs.pivot_W[i] += dt * cs.rate[i];
    }
  }
  const Eigen::Vector3d w_W = data.axes[c][0] * cs.rate[3] + data.axes[c][1] * cs.rate[4] +
                              data.axes[c][2] * cs.rate[5];
  cs.R_WB = update_rotation(cs.R_WB, w_W, dt);
  if (project_rotation) {
    // locked and prescribed angles are constraints: put the rotation back on them exactly
    GimbalAngles g = find_gimbal_angles(cs.R_WB);
    double* angle[3] = {&g.vv, &g.ie, &g.fe};
    for (int r = 0; r < 3; ++r) {
      const DofModel& dof = cm.dofs[3 + r];
      if (dof.mode == DofMode::kLocked || dof.mode == DofMode::kPrescribed) {
        *angle[r] = target_value(model, dof, t1);
      }
    }
    cs.R_WB = gimbal_rotation(g);
  }
}

// a carriage far from where it started has lost the implant (e.g. fell through or flipped)
bool is_runaway(const Model& model, const Data& data) {
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < kNumDof; ++i) {
      const double excursion = std::abs(data.q[c][i] - model.carriages[c].dofs[i].initial);
      const bool prescribed = model.carriages[c].dofs[i].mode == DofMode::kPrescribed;
      if (prescribed) continue;
      if (is_rotation(i) ? excursion > 60.0 * M_PI / 180.0 : excursion > 0.05) return true;
    }
  }
  return false;
}

bool is_finite(const State& state) {
  for (const CarriageState& cs : state.carriages) {
    if (!cs.pivot_W.allFinite() || !cs.R_WB.allFinite()) return false;
    for (double r : cs.rate)
      if (!std::isfinite(r)) return false;
  }
  return true;
}

}  // namespace

StepStatus find_runaway(const Model& model, const Data& data) {
  if (is_runaway(model, data)) return StepStatus::kRunawayMotion;
  // beyond 90 % of the distance field's exact band a deeper overlap could not be measured
  if (data.contact.max_penetration_ratio > model.contact.runaway_fraction ||
      data.contact.max_penetration > 0.9 * model.femur_sdf.band) {
    return StepStatus::kRunawayPenetration;
  }
  return StepStatus::kOk;
}

double calc_stability_ratio(const Model& model, const Data& data) {
  const double w = data.contact.omega_max;
  const double z = 0.5 * model.contact.damping_beta * w;
  return w * model.dt / (2.0 * (std::sqrt(1.0 + z * z) - z));
}

const char* to_string(StepStatus status) {
  switch (status) {
    case StepStatus::kOk:
      return "ok";
    case StepStatus::kNotFinite:
      return "a position or velocity became NaN or infinite";
    case StepStatus::kRunawayMotion:
      return "runaway motion: a carriage moved more than 50 mm or tilted more than 60 deg from "
             "its start (lost contact, or the rig is unstable)";
    case StepStatus::kUnstableStep:
      return "the contact stiffened beyond the stability limit of the time step";
    case StepStatus::kRunawayPenetration:
      return "runaway penetration: the femoral component sank through the insert's elastic "
             "layer";
    case StepStatus::kInvertedElement:
      return "an element of the deformable insert inverted (its volume went through zero)";
  }
  return "unknown";
}

namespace {

// calc_forces, and with `advance` the deformable insert's nodes stepped in its node loop
void calc_forces_and_advance(const Model& model, const State& state, Data& data,
                             solid::SolidState* advance) {
  // kinematics: DOF values, gimbal axes, part poses
  update_kinematics(model, state, data);
  for (auto& Q : data.generalized) Q.fill(0.0);
  // loads: gait waveforms at t (axial force, AP force, IE torque)
  apply_loads(model, state, data);
  if (model.insert_solid.empty()) {
    // contact search and forces: elastic foundation + regularized Coulomb friction
    calc_contact(model, state, data);
  } else {
    // deformable insert: element forces, its top nodes against the femur, the tray's load
    calc_insert_solid_forces(model, state, data, advance);
  }
  // springs: spring-gap soft-tissue restraint on the tibial carriage
  apply_restraint(model, data);
}

}  // namespace

void calc_forces(const Model& model, const State& state, Data& data) {
  calc_forces_and_advance(model, state, data, nullptr);
}

StepStatus step(const Model& model, State& state, Data& data) {
  // forces at x(n) with velocities v(n - 1/2); the deformable insert's nodes take their
  // central-difference step in its node loop (they need only their own forces)
  const bool solid = !model.insert_solid.empty();
  calc_forces_and_advance(model, state, data, solid ? &state.insert_solid : nullptr);
  // an inverted insert element: stop before anything moves (the state stays the last good one)
  if (solid && data.insert_solid.status != solid::SolidStatus::kOk) {
    return StepStatus::kInvertedElement;
  }
  // rates v(n + 1/2): light AP and IE implicit, the rest central difference; the light DOFs
  // each alone, or coupled to every moved DOF through the contact's stiffness; then x(n + 1),
  // R(n + 1) on SO(3)
  if (model.coupled_rig_step) update_coupled_rates(model, state, data);
  for (int c = 0; c < 2; ++c) integrate_carriage(model, c, state, data);
  state.time += model.dt;
  ++state.step;
  // checks: NaN, runaway penetration
  if (!is_finite(state)) return StepStatus::kNotFinite;
  // (runaway motion before the step's stability: a carriage that flew off says so)
  if (is_runaway(model, data)) return StepStatus::kRunawayMotion;
  if (calc_stability_ratio(model, data) > 1.0) return StepStatus::kUnstableStep;
  return find_runaway(model, data);
}

State make_initial_state(const Model& model) {
  State state;
  for (int c = 0; c < 2; ++c) {
    const CarriageModel& cm = model.carriages[c];
    std::array<double, kNumDof> q{};
    for (int i = 0; i < kNumDof; ++i) q[i] = target_value(model, cm.dofs[i], 0.0);
    state.carriages[c].pivot_W = cm.pivot0_W + Eigen::Vector3d(q[0], q[1], q[2]);
    state.carriages[c].R_WB = gimbal_rotation({q[3], q[4], q[5]});
    state.carriages[c].rate.fill(0.0);
  }
  if (!model.insert_solid.empty()) state.insert_solid = solid::make_solid_state(model.insert_solid);
  return state;
}

Data make_data(const Model& model) {
  Data data;
  const int n = model.insert.size();
  data.recheck_at.assign(n, 0.0);
  data.due.reserve(n);
  data.due_mask.assign((n + 63) / 64, 0);
  data.in_contact.reserve(n);
  data.pressure.assign(n, 0.0);
  data.penetration.assign(n, 0.0);
  data.slip_speed.assign(n, 0.0);
  data.slip_velocity_T.assign(n, Eigen::Vector3d::Zero());
  data.element_force_W.assign(n, Eigen::Vector3d::Zero());
  data.friction_viscosity.assign(n, 0.0);
  data.contact_stiffness.assign(n, 0.0);
  for (int e = 0; e < n; ++e) {
    data.insert_radius = std::max(data.insert_radius, model.insert.centroid_T[e].norm());
  }
  if (!model.insert_solid.empty()) {
    data.insert_solid = solid::make_solid_data(model.insert_solid);
    data.insert_contact = solid::make_surface_contact_data(model.insert_contact);
  }
  return data;
}

uint64_t hash_state(const State& state) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) {
      h ^= b[i];
      h *= 1099511628211ull;
    }
  };
  mix(&state.time, sizeof state.time);
  mix(&state.step, sizeof state.step);
  for (const CarriageState& cs : state.carriages) {
    mix(cs.pivot_W.data(), 3 * sizeof(double));
    mix(cs.R_WB.data(), 9 * sizeof(double));
    mix(cs.rate.data(), kNumDof * sizeof(double));
  }
  const solid::SolidState& solid = state.insert_solid;
  mix(solid.position.data(), solid.position.size() * sizeof(Eigen::Vector3d));
  mix(solid.velocity.data(), solid.velocity.size() * sizeof(Eigen::Vector3d));
  mix(solid.plastic_strain.data(), solid.plastic_strain.size() * sizeof(solid::Sym6));
  mix(solid.alpha.data(), solid.alpha.size() * sizeof(double));
  mix(solid.plastic_work.data(), solid.plastic_work.size() * sizeof(double));
  return h;
}

}  // namespace kneesim::engine
