#include "analysis/run/solid_outputs.h"

#include <algorithm>
#include <cmath>

#include "engine/io/vtp.h"
#include "engine/io/vtu.h"
#include "engine/solid/energy_ratio.h"
#include "engine/step.h"

namespace kneesim::run {

// the share of the first cycle of a run from rest left out of the energy ratio's
// max_after_settling: the femur settles in about 3 ms (0.3 % of a 1 s cycle) on the DM and
// built-in implants; 1 % leaves a margin of three
constexpr double kSettlingShare = 0.01;

SolidCycleTracker::SolidCycleTracker(const engine::Model& model)
    : von_mises_max(model.insert_solid.num_elements(), 0.0),
      normal_force_sum(model.insert_contact.size(), 0.0) {
  const long steps = std::lround(model.period / model.dt) + 2;
  kinetic.reserve(steps);
  internal.reserve(steps);
}

void SolidCycleTracker::observe(const engine::Data& data) {
  const engine::solid::SolidData& sd = data.insert_solid;
  const int n = static_cast<int>(von_mises_max.size());
  for (int e = 0; e < n; ++e) von_mises_max[e] = std::max(von_mises_max[e], sd.von_mises[e]);
  const std::vector<Eigen::Vector3d>& force = data.insert_contact.force;
  // only the nodes in contact (the others' force is zero; skipping them, not the sum, saves
  // a square root per top node and step on the run's serial path)
  for (size_t i = 0; i < normal_force_sum.size(); ++i) {
    const double squared = force[i].squaredNorm();  // norm() is the root of the same sum
    if (squared > 0.0) normal_force_sum[i] += std::sqrt(squared);
  }
  kinetic.push_back(sd.kinetic_energy);
  internal.push_back(sd.total_strain_energy + sd.total_plastic_work);
}

double calc_share_outside_zone(const SolidCycleTracker& tracker,
                               const std::vector<unsigned char>& refined_node) {
  double outside = 0.0, total = 0.0;
  for (size_t i = 0; i < tracker.normal_force_sum.size() && i < refined_node.size(); ++i) {
    total += tracker.normal_force_sum[i];
    if (!refined_node[i]) outside += tracker.normal_force_sum[i];
  }
  return total > 0.0 ? outside / total : 0.0;
}

nlohmann::json describe_solid_model(const engine::Model& model) {
  const engine::solid::SolidModel& solid = model.insert_solid;
  nlohmann::json j;
  j["insert"] = "deformable";
  j["solid_elements"] = solid.num_elements();
  j["solid_nodes"] = solid.num_nodes();
  j["solid_surface_nodes"] = model.insert_contact.size();
  j["solid_dt_critical_s"] = solid.dt_critical;
  j["solid_mass_kg"] = solid.physical_mass;
  j["solid_added_mass_kg"] = solid.added_mass;
  j["solid_damping_per_s"] = solid.damping_alpha;
  return j;
}

nlohmann::json describe_solid_cycle(const engine::Model& model, const engine::State& state,
                                    const SolidCycleTracker& tracker) {
  const engine::solid::SolidModel& solid = model.insert_solid;
  const int n_el = solid.num_elements();
  std::vector<unsigned char> surface(n_el, 0);
  for (int e : model.insert_top_face_element) surface[e] = 1;
  double vm_surface = 0.0, vm_sub = 0.0, ep_surface = 0.0, ep_sub = 0.0;
  for (int e = 0; e < n_el; ++e) {
    const double vm = tracker.von_mises_max[e], ep = state.insert_solid.alpha[e];
    if (surface[e]) {
      vm_surface = std::max(vm_surface, vm);
      ep_surface = std::max(ep_surface, ep);
    } else {
      vm_sub = std::max(vm_sub, vm);
      ep_sub = std::max(ep_sub, ep);
    }
  }
  const size_t settling_steps =
      tracker.from_rest ? static_cast<size_t>(std::lround(kSettlingShare * model.period / model.dt))
                        : 0;
  const engine::solid::EnergyRatio energy =
      engine::solid::calc_energy_ratio(tracker.kinetic, tracker.internal, settling_steps);
  nlohmann::json j = describe_solid_model(model);
  j["von_mises_max_surface_MPa"] = vm_surface * 1e-6;
  j["von_mises_max_subsurface_MPa"] = vm_sub * 1e-6;
  j["plastic_strain_max_surface"] = ep_surface;
  j["plastic_strain_max_subsurface"] = ep_sub;
  j["kinetic_to_internal_max"] = energy.max;
  j["kinetic_to_internal_cycle"] = energy.cycle;
  j["kinetic_to_internal_max_after_settling"] = energy.max_after_settling;
  j["settling_s"] = settling_steps * model.dt;
  return j;
}

namespace {

// the top surface at the reference nodes (quads split in two) with one value per node (top
// nodes in model.insert_contact order, 0 elsewhere) and, per face, the von Mises maximum and
// plastic strain of the element under it
io::VtpSurface make_top_surface(const engine::Model& model, const char* name,
                                const std::vector<double>& top_node_values,
                                const engine::State& state,
                                const std::vector<double>& von_mises_max_Pa) {
  const engine::solid::SolidModel& solid = model.insert_solid;
  io::VtpSurface s;
  for (const auto& x : solid.reference_positions) s.points_mm.push_back(x * 1e3);
  io::VtpArray p{name, std::vector<double>(solid.num_nodes(), 0.0)};
  for (int i = 0; i < model.insert_contact.size(); ++i) {
    p.values[model.insert_contact.nodes[i]] = top_node_values[i];
  }
  s.point_data.push_back(std::move(p));
  io::VtpArray vm{"von_mises_max_MPa", {}}, ep{"plastic_strain", {}};
  for (size_t f = 0; f < model.insert_top_faces.size(); ++f) {
    const auto& q = model.insert_top_faces[f];
    s.triangles.emplace_back(q[0], q[1], q[2]);
    s.triangles.emplace_back(q[0], q[2], q[3]);
    const int e = model.insert_top_face_element[f];
    for (int k = 0; k < 2; ++k) {
      vm.values.push_back(von_mises_max_Pa[e] * 1e-6);
      ep.values.push_back(state.insert_solid.alpha[e]);
    }
  }
  s.cell_data.push_back(std::move(vm));
  s.cell_data.push_back(std::move(ep));
  return s;
}

std::vector<double> scaled(const std::vector<double>& v, double factor) {
  std::vector<double> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) out[i] = v[i] * factor;
  return out;
}

}  // namespace

void write_solid_pressure_map(const std::filesystem::path& path, const engine::Model& model,
                              const std::vector<double>& node_pressure_Pa,
                              const engine::State& state, const SolidCycleTracker& tracker) {
  io::write_vtp(path, make_top_surface(model, "pressure_MPa", scaled(node_pressure_Pa, 1e-6),
                                       state, tracker.von_mises_max));
}

void write_solid_stress_vtu(const std::filesystem::path& path, const engine::Model& model,
                            const engine::State& state, const engine::Data& data,
                            const SolidCycleTracker& tracker) {
  const engine::solid::SolidModel& solid = model.insert_solid;
  io::VtuHexMesh m;
  for (const auto& x : state.insert_solid.position) m.points_mm.push_back(x * 1e3);
  m.hexes = solid.elements;
  io::VtpArray vm_max{"von_mises_max_MPa", {}}, vm{"von_mises_MPa", {}}, ep{"plastic_strain", {}};
  for (int e = 0; e < solid.num_elements(); ++e) {
    vm_max.values.push_back(tracker.von_mises_max[e] * 1e-6);
    vm.values.push_back(data.insert_solid.von_mises[e] * 1e-6);
    ep.values.push_back(state.insert_solid.alpha[e]);
  }
  m.cell_data = {std::move(vm_max), std::move(vm), std::move(ep)};
  io::write_vtu(path, m);
}

void write_solid_wear_outputs(const std::filesystem::path& out, const engine::Model& model,
                              const engine::State& state,
                              const std::vector<double>& von_mises_max_Pa,
                              const std::vector<double>& depth) {
  SolidCycleTracker tracker(model);
  tracker.von_mises_max = von_mises_max_Pa;
  engine::Data data = engine::make_data(model);
  engine::calc_forces(model, state, data);  // the stresses at the state
  write_solid_stress_vtu(out / "insert_stress.vtu", model, state, data, tracker);

  io::write_vtp(out / "wear_surface.vtp", make_top_surface(model, "wear_depth_mm",
                                                           scaled(depth, 1e3), state,
                                                           von_mises_max_Pa));
}

}  // namespace kneesim::run
