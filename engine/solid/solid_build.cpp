#include "engine/solid/solid_build.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace kneesim::engine::solid {
namespace {

std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

void check_solid_material(const SolidMaterial& m) {
  if (!(m.youngs_modulus > 0.0)) {
    throw InputError("solid material: Young's modulus " + format(m.youngs_modulus) +
                          " Pa is out of range (must be > 0)");
  }
  if (!(m.poisson >= 0.0 && m.poisson < 0.5)) {
    throw InputError("solid material: Poisson ratio " + format(m.poisson) +
                          " is out of range (0 <= nu < 0.5; a solid at 0.5 is incompressible)");
  }
  if (!(m.density > 0.0)) {
    throw InputError("solid material: density " + format(m.density) +
                          " kg/m^3 is out of range (must be > 0)");
  }
  if (m.kind == SolidMaterialKind::kJ2Plastic &&
      !(m.yield_stress > 0.0 && m.hardening_modulus >= 0.0)) {
    throw InputError("solid material: yield stress " + format(m.yield_stress) +
                          " Pa and hardening modulus " + format(m.hardening_modulus) +
                          " Pa are out of range (yield > 0, hardening >= 0)");
  }
}

double calc_element_stable_step(const Hex8Reference& ref, const SolidMaterial& material,
                                double density) {
  return ref.characteristic_length / std::sqrt(material.dilatational_modulus() / density);
}

SolidModel make_solid_model(std::vector<Eigen::Vector3d> nodes,
                            std::vector<std::array<int, kHexNodes>> elements,
                            const SolidMaterial& material, const SolidOptions& options,
                            std::vector<uint8_t> constraint) {
  check_solid_material(material);
  SolidModel model;
  model.material = material;
  model.reference_positions = std::move(nodes);
  model.elements = std::move(elements);
  model.damping_alpha = options.damping_alpha;
  model.threads = std::max(1, options.threads);
  const int n_nodes = model.num_nodes(), n_el = model.num_elements();
  model.constraint = constraint.empty() ? std::vector<uint8_t>(n_nodes, 0) : std::move(constraint);
  if (static_cast<int>(model.constraint.size()) != n_nodes) {
    throw InputError("solid mesh: " + std::to_string(model.constraint.size()) +
                          " constraint flags for " + std::to_string(n_nodes) + " nodes");
  }

  model.reference.resize(n_el);
  model.nodal_mass.assign(n_nodes, 0.0);
  model.dt_critical = INFINITY;
  std::vector<int> count(n_nodes, 0);
  for (int e = 0; e < n_el; ++e) {
    HexPoints X;
    for (int a = 0; a < kHexNodes; ++a) {
      const int n = model.elements[e][a];
      if (n < 0 || n >= n_nodes) {
        throw InputError("solid mesh: element " + std::to_string(e) + " names node " +
                              std::to_string(n) + ", outside 0.." + std::to_string(n_nodes - 1));
      }
      X[a] = model.reference_positions[n];
      ++count[n];
    }
    const Hex8Reference& ref = model.reference[e] =
        make_hex8_reference(X, material.youngs_modulus, material.shear_modulus());
    if (!(ref.min_jacobian > 0.0)) {
      throw InputError("solid mesh: element " + std::to_string(e) +
                            " is inverted or degenerate in its reference configuration "
                            "(smallest corner Jacobian " + format(ref.min_jacobian) +
                            " m^3, must be > 0)");
    }
    // mass scaling: raise the density until the element's step reaches the target
    double density = material.density;
    const double dt_e = calc_element_stable_step(ref, material, density);
    if (options.mass_scaling_dt > dt_e) {
      density *= (options.mass_scaling_dt / dt_e) * (options.mass_scaling_dt / dt_e);
    }
    model.dt_critical = std::min(model.dt_critical, calc_element_stable_step(ref, material, density));
    model.physical_mass += material.density * ref.volume;
    model.added_mass += (density - material.density) * ref.volume;
    for (int a = 0; a < kHexNodes; ++a) {
      model.nodal_mass[model.elements[e][a]] += density * ref.volume / kHexNodes;
    }
  }
  model.inverse_mass.resize(n_nodes);
  for (int n = 0; n < n_nodes; ++n) {
    model.inverse_mass[n] = model.nodal_mass[n] > 0.0 ? 1.0 / model.nodal_mass[n] : 0.0;
  }

  // the element loop's batches
  const int n_batches = (n_el + kBatchLanes - 1) / kBatchLanes;
  model.batches.resize(n_batches);
  for (int b = 0; b < n_batches; ++b) {
    const int e0 = b * kBatchLanes;
    model.batches[b] = make_hex8_batch(&model.elements[e0], &model.reference[e0],
                                       std::min(kBatchLanes, n_el - e0),
                                       model.reference_positions.data());
  }

  // CSR incidence in ascending element order, as offsets into the batched force buffers
  model.incidence_start.assign(n_nodes + 1, 0);
  for (int n = 0; n < n_nodes; ++n) model.incidence_start[n + 1] = model.incidence_start[n] + count[n];
  model.incidence.resize(model.incidence_start[n_nodes]);
  std::vector<int> fill(model.incidence_start.begin(), model.incidence_start.end() - 1);
  constexpr int kBatchDoubles = sizeof(Hex8BatchForce) / sizeof(double);
  static_assert(kBatchDoubles == kHexNodes * 3 * kBatchLanes, "Hex8BatchForce is unpadded");
  for (int e = 0; e < n_el; ++e) {
    const int b = e / kBatchLanes, lane = e % kBatchLanes;
    for (int a = 0; a < kHexNodes; ++a) {
      model.incidence[fill[model.elements[e][a]]++] =
          b * kBatchDoubles + a * 3 * kBatchLanes + lane;
    }
  }
  return model;
}

SolidState make_solid_state(const SolidModel& model) {
  SolidState s;
  s.position = model.reference_positions;
  s.velocity.assign(model.num_nodes(), Eigen::Vector3d::Zero());
  s.plastic_strain.assign(model.num_elements(), Sym6::Zero());
  s.alpha.assign(model.num_elements(), 0.0);
  s.plastic_work.assign(model.num_elements(), 0.0);
  return s;
}

SolidData make_solid_data(const SolidModel& model) {
  SolidData d;
  const int nn = model.num_nodes(), ne = model.num_elements();
  d.external_force.assign(nn, Eigen::Vector3d::Zero());
  d.prescribed_velocity.assign(nn, Eigen::Vector3d::Zero());
  d.friction_viscosity.assign(nn, 0.0);
  d.friction_normal.assign(nn, Eigen::Vector3d::UnitY());
  d.friction_body_velocity.assign(nn, Eigen::Vector3d::Zero());
  d.batch_force.resize(model.num_batches());
  d.batch_totals.resize(model.num_batches());
  d.internal_force.assign(nn, Eigen::Vector3d::Zero());
  d.stress.assign(ne, Sym6::Zero());
  d.von_mises.assign(ne, 0.0);
  d.strain_energy.assign(ne, 0.0);
  d.hourglass_energy.assign(ne, 0.0);
  d.plastic_step.assign(ne, 0);
  d.next_plastic_strain.assign(ne, Sym6::Zero());
  d.next_alpha.assign(ne, 0.0);
  d.next_plastic_work.assign(ne, 0.0);
  d.jacobian_ratio.assign(ne, 1.0);
  d.nodal_kinetic_energy.assign(nn, 0.0);
  return d;
}

}  // namespace kneesim::engine::solid
