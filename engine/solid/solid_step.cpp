#include "engine/solid/solid_step.h"

#include <Eigen/LU>
#include <algorithm>
#include <bit>

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

void run_element_loop(const SolidModel& model, const SolidState& state, SolidData& data,
                      bool element_fields) {
  const int n_el = model.num_elements();
  const bool plastic = model.material.kind == SolidMaterialKind::kJ2Plastic;
  double* node_force = data.internal_force.empty() ? nullptr : data.internal_force[0].data();
  double* slot_force = data.slot_force.data();
  auto task = [&](int r) {
    // the nodes this range sums in place start from zero
    for (int k = model.range_interior_start[r]; k < model.range_interior_start[r + 1]; ++k) {
      data.internal_force[model.range_interior[k]].setZero();
    }
    // one result block for the range's batches (every batch writes what it reads back; built
    // per batch, its eight StressUpdates were initialized every time)
    Hex8BatchResult res;
    for (int b = model.range_batch[r]; b < model.range_batch[r + 1]; ++b) {
      const int e0 = b * kBatchLanes, count = std::min(kBatchLanes, n_el - e0);
      calc_hex8_batch_scatter(model.batches[b], model.material, state.position.data(),
                              plastic ? &state.plastic_strain[e0] : nullptr,
                              plastic ? &state.alpha[e0] : nullptr, count, node_force,
                              slot_force, res);
      SolidBatchTotals t;
      for (int l = 0; l < count; ++l) {
        const int e = e0 + l;
        data.von_mises[e] = res.von_mises[l];
        t.strain_energy += res.strain_energy[l];
        t.hourglass_energy += res.hourglass_energy[l];
        if (!(res.det_F[l] > 0.0) && t.inverted_element < 0) t.inverted_element = e;
        if (element_fields) {
          for (int v = 0; v < 6; ++v) data.stress[e][v] = res.stress[v][l];
          data.strain_energy[e] = res.strain_energy[l];
          data.hourglass_energy[e] = res.hourglass_energy[l];
          data.jacobian_ratio[e] = res.det_F[l];
        }
        if (!plastic) continue;
        if (res.yielded[l]) {
          t.yielded_lanes |= 1u << l;
          data.next_plastic_strain[e] = res.update[l].plastic_strain;
          data.next_alpha[e] = res.update[l].alpha;
          data.next_plastic_work[e] =
              state.plastic_work[e] + res.update[l].plastic_work * model.batches[b].volume[l];
          t.plastic_work += data.next_plastic_work[e];
        } else {
          t.plastic_work += state.plastic_work[e];
        }
      }
      data.batch_totals[b] = t;
    }
  };
  for_each_range(model, data, task);
  // serial sums in batch order (deterministic) and the inversion check
  data.status = SolidStatus::kOk;
  data.inverted_element = -1;
  double strain = 0.0, hourglass = 0.0, plastic_work = 0.0;
  for (const SolidBatchTotals& t : data.batch_totals) {
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

void commit_plastic_state(const SolidModel& model, SolidState& state, const SolidData& data,
                          int b0, int b1) {
  if (model.material.kind != SolidMaterialKind::kJ2Plastic) return;
  for (int b = b0; b < b1; ++b) {
    for (uint32_t lanes = data.batch_totals[b].yielded_lanes; lanes; lanes &= lanes - 1) {
      const int e = b * kBatchLanes + std::countr_zero(lanes);
      state.plastic_strain[e] = data.next_plastic_strain[e];
      state.alpha[e] = data.next_alpha[e];
      state.plastic_work[e] = data.next_plastic_work[e];
    }
  }
}

void calc_solid_forces(const SolidModel& model, const SolidState& state, SolidData& data) {
  run_element_loop(model, state, data, true);
  auto nothing = [](int) { return 0.0; };
  run_node_loop(model, nullptr, data, nothing);
}

SolidStatus step_solid(const SolidModel& model, SolidState& state, SolidData& data, double dt) {
  // stresses and internal forces at x(n); an inverted element stops the step before any node
  // moves
  run_element_loop(model, state, data, false);
  if (data.status != SolidStatus::kOk) return data.status;
  const double c = 0.5 * dt * model.damping_alpha;
  // the update inlined into the node loop (gcc 12 left it a call per node: bench_solid on 2
  // threads 64.6-65.3 M updates/s with the call, 67.9-70.3 inlined, three alternating runs)
  auto advance = [&](int n) __attribute__((always_inline)) {
    return advance_node_inlined(model, state, data, n, dt, c);
  };
  run_node_loop(model, &state, data, advance);
  return SolidStatus::kOk;
}

}  // namespace kneesim::engine::solid
