#include "engine/rig_coupling.h"

#include <algorithm>
#include <cmath>

#include "engine/data.h"
#include "engine/implicit_friction.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

CoupledDofs find_coupled_dofs(const Model& model) {
  CoupledDofs d;
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < kNumDof; ++i) {
      const DofMode mode = model.carriages[c].dofs[i].mode;
      if (mode == DofMode::kFree || mode == DofMode::kForce) d.slot[d.n++] = coupling_slot(c, i);
    }
  }
  return d;
}

void add_contact_coupling(const CoupledDofs& dofs, double ke, double ce,
                          const Eigen::Vector3d& c_W, const Eigen::Vector3d& n_W,
                          const Eigen::Vector3d& m_W,
                          const std::array<std::array<Eigen::Vector3d, 3>, 2>& axes,
                          const std::array<Eigen::Vector3d, 2>& pivots,
                          std::array<double, 144>& K, std::array<double, 144>* C) {
  // g: the point's motion along n_W per unit DOF rate, h: along m_W; the femur's and the
  // tibia's enter with opposite signs (the gap closes when they move towards each other)
  std::array<double, 12> g{}, h{};
  std::array<Eigen::Vector3d, 12> tangential;
  for (int k = 0; k < dofs.n; ++k) {
    const int c = dofs.slot[k] / 6, i = dofs.slot[k] % 6;
    const double sign = c == 0 ? 1.0 : -1.0;
    // the point's velocity per unit DOF rate
    Eigen::Vector3d J = Eigen::Vector3d::Zero();
    if (i < 3) {
      J[i] = sign;
    } else {
      J = sign * axes[c][i - 3].cross(c_W - pivots[c]);
    }
    g[k] = n_W.dot(J);
    h[k] = m_W.dot(J);
    tangential[k] = J - g[k] * n_W;
  }
  if (C != nullptr && ce > 0.0) {
    for (int k = 0; k < dofs.n; ++k) {
      double* row = &(*C)[12 * dofs.slot[k]];
      for (int l = 0; l < dofs.n; ++l) row[dofs.slot[l]] += ce * tangential[k].dot(tangential[l]);
    }
  }
  for (int k = 0; k < dofs.n; ++k) {
    const double kg = ke * g[k];
    double* row = &K[12 * dofs.slot[k]];
    for (int l = 0; l < dofs.n; ++l) row[dofs.slot[l]] += kg * h[l];
  }
}

int solve_coupled_system(const CoupledSystem& sys, std::array<double, 12>& x, double tol,
                         int max_sweeps) {
  x.fill(0.0);
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    double change = 0.0, scale = 0.0;
    for (int k = 0; k < sys.n; ++k) {
      double rhs = sys.b[k], friction = sys.friction[k];
      const double* row = &sys.off[12 * k];
      const double* row_f = &sys.off_friction[12 * k];
      for (int l = 0; l < sys.n; ++l) {
        if (l != k) {
          rhs -= row[l] * x[l];
          friction -= row_f[l] * x[l];
        }
      }
      // the row alone: a x = rhs + F(x), F the capped secant line of its friction
      const double next = find_implicit_friction_rate(0.0, sys.a[k], rhs, friction,
                                                      sys.secant[k], sys.capacity[k]);
      change = std::max(change, sys.a[k] * std::abs(next - x[k]));
      scale = std::max(scale, std::abs(sys.b[k]) + sys.a[k] * std::abs(next));
      x[k] = next;
    }
    if (change <= tol * scale) return sweep;
  }
  return max_sweeps;
}

void update_coupled_rates(const Model& model, State& state, const Data& data) {
  const CoupledDofs dofs = find_coupled_dofs(model);
  const double dt = model.dt, beta = model.contact.damping_beta;
  const std::array<double, 144>& K = data.contact_coupling;
  const std::array<double, 144>& C = data.friction_coupling;
  std::array<double, 12> v{};
  for (int k = 0; k < dofs.n; ++k) {
    v[k] = state.carriages[dofs.slot[k] / 6].rate[dofs.slot[k] % 6];
  }
  CoupledSystem sys;
  sys.n = dofs.n;
  for (int k = 0; k < dofs.n; ++k) {
    const int c = dofs.slot[k] / 6, i = dofs.slot[k] % 6;
    const DofModel& dof = model.carriages[c].dofs[i];
    const FrictionTerms& f = data.friction[c];
    sys.friction[k] = f.force[i];
    sys.secant[k] = f.secant[i];
    sys.capacity[k] = f.capacity[i];
    if (!dof.implicit) {
      // a heavy DOF: central difference as in the partitioned step (its row stands alone),
      // friction at the new rate capped
      sys.a[k] = dof.mass / dt;
      sys.b[k] = data.generalized[c][i] - f.force[i] - dof.damping * v[k];
      continue;
    }
    // a light DOF: implicit in the contact's stiffness to every moved DOF (the heavy ones at
    // their new rates), the restraint on the tibial AP and IE (its AP-IE coupling left
    // explicit), the dampers at the new rate, its friction moved by the others' rates
    const double k_restraint = c == 1 ? data.restraint_stiffness[i] : 0.0;
    const double* row = &K[12 * dofs.slot[k]];
    double k_v = k_restraint * v[k];
    for (int l = 0; l < dofs.n; ++l) k_v += row[dofs.slot[l]] * v[l];
    sys.a[k] = dof.mass / dt + dof.damping + (beta + dt) * row[dofs.slot[k]] + dt * k_restraint;
    sys.b[k] = data.generalized[c][i] - f.force[i] - dof.damping * v[k] - dt * k_v;
    for (int l = 0; l < dofs.n; ++l) {
      if (l != k) {
        sys.off[12 * k + l] = (beta + dt) * row[dofs.slot[l]];
        sys.off_friction[12 * k + l] = C[12 * dofs.slot[k] + dofs.slot[l]];
      }
    }
  }
  std::array<double, 12> x{};
  solve_coupled_system(sys, x);
  for (int k = 0; k < dofs.n; ++k) {
    state.carriages[dofs.slot[k] / 6].rate[dofs.slot[k] % 6] = v[k] + x[k];
  }
}

}  // namespace kneesim::engine
