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
  data.due.clear();
  const int n = model.insert.size();
  for (int e = 0; e < n; ++e) {
    if (data.recheck_at[e] <= data.motion) data.due.push_back(e);  // capacity reserved
  }
}

void calc_contact(const Model& model, const State& state, Data& data) {
  update_contact_schedule(model, data);
  const InsertSurface& s = model.insert;
  const ContactModel& cm = model.contact;
  const Eigen::Isometry3d X_FW = data.X_WF.inverse();
  const Eigen::Matrix3d R_TW = data.X_WT.linear().transpose();
  const int n = static_cast<int>(data.due.size());
  data.evaluations += n;

  // element-local evaluation (parallel when large; each element writes only its own slots)
#pragma omp parallel for schedule(static) if (n > 2000) num_threads(model.threads)
  for (int i = 0; i < n; ++i) {
    const int e = data.due[i];
    const Eigen::Vector3d c_W = data.X_WT * s.centroid_T[e];
    const Eigen::Vector3d c_F = X_FW * c_W;
    const double phi = model.femur_sdf.sample(c_F);
    const double d = -phi;
    if (d <= 0.0) {
      // out of contact: sleep until the motion could have closed the gap; beyond the fine
      // band the coarse field (less its interpolation error) tells the distance
      double gap = phi;
      if (phi >= model.femur_sdf.band) {
        const double far = model.femur_far_sdf.sample(c_F) - model.femur_far_sdf.spacing;
        gap = std::max(phi, far);
      }
      if (model.femur_radius > 0.0) {
        // a point farther from the femoral origin than femur_radius moves proportionally more
        gap *= std::min(1.0, model.femur_radius / c_F.norm());
      }
      data.recheck_at[e] = data.motion + kLipschitz * gap;
      data.pressure[e] = 0.0;
      data.penetration[e] = 0.0;
      data.slip_speed[e] = 0.0;
      data.slip_velocity_T[e].setZero();
      data.element_force_W[e].setZero();
      continue;
    }
    data.recheck_at[e] = data.motion;  // in contact: evaluate every step
    const Eigen::Vector3d n_W = data.X_WT.linear() * s.normal_T[e];
    const double h = s.thickness[e];
    // relative velocity of the femoral surface over the insert at the element
    const Eigen::Vector3d v_rel =
        find_point_velocity(state, data, 0, c_W) - find_point_velocity(state, data, 1, c_W);
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
  ContactSummary& sum = data.contact;
  sum = ContactSummary{};
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment_O = Eigen::Vector3d::Zero();
  std::array<double, 2> weight{};
  std::array<std::array<double, kNumDof>, 2> stiffness{};
  for (auto& f : data.friction_damping) f.fill(0.0);
  for (int e : data.in_contact) {
    const Eigen::Vector3d c_W = data.X_WT * s.centroid_T[e];
    const Eigen::Vector3d n_W = data.X_WT.linear() * s.normal_T[e];
    const double ke = s.area[e] * ef_stiffness(cm.law, cm.foundation_modulus,
                                               data.penetration[e], s.thickness[e]);
    const double ce = data.friction_viscosity[e];
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector3d r = c_W - state.carriages[c].pivot_W;
      const Eigen::Vector3d rxn = r.cross(n_W);
      for (int i = 0; i < 3; ++i) {
        // normal stiffness along the DOF's direction; friction acts on its tangential part
        stiffness[c][i] += ke * n_W[i] * n_W[i];
        data.friction_damping[c][i] += ce * (1.0 - n_W[i] * n_W[i]);
        const double j = data.axes[c][i].dot(rxn);
        stiffness[c][3 + i] += ke * j * j;
        const double jj = data.axes[c][i].cross(r).squaredNorm();
        data.friction_damping[c][3 + i] += ce * (jj - j * j);
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
  for (int side = 0; side < 2; ++side) {
    if (weight[side] > 0.0) sum.cop_T[side] /= weight[side];
  }
  const double area = sum.area[0] + sum.area[1];
  sum.mean_pressure = area > 0.0 ? (sum.normal_force[0] + sum.normal_force[1]) / area : 0.0;
  sum.force_W = force;
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < kNumDof; ++i) {
      const DofModel& dof = model.carriages[c].dofs[i];
      if (dof.mode != DofMode::kFree && dof.mode != DofMode::kForce) continue;
      sum.omega_max = std::max(sum.omega_max, std::sqrt(stiffness[c][i] / dof.mass));
    }
  }

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
