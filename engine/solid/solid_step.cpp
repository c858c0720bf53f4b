#include "engine/solid/solid_step.h"

#include <Eigen/LU>
#include <algorithm>

namespace kneesim::engine::solid {

void calc_hex8_response(const Hex8Reference& ref, const SolidMaterial& material,
                        const HexPoints& x, const Sym6& plastic_strain, double alpha,
                        Hex8Response& out) {
  const Eigen::Matrix3d F = calc_deformation_gradient(ref.gradient, x);
  out.det_F = F.determinant();
  // Green-Lagrange strain and the material's second Piola-Kirchhoff stress
  const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
  out.update = calc_stress(material, to_voigt(E), plastic_strain, alpha);
  const Eigen::Matrix3d S = from_voigt(out.update.stress);
  // nodal forces f_a = V0 F S B_a
  const Eigen::Matrix3d P = ref.volume * (F * S);
  for (int a = 0; a < kHexNodes; ++a) out.force[a] = P * ref.gradient.row(a).transpose();
  // elastic energy V0 S : E_e / 2
  const Sym6 e = to_voigt(E) - out.update.plastic_strain;
  const Sym6& s = out.update.stress;
  out.strain_energy = 0.5 * ref.volume *
                      (s[0] * e[0] + s[1] * e[1] + s[2] * e[2] +
                       2.0 * (s[3] * e[3] + s[4] * e[4] + s[5] * e[5]));
  // hourglass forces on the hourglass displacements q_m = sum_a gamma_m,a x_a
  out.hourglass_energy = 0.0;
  for (int m = 0; m < kHourglassModes; ++m) {
    Eigen::Vector3d q = -ref.hourglass_offset[m];
    for (int a = 0; a < kHexNodes; ++a) q += ref.gamma(m, a) * x[a];
    const Eigen::Vector3d kq = ref.hourglass_stiffness[m] * q;
    out.hourglass_energy += 0.5 * q.dot(kq);
    for (int a = 0; a < kHexNodes; ++a) out.force[a] += ref.gamma(m, a) * kq;
  }
}

void calc_solid_forces(const SolidModel& model, const SolidState& state, SolidData& data) {
  const int n_el = model.num_elements(), n_nodes = model.num_nodes();
  const int n_batches = model.num_batches();
  const bool plastic = model.material.kind == SolidMaterialKind::kJ2Plastic;
  // element loop over batches: each batch writes only its own buffers and its elements' slots
#pragma omp parallel for num_threads(model.threads) schedule(static)
  for (int b = 0; b < n_batches; ++b) {
    const int e0 = b * kBatchLanes, count = std::min(kBatchLanes, n_el - e0);
    Hex8BatchResult r;
    calc_hex8_batch(model.batches[b], model.material, state.position.data(),
                    plastic ? &state.plastic_strain[e0] : nullptr,
                    plastic ? &state.alpha[e0] : nullptr, count, data.batch_force[b], r);
    SolidBatchTotals t;
    for (int l = 0; l < count; ++l) {
      const int e = e0 + l;
      Sym6& stress = data.stress[e];
      for (int v = 0; v < 6; ++v) stress[v] = r.stress[v][l];
      data.von_mises[e] = r.von_mises[l];
      data.strain_energy[e] = r.strain_energy[l];
      data.hourglass_energy[e] = r.hourglass_energy[l];
      data.jacobian_ratio[e] = r.det_F[l];
      t.strain_energy += r.strain_energy[l];
      t.hourglass_energy += r.hourglass_energy[l];
      if (!(r.det_F[l] > 0.0) && t.inverted_element < 0) t.inverted_element = e;
      if (!plastic) continue;
      data.plastic_step[e] = r.yielded[l];
      if (r.yielded[l]) {
        data.next_plastic_strain[e] = r.update[l].plastic_strain;
        data.next_alpha[e] = r.update[l].alpha;
        data.next_plastic_work[e] =
            state.plastic_work[e] + r.update[l].plastic_work * model.batches[b].volume[l];
        t.plastic_work += data.next_plastic_work[e];
      } else {
        t.plastic_work += state.plastic_work[e];
      }
    }
    data.batch_totals[b] = t;
  }
  // node loop: gather in ascending element order
  const double* force = data.batch_force.empty() ? nullptr : data.batch_force[0].f[0][0];
#pragma omp parallel for num_threads(model.threads) schedule(static)
  for (int n = 0; n < n_nodes; ++n) {
    double fx = 0.0, fy = 0.0, fz = 0.0;
    for (int k = model.incidence_start[n]; k < model.incidence_start[n + 1]; ++k) {
      const double* f = force + model.incidence[k];
      fx += f[0];
      fy += f[kBatchLanes];
      fz += f[2 * kBatchLanes];
    }
    data.internal_force[n] = Eigen::Vector3d(fx, fy, fz);
  }
  // serial sums in batch order (deterministic) and the inversion check
  data.status = SolidStatus::kOk;
  data.inverted_element = -1;
  double strain = 0.0, hourglass = 0.0, plastic_work = 0.0;
  for (int b = 0; b < n_batches; ++b) {
    const SolidBatchTotals& t = data.batch_totals[b];
    strain += t.strain_energy;
    hourglass += t.hourglass_energy;
    plastic_work += t.plastic_work;
    if (t.inverted_element >= 0 && data.inverted_element < 0) {
      data.status = SolidStatus::kInverted;
      data.inverted_element = t.inverted_element;
    }
  }
  data.total_strain_energy = strain + hourglass;
  data.total_hourglass_energy = hourglass;
  data.total_plastic_work = plastic_work;
}

SolidStatus step_solid(const SolidModel& model, SolidState& state, SolidData& data, double dt) {
  // stresses and internal forces at x(n)
  calc_solid_forces(model, state, data);
  if (data.status != SolidStatus::kOk) return data.status;
  update_solid_nodes(model, state, data, dt);
  return SolidStatus::kOk;
}

void update_solid_nodes(const SolidModel& model, SolidState& state, SolidData& data, double dt) {
  // central-difference update of the nodes; kinetic energy at t(n) from the mean of the
  // half-step velocities
  const int n_nodes = model.num_nodes(), n_el = model.num_elements();
  const double c = 0.5 * dt * model.damping_alpha;
#pragma omp parallel for num_threads(model.threads) schedule(static)
  for (int n = 0; n < n_nodes; ++n) {
    const Eigen::Vector3d v_old = state.velocity[n];
    Eigen::Vector3d v = ((1.0 - c) * v_old + dt * model.inverse_mass[n] *
                                                 (data.external_force[n] - data.internal_force[n])) /
                        (1.0 + c);
    if (data.friction_viscosity[n] > 0.0) {
      // friction implicit: (I + a P)(v_new - v_body) = v - v_body with P the tangential
      // projector, solved by (I + a P)^-1 = I - a / (1 + a) P
      const double a = dt * model.inverse_mass[n] * data.friction_viscosity[n];
      const Eigen::Vector3d& nb = data.friction_normal[n];
      const Eigen::Vector3d rel = v - data.friction_body_velocity[n];
      v -= (a / (1.0 + a)) * (rel - rel.dot(nb) * nb);
    }
    const uint8_t fixed = model.constraint[n];
    for (int i = 0; i < 3; ++i) {
      if (fixed & (1u << i)) v[i] = data.prescribed_velocity[n][i];
    }
    state.velocity[n] = v;
    state.position[n] += dt * v;
    data.nodal_kinetic_energy[n] = 0.125 * model.nodal_mass[n] * (v + v_old).squaredNorm();
  }
  // commit the plastic state the forces were computed with, where it changed
  if (model.material.kind == SolidMaterialKind::kJ2Plastic) {
#pragma omp parallel for num_threads(model.threads) schedule(static)
    for (int e = 0; e < n_el; ++e) {
      if (!data.plastic_step[e]) continue;
      state.plastic_strain[e] = data.next_plastic_strain[e];
      state.alpha[e] = data.next_alpha[e];
      state.plastic_work[e] = data.next_plastic_work[e];
    }
  }
  double kinetic = 0.0;
  for (int n = 0; n < n_nodes; ++n) kinetic += data.nodal_kinetic_energy[n];
  data.kinetic_energy = kinetic;
}

}  // namespace kneesim::engine::solid
