// Outputs of a run with the deformable insert (insert = "deformable"): the per-element maxima
// of von Mises stress over the last cycle and the equivalent plastic strain it ends with,
// split into the surface layer (elements under the top surface) and the subsurface; the
// kinetic/internal energy ratio of the cycle (quasi-static validity, below 5 %); the top
// surface with node pressures (.vtp) and the whole hex mesh with its element fields (.vtu).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::run {

// fed by the run's per-step observer over the last cycle; sized once, no allocation per step
struct SolidCycleTracker {
  std::vector<double> von_mises_max;  // per element, max over the observed steps [Pa]
  std::vector<double> kinetic;        // solid kinetic energy per observed step [J]
  std::vector<double> internal;       // elastic + hourglass + plastic work [J]
  std::vector<double> normal_force_sum;  // per top contact node, sum of |normal force| over
                                         // the observed steps [N] (an impulse / dt)
  // the observed cycle begins at t = 0 from rest (a one-cycle run): its first 1 % is the
  // femur's settling onto the insert (engine/solid/energy_ratio.h)
  bool from_rest = false;
  explicit SolidCycleTracker(const engine::Model& model);
  void observe(const engine::Data& data);
};

// the share of the observed contact impulse carried by top nodes outside the refined zone
// (refined_node: per model.insert_contact node, 1 inside; models/contact_footprint.h)
double calc_share_outside_zone(const SolidCycleTracker& tracker,
                               const std::vector<unsigned char>& refined_node);

// summary fields of the solid itself: element and node counts, mass and mass scaling, damping
nlohmann::json describe_solid_model(const engine::Model& model);

// summary fields: element and node counts, mass scaling, stress and plastic-strain maxima
// (surface and subsurface), and the energy ratio
nlohmann::json describe_solid_cycle(const engine::Model& model, const engine::State& state,
                                    const SolidCycleTracker& tracker);

// the top surface (triangulated quads of the reference mesh) with the node pressure of one
// frame (pressure_MPa) and, per face, the element's von Mises maximum and plastic strain
void write_solid_pressure_map(const std::filesystem::path& path, const engine::Model& model,
                              const std::vector<double>& node_pressure_Pa,
                              const engine::State& state, const SolidCycleTracker& tracker);

// the hex mesh at the state's node positions with von_mises_max_MPa, plastic_strain and
// von_mises_MPa (at the state) per element
void write_solid_stress_vtu(const std::filesystem::path& path, const engine::Model& model,
                            const engine::State& state, const engine::Data& data,
                            const SolidCycleTracker& tracker);

// the outputs of a wear run on the deformable insert (kneesim wear): out/insert_stress.vtu, the
// worn hex mesh at the state with von_mises_max_MPa (over the last cycle), von_mises_MPa and
// plastic_strain per element, and out/wear_surface.vtp, the worn top surface (reference
// positions) with wear_depth_mm per node and the von Mises maximum and plastic strain of the
// element under each face; depth per top node (model.insert_contact order) [m]
void write_solid_wear_outputs(const std::filesystem::path& out, const engine::Model& model,
                              const engine::State& state,
                              const std::vector<double>& von_mises_max_Pa,
                              const std::vector<double>& depth);

}  // namespace kneesim::run
