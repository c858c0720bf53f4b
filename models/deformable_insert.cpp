#include "models/deformable_insert.h"

#include <cmath>

#include "engine/errors.h"
#include "engine/solid/solid_build.h"
#include "models/hex_mesh.h"

namespace kneesim::models {

engine::solid::SolidMaterial make_insert_solid_material(const Config& c) {
  engine::solid::SolidMaterial m;
  const MaterialConfig& mat = c.material;
  m.kind = c.deformable_material == "elastic" ? engine::solid::SolidMaterialKind::kElastic
                                              : engine::solid::SolidMaterialKind::kJ2Plastic;
  m.youngs_modulus = mat.elastic_modulus_MPa * 1e6;
  m.poisson = mat.poisson;
  m.density = mat.density_g_per_cm3 * 1e3;
  m.yield_stress = mat.yield_MPa * 1e6;
  m.hardening_modulus = c.deformable_hardening_MPa * 1e6;
  m.yield_cap = c.deformable_yield_cap_MPa * 1e6;
  return m;
}

void attach_deformable_insert(const Config& c, BuiltModel& built) {
  engine::Model& m = built.model;
  const std::string where = c.file.empty() ? std::string("built-in config") : c.file.string();
  if (m.integrator != engine::IntegratorKind::kCentralDifference) {
    throw InputError(where + ": insert = \"deformable\" runs with solver.integrator = "
                     "\"central_difference\" only (got \"" + c.integrator + "\")");
  }
  InsertMeshOptions options;
  options.element_size = c.deformable_element_size_mm * 1e-3;
  options.layers = c.deformable_layers;
  options.grading = c.deformable_grading;
  HexMesh mesh;
  try {
    mesh = make_insert_hex_mesh(built.implant.insert, 0.0, options);
  } catch (const InputError& e) {
    throw InputError(where + ": deformable.element_size_mm / layers / grading: " + e.what());
  }
  std::vector<uint8_t> constraint(mesh.nodes.size(), 0);
  for (int b : mesh.base_nodes) constraint[b] = engine::solid::kFixAll;
  engine::solid::SolidOptions solid_options;
  // the step taken is dt_safety times the solid's limit: scale the mass so that it is dt_us
  solid_options.mass_scaling_dt = c.deformable_dt_us * 1e-6 / c.dt_safety;
  solid_options.damping_alpha = c.deformable_damping_per_s;
  solid_options.threads = c.threads;
  try {
    m.insert_solid = engine::solid::make_solid_model(mesh.nodes, mesh.elements,
                                                     make_insert_solid_material(c),
                                                     solid_options, constraint);
  } catch (const InputError& e) {
    throw InputError(where + ": insert = \"deformable\" with material \"" + c.material.name +
                     "\": " + e.what());
  }
  const double friction =
      c.friction_override >= 0.0 ? c.friction_override : c.material.friction;
  m.insert_contact = engine::solid::make_surface_contact(
      m.insert_solid, mesh.top_faces, mesh.top_face_element, friction,
      c.friction_regularization_mm_per_s * 1e-3);
  m.insert_base_nodes = mesh.base_nodes;
  std::sort(m.insert_base_nodes.begin(), m.insert_base_nodes.end());
  m.insert_top_faces = mesh.top_faces;
  m.insert_top_face_element = mesh.top_face_element;

  // one global step: the smaller of the rigid rig's and the solid's, a whole number per cycle
  const double dt_solid = c.dt_safety * m.insert_solid.dt_critical;
  if (dt_solid < m.dt) {
    const long steps = static_cast<long>(std::ceil(m.period / dt_solid));
    m.dt = m.period / steps;
  }
  m.dt_critical = std::min(m.dt_critical, m.insert_solid.dt_critical);
}

}  // namespace kneesim::models
