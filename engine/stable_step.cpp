#include "engine/stable_step.h"

#include <algorithm>
#include <cmath>

#include "engine/contact.h"
#include "engine/contact_law.h"
#include "engine/kinematics.h"
#include "engine/step.h"

namespace kneesim::engine {

double position_femur_statically(const Model& model, State& state, Data& data, double load) {
  // bisection on the femur height: contact force rises monotonically as it goes down
  // the contact schedule follows the femur's moves like any motion: elements far from it stay
  // asleep while the bisection homes in
  data.schedule_valid = false;
  auto force_at = [&](double y) {
    state.carriages[0].pivot_W.y() = y;
    calc_forces(model, state, data);
    return data.contact.force_W.y();
  };
  double hi = state.carriages[0].pivot_W.y() + 0.5e-3;
  double step = 0.5e-3;
  // raise until out of contact
  for (int i = 0; i < 60 && force_at(hi) > 0.0; ++i) hi += step;
  double lo = hi;
  // lower until the load is exceeded (stop before runaway)
  for (int i = 0; i < 200; ++i) {
    lo -= 0.1e-3;
    if (force_at(lo) >= load || data.contact.max_penetration_ratio > 0.4) break;
  }
  for (int it = 0; it < 26; ++it) {  // 20 mm / 2^26: 0.3 nm
    const double mid = 0.5 * (lo + hi);
    if (force_at(mid) > load) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double f = force_at(0.5 * (lo + hi));
  state.carriages[0].rate.fill(0.0);
  return f;
}

std::array<std::array<double, kNumDof>, 2> calc_contact_stiffness(const Model& model,
                                                                  const State& state,
                                                                  Data& data) {
  calc_forces(model, state, data);
  std::array<std::array<double, kNumDof>, 2> k{};
  const InsertSurface& s = model.insert;
  for (int e : data.in_contact) {
    const double d = data.penetration[e];
    if (d <= 0.0) continue;
    const double ke = s.area[e] * ef_stiffness(model.contact.law, model.contact.foundation_modulus,
                                               model.contact.exponent,
                                               d, s.thickness[e]);
    const Eigen::Vector3d c_W = data.X_WT * s.centroid_T[e];
    const Eigen::Vector3d n_W = data.X_WT.linear() * s.normal_T[e];
    for (int c = 0; c < 2; ++c) {
      const Eigen::Vector3d r = c_W - state.carriages[c].pivot_W;
      for (int i = 0; i < kNumDof; ++i) {
        const double j = is_rotation(i) ? data.axes[c][i - 3].cross(r).dot(n_W) : n_W[i];
        k[c][i] += ke * j * j;
      }
    }
  }
  return k;
}

StableStepReport calc_stable_time_step(const Model& model, double peak_load,
                                       const std::vector<double>& flexion_probes,
                                       double damping_ratio, double safety) {
  StableStepReport report;
  Data data = make_data(model);
  // light (implicit) DOFs are stable in their own stiffness for any step and do not limit it,
  // unless no moved DOF is explicit (a hand-made rig): then every moved DOF counts
  bool any_explicit = false;
  for (const CarriageModel& cm : model.carriages) {
    for (const DofModel& dof : cm.dofs) {
      any_explicit |= !dof.implicit && (dof.mode == DofMode::kFree || dof.mode == DofMode::kForce);
    }
  }
  for (double flexion : flexion_probes) {
    State state = make_initial_state(model);
    // pose the femur at the probe flexion, everything else at its t = 0 value
    GimbalAngles g = find_gimbal_angles(state.carriages[0].R_WB);
    g.fe = flexion;
    state.carriages[0].R_WB = gimbal_rotation(g);
    position_femur_statically(model, state, data, peak_load);
    const auto k = calc_contact_stiffness(model, state, data);
    for (int c = 0; c < 2; ++c) {
      for (int i = 0; i < kNumDof; ++i) {
        const DofModel& dof = model.carriages[c].dofs[i];
        if (dof.mode != DofMode::kFree && dof.mode != DofMode::kForce) continue;
        if (dof.implicit && any_explicit) continue;
        double ki = k[c][i];
        for (const RestraintSpring& s : model.restraint) {
          if (c == 1 && (i == 4 || (i == 0 && s.kind == RestraintKind::kTranslational))) {
            ki += std::max({s.k_inside, s.k_positive, s.k_negative}) *
                  (s.kind == RestraintKind::kTranslational && i == 4 ? s.z_arm * s.z_arm : 1.0);
          }
        }
        const double omega = std::sqrt(ki / dof.mass);
        if (omega > report.omega_max) {
          report.omega_max = omega;
          report.stiffness_max = ki;
          report.governing_carriage = c;
          report.governing_dof = i;
          report.governing_flexion = flexion;
        }
      }
    }
  }
  if (report.omega_max <= 0.0) report.omega_max = 1.0;
  const double z = damping_ratio;
  report.dt_critical = 2.0 / report.omega_max * (std::sqrt(1.0 + z * z) - z);
  report.dt = safety * report.dt_critical;
  report.damping_beta = 2.0 * z / report.omega_max;
  return report;
}

}  // namespace kneesim::engine
