#include "engine/solid/solid_build.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace kneesim::engine::solid {
namespace {

// a range of fewer batches does not pay for the thread that takes it (the team's loop costs a
// few microseconds, 64 batches of 8 elements about 20)
constexpr int kMinRangeBatches = 64;

std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

void cut_solid_ranges(SolidModel& model, int ranges) {
  const int n_nodes = model.num_nodes(), n_el = model.num_elements();
  const int n_batches = model.num_batches();
  std::vector<int> elements_of_node(n_nodes, 0);
  for (const auto& element : model.elements)
    for (int n : element) ++elements_of_node[n];
  model.ranges = std::clamp(std::min(ranges, n_batches), 1, WorkTeam::kMaxTasks);
  const int R = model.ranges;
  model.range_batch.resize(R + 1);
  for (int r = 0; r <= R; ++r) {
    model.range_batch[r] = static_cast<int>(static_cast<long>(n_batches) * r / R);
  }
  std::vector<int> range_of_batch(n_batches);
  for (int r = 0; r < R; ++r) {
    for (int b = model.range_batch[r]; b < model.range_batch[r + 1]; ++b) range_of_batch[b] = r;
  }
  // each node's lowest and highest element (elements ascend, so the first and last seen)
  std::vector<int> first(n_nodes, -1), last(n_nodes, -1);
  for (int e = 0; e < n_el; ++e) {
    for (int n : model.elements[e]) {
      if (first[n] < 0) first[n] = e;
      last[n] = e;
    }
  }
  const auto range_of = [&](int e) { return range_of_batch[e / kBatchLanes]; };
  // interior nodes, by range; slots of the shared nodes
  std::vector<uint8_t> shared(n_nodes, 0);
  std::vector<std::vector<int>> interior(R);
  model.slot_start.assign(n_nodes + 1, 0);
  for (int n = 0; n < n_nodes; ++n) {
    int slots = 0;
    if (first[n] >= 0) {
      if (range_of(first[n]) == range_of(last[n])) {
        interior[range_of(first[n])].push_back(n);
      } else {
        shared[n] = 1;
        slots = elements_of_node[n];
      }
    }
    model.slot_start[n + 1] = model.slot_start[n] + slots;
  }
  model.num_slots = model.slot_start[n_nodes];
  model.range_interior_start.assign(R + 1, 0);
  model.range_interior.clear();
  for (int r = 0; r < R; ++r) {
    model.range_interior.insert(model.range_interior.end(), interior[r].begin(), interior[r].end());
    model.range_interior_start[r + 1] = static_cast<int>(model.range_interior.size());
  }
  std::vector<int> fill(model.slot_start.begin(), model.slot_start.end() - 1);
  for (int e = 0; e < n_el; ++e) {
    Hex8Batch& batch = model.batches[e / kBatchLanes];
    for (int a = 0; a < kHexNodes; ++a) {
      const int n = model.elements[e][a];
      batch.scatter[a][e % kBatchLanes] = shared[n] ? ~fill[n]++ : n;
    }
  }
  // node ranges on kNodeBlock boundaries, cut where the node loop's work is shared evenly: a
  // node costs kNodeWork and each of its slots one more (bench_solid, 2 threads: with every
  // shared node's slot sums in the range of its first element, that range's node loop took
  // 25 us against the other's 19; a node's update about four slot additions). Interior nodes
  // then mostly fall in the range whose elements sum them (their forces in its cache)
  constexpr long kNodeWork = 4;
  const long total = kNodeWork * n_nodes + model.num_slots;
  model.range_node.assign(R + 1, 0);
  model.range_node[R] = n_nodes;
  long work = 0;
  for (int n = 0, r = 1; n < n_nodes && r < R; ++n) {
    work += kNodeWork + (model.slot_start[n + 1] - model.slot_start[n]);
    while (r < R && work >= total * r / R) {
      const int at = std::min(n_nodes, (n + 1 + kNodeBlock / 2) / kNodeBlock * kNodeBlock);
      model.range_node[r] = std::max(model.range_node[r - 1], at);
      ++r;
    }
  }
}

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
  model.threads = resolve_thread_count(options.threads);
  const int n_nodes = model.num_nodes(), n_el = model.num_elements();
  model.constraint = constraint.empty() ? std::vector<uint8_t>(n_nodes, 0) : std::move(constraint);
  if (static_cast<int>(model.constraint.size()) != n_nodes) {
    throw InputError("solid mesh: " + std::to_string(model.constraint.size()) +
                          " constraint flags for " + std::to_string(n_nodes) + " nodes");
  }

  model.reference.resize(n_el);
  model.nodal_mass.assign(n_nodes, 0.0);
  model.dt_critical = INFINITY;
  for (int e = 0; e < n_el; ++e) {
    HexPoints X;
    for (int a = 0; a < kHexNodes; ++a) {
      const int n = model.elements[e][a];
      if (n < 0 || n >= n_nodes) {
        throw InputError("solid mesh: element " + std::to_string(e) + " names node " +
                              std::to_string(n) + ", outside 0.." + std::to_string(n_nodes - 1));
      }
      X[a] = model.reference_positions[n];
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

  cut_solid_ranges(model, std::min(model.threads, model.num_batches() / kMinRangeBatches));
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
  d.batch_totals.resize(model.num_batches());
  d.internal_force.assign(nn, Eigen::Vector4d::Zero());
  d.slot_force.assign(3 * static_cast<size_t>(model.num_slots), 0.0);
  d.von_mises.assign(ne, 0.0);
  d.stress.assign(ne, Sym6::Zero());
  d.strain_energy.assign(ne, 0.0);
  d.hourglass_energy.assign(ne, 0.0);
  d.jacobian_ratio.assign(ne, 1.0);
  d.next_plastic_strain.assign(ne, Sym6::Zero());
  d.next_alpha.assign(ne, 0.0);
  d.next_plastic_work.assign(ne, 0.0);
  d.block_kinetic_energy.assign((nn + kNodeBlock - 1) / kNodeBlock, 0.0);
  d.team = SolidTeam(std::min(model.threads, model.ranges));
  return d;
}

}  // namespace kneesim::engine::solid
