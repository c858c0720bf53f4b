#include "engine/contact.h"

#include <algorithm>
#include <cmath>

#include "engine/contact_law.h"
#include "engine/kinematics.h"

namespace kneesim::engine {

void update_contact_schedule(const Model& model, Data& data) {
  const Eigen::Isometry3d X_FT = data.X_WF.inverse() * data.X_WT;
  if (!data.schedule_valid) {
    std::fill(data.recheck_at.begin(), data.recheck_at.end(), data.motion);
    data.schedule_valid = true;
  } else if (model.femur_radius > 0.0) {
    // the step's motion seen from the femur, D = X_FT(n+1) X_FT(n)^-1, moves a point at p_F by
    // at most angle(D) |p_F| + |t_D|; measured at |p_F| = femur_radius
    const Eigen::Isometry3d D = X_FT * data.X_FT_prev.inverse();
    const double angle = Eigen::AngleAxisd(D.linear()).angle();
    data.motion += D.translation().norm() + angle * model.femur_radius;
  } else {
    // no femoral radius known: bound by the insert's own extent
    const Eigen::Isometry3d delta = data.X_FT_prev.inverse() * X_FT;
    const double angle = Eigen::AngleAxisd(delta.linear()).angle();
    data.motion += delta.translation().norm() + angle * data.insert_radius;
  }
  data.X_FT_prev = X_FT;
  // branch-free compaction: most elements sleep, and which ones is not predictable
  const int n = model.insert.size();
  data.due.resize(n);  // capacity reserved
  int* due = data.due.data();
  const double* recheck_at = data.recheck_at.data();
  const double motion = data.motion;
  int count = 0;
  for (int e = 0; e < n; ++e) {
    due[count] = e;
    count += recheck_at[e] <= motion ? 1 : 0;
  }
  data.due.resize(count);
}

namespace {

// a carriage's rigid motion this step: pivot velocity, angular velocity and pivot [m/s,
// rad/s, m], the terms of find_point_velocity (engine/kinematics.h) computed once per step
struct CarriageMotion {
  Eigen::Vector3d v, w, pivot;
};

CarriageMotion find_carriage_motion(const State& state, const Data& data, int c) {
  const CarriageState& cs = state.carriages[c];
  return {Eigen::Vector3d(cs.rate[0], cs.rate[1], cs.rate[2]),
          data.axes[c][0] * cs.rate[3] + data.axes[c][1] * cs.rate[4] +
              data.axes[c][2] * cs.rate[5],
          cs.pivot_W};
}

}  // namespace

void finish_contact_summary(const Model& model, const std::array<double, 2>& weight,
                            const std::array<std::array<double, kNumDof>, 2>& stiffness,
                            ContactSummary& sum) {
  for (int side = 0; side < 2; ++side) {
    if (weight[side] > 0.0) sum.cop_T[side] /= weight[side];
  }
  const double area = sum.area[0] + sum.area[1];
  sum.mean_pressure = area > 0.0 ? (sum.normal_force[0] + sum.normal_force[1]) / area : 0.0;
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < kNumDof; ++i) {
      const DofModel& dof = model.carriages[c].dofs[i];
      if (dof.mode != DofMode::kFree && dof.mode != DofMode::kForce) continue;
      sum.omega_max = std::max(sum.omega_max, std::sqrt(stiffness[c][i] / dof.mass));
    }
  }
}

void calc_contact(const Model& model, const State& state, Data& data) {
  update_contact_schedule(model, data);
  const InsertSurface& s = model.insert;
  const ContactModel& cm = model.contact;
  const SignedDistanceField& field = model.femur_sdf;
  const SignedDistanceField& far_field = model.femur_far_sdf;
  const Eigen::Isometry3d X_FW = data.X_WF.inverse();
  const Eigen::Matrix3d R_TW = data.X_WT.linear().transpose();
  const CarriageMotion femur = find_carriage_motion(state, data, 0);
  const CarriageMotion tibia = find_carriage_motion(state, data, 1);
  const double radius2 = model.femur_radius * model.femur_radius;
  const int n = static_cast<int>(data.due.size());
  data.evaluations += n;

  // element-local evaluation (parallel when large; each element writes only its own slots)
#pragma omp parallel for schedule(static) if (n > 2000) num_threads(model.threads)
  for (int i = 0; i < n; ++i) {
    const int e = data.due[i];
    const Eigen::Vector3d c_F = X_FW * (data.X_WT * s.centroid_T[e]);
    const double phi = field.sample(c_F);
    const double d = -phi;
    if (d <= 0.0) {
      // out of contact: sleep until the motion could have closed the gap; beyond the fine
      // band the coarse field (less its interpolation error) tells the distance
      double gap = phi;
      if (phi >= field.band) {
        const double far = far_field.sample(c_F) - far_field.spacing;
        gap = std::max(phi, far);
      }
      const double r2 = c_F.squaredNorm();
      if (model.femur_radius > 0.0 && r2 > radius2) {
        // a point farther from the femoral origin than femur_radius moves proportionally more
        gap *= model.femur_radius / std::sqrt(r2);
      }
      data.recheck_at[e] = data.motion + kLipschitz * gap;
      if (data.penetration[e] != 0.0) {
        // leaving contact: clear the element's slots (they stay zero while it is out, and
        // most evaluations are of elements out of contact: five scattered stores saved)
        data.pressure[e] = 0.0;
        data.penetration[e] = 0.0;
        data.slip_speed[e] = 0.0;
        data.slip_velocity_T[e].setZero();
        data.element_force_W[e].setZero();
      }
      continue;
    }
    data.recheck_at[e] = data.motion;  // in contact: evaluate every step
    const Eigen::Vector3d c_W = data.X_WT * s.centroid_T[e];
    const Eigen::Vector3d n_W = data.X_WT.linear() * s.normal_T[e];
    const double h = s.thickness[e];
    // relative velocity of the femoral surface over the insert at the element
    const Eigen::Vector3d v_rel = (femur.v + femur.w.cross(c_W - femur.pivot)) -
                                  (tibia.v + tibia.w.cross(c_W - tibia.pivot));
    const double closing = -v_rel.dot(n_W);  // rate of penetration [m/s]
    const Eigen::Vector3d v_slip = v_rel + closing * n_W;
    const double p_elastic = ef_pressure(cm.law, cm.foundation_modulus, d, h);
    const double p_damping =
        cm.damping_beta * ef_stiffness(cm.law, cm.foundation_modulus, d, h) * closing;
    // the damper may at most double or cancel the elastic pressure: an impact (a fast closing
    // speed) must not produce a force spike that the stable step does not cover
    const double p = p_elastic + std::clamp(p_damping, -p_elastic, p_elastic);
    const Eigen::Vector3d traction = p * n_W + friction_traction(cm.friction, p, v_slip,
                                                                 cm.slip_regularization);
    data.pressure[e] = p_elastic;
    data.penetration[e] = d;
    data.slip_speed[e] = v_slip.norm();
    data.slip_velocity_T[e] = R_TW * v_slip;
    data.element_force_W[e] = s.area[e] * traction;
    data.friction_viscosity[e] = s.area[e] * cm.friction * p /
                                 std::sqrt(v_slip.squaredNorm() +
                                           cm.slip_regularization * cm.slip_regularization);
  }
  data.in_contact.clear();
  for (int i = 0; i < n; ++i) {
    if (data.penetration[data.due[i]] > 0.0) data.in_contact.push_back(data.due[i]);
  }

  // fixed-order reduction: totals, per-condyle summary, torques about the pivots, and the
  // tangent stiffness per DOF for the stability monitor
  ContactSummary sum;  // local until complete (see friction_damping below)
  sum.cop_T = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment_O = Eigen::Vector3d::Zero();
  std::array<double, 2> weight{};
  std::array<std::array<double, kNumDof>, 2> stiffness{};
  // local copies: stores into data would be reloaded at every element (they might alias)
  std::array<std::array<double, kNumDof>, 2> friction_damping{};
  const std::array<std::array<Eigen::Vector3d, 3>, 2> axes = data.axes;
  const std::array<Eigen::Vector3d, 2> pivots = {state.carriages[0].pivot_W,
                                                 state.carriages[1].pivot_W};
  for (int e : data.in_contact) {
    const Eigen::Vector3d c_W = data.X_WT * s.centroid_T[e];
    const Eigen::Vector3d n_W = data.X_WT.linear() * s.normal_T[e];
    const double ke = s.area[e] * ef_stiffness(cm.law, cm.foundation_modulus,
                                               data.penetration[e], s.thickness[e]);
    const double ce = data.friction_viscosity[e];
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector3d r = c_W - pivots[c];
      const Eigen::Vector3d rxn = r.cross(n_W);
      for (int i = 0; i < 3; ++i) {
        // normal stiffness along the DOF's direction; friction acts on its tangential part
        stiffness[c][i] += ke * n_W[i] * n_W[i];
        friction_damping[c][i] += ce * (1.0 - n_W[i] * n_W[i]);
        const double j = axes[c][i].dot(rxn);
        stiffness[c][3 + i] += ke * j * j;
        const double jj = axes[c][i].cross(r).squaredNorm();
        friction_damping[c][3 + i] += ce * (jj - j * j);
      }
    }
    const Eigen::Vector3d& f = data.element_force_W[e];
    force += f;
    moment_O += c_W.cross(f);
    const double p = data.pressure[e];
    const int side = s.medial[e] ? 0 : 1;
    sum.normal_force[side] += p * s.area[e];
    sum.area[side] += s.area[e];
    sum.cop_T[side] += (p * s.area[e]) * s.centroid_T[e];
    weight[side] += p * s.area[e];
    sum.peak_pressure = std::max(sum.peak_pressure, p);
    sum.max_penetration = std::max(sum.max_penetration, data.penetration[e]);
    sum.max_penetration_ratio =
        std::max(sum.max_penetration_ratio, data.penetration[e] / s.thickness[e]);
    ++sum.elements_in_contact;
  }
  data.friction_damping = friction_damping;
  sum.force_W = force;
  sum.tray_force_W = -force;
  finish_contact_summary(model, weight, stiffness, sum);
  data.contact = sum;

  // generalized forces: +force on the femur, -force on the tibia
  for (int c = 0; c < 2; ++c) {
    const double sign = c == 0 ? 1.0 : -1.0;
    const Eigen::Vector3d& pivot = state.carriages[c].pivot_W;
    const Eigen::Vector3d torque = sign * (moment_O - pivot.cross(force));
    auto& Q = data.generalized[c];
    Q[0] += sign * force.x();
    Q[1] += sign * force.y();
    Q[2] += sign * force.z();
    Q[3] += torque.dot(data.axes[c][0]);
    Q[4] += torque.dot(data.axes[c][1]);
    Q[5] += torque.dot(data.axes[c][2]);
  }
}

}  // namespace kneesim::engine
