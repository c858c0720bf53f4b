#include "models/deformable_insert.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/contact_law.h"
#include "engine/errors.h"
#include "engine/solid/solid_build.h"
#include "models/contact_footprint.h"
#include "models/hex_mesh.h"

namespace kneesim::models {
namespace {

// growth of the footprint spacing per element away from the refined zone: a gentle grading
// (a jump in element size reflects stress waves and stiffens the transition)
constexpr double kRefinedGrowth = 1.3;
// growth of the layer thickness per layer down from the surface (layers = 0)
constexpr double kLayerGrowth = 1.5;
// the narrowest patches: this percentile of the loaded frames' patch widths
constexpr double kPatchPercentile = 0.1;

}  // namespace

std::pair<int, double> find_graded_layers(double height, double top, double growth) {
  if (!(height > 0.0) || !(top > 0.0) || top >= height) return {1, 1.0};
  // the fewest layers whose thicknesses, top, top * growth, ..., reach the height
  const int layers = std::clamp(
      static_cast<int>(std::ceil(std::log1p(height * (growth - 1.0) / top) / std::log(growth))),
      2, 40);
  // the ratio r (each layer r times the one below) that makes the top layer exactly `top`:
  // top(r) = height r^(L-1) (1 - r) / (1 - r^L) grows with r; bisection
  auto top_of = [&](double r) {
    return r >= 1.0 ? height / layers
                    : height * std::pow(r, layers - 1) * (1.0 - r) / (1.0 - std::pow(r, layers));
  };
  if (top_of(1.0) <= top) return {layers, 1.0};
  double a = 1e-6, b = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double r = 0.5 * (a + b);
    (top_of(r) < top ? a : b) = r;
  }
  return {layers, std::pow(0.5 * (a + b), layers - 1)};
}

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
  DeformableMeshReport& report = built.deformable_mesh;
  report = {};
  const bool adaptive = c.deformable_elements_across_contact > 0;
  const bool zone = c.deformable_refine == "contact";
  if (adaptive || zone || c.deformable_layers == 0) {
    // the cycle's contact, found with the law as specified (not the config's calibrated law),
    // so the mesh is the same whatever rigid law the config names
    const double k_specified = engine::foundation_modulus(c.material.elastic_modulus_MPa * 1e6,
                                                          c.material.poisson);
    ContactFootprint f;
    try {
      f = find_contact_footprint(m, k_specified, c.dt_safety, c.deformable_refine_margin_mm * 1e-3);
    } catch (const std::runtime_error& e) {
      throw InputError(where + ": the deformable insert's mesh follows the contact of a rigid "
                       "cycle (deformable.refine, elements_across_contact, layers = 0), and " +
                       e.what() + "; give deformable.refine = \"none\", "
                       "elements_across_contact = 0 and layers > 0 for a mesh of fixed size");
    }
    report.patch_width_x = find_percentile(f.width_x, kPatchPercentile);
    report.patch_width_z = find_percentile(f.width_z, kPatchPercentile);
    if (adaptive) {
      const double lo = c.deformable_min_element_size_mm * 1e-3, hi = options.element_size;
      const double n = c.deformable_elements_across_contact;
      options.element_size = std::clamp(report.patch_width_x / n, std::min(lo, hi), hi);
      options.element_size_z = std::clamp(report.patch_width_z / n, std::min(lo, hi), hi);
    }
    if (zone) {
      options.outer_element_size = c.deformable_outer_element_size_mm * 1e-3;
      options.growth = kRefinedGrowth;
      options.refine_x = f.x;
      options.refine_z = f.z;
      built.refined_x = f.x;
      built.refined_z = f.z;
    }
    if (c.deformable_layers == 0) {
      const double top = std::min(options.element_size,
                                  options.element_size_z > 0.0 ? options.element_size_z
                                                               : options.element_size);
      const auto [layers, grading] = find_graded_layers(f.layer_thickness, top, kLayerGrowth);
      options.layers = layers;
      options.grading = grading;
    }
    report.layer_thickness = f.layer_thickness;
  }
  report.element_size_x = options.element_size;
  report.element_size_z = options.element_size_z > 0.0 ? options.element_size_z : options.element_size;
  report.layers = options.layers;
  report.grading = options.grading;
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
  built.refined_contact_node.clear();
  report.elements = static_cast<int>(mesh.elements.size());
  if (!built.refined_x.empty()) {
    auto inside = [](const std::vector<Interval>& zone, double v) {
      for (const Interval& z : zone) {
        if (v >= z.lo && v <= z.hi) return true;
      }
      return false;
    };
    for (int node : m.insert_contact.nodes) {
      const Eigen::Vector3d& x = mesh.nodes[node];
      built.refined_contact_node.push_back(inside(built.refined_x, x.x()) &&
                                           inside(built.refined_z, x.z()));
    }
  }
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

namespace kneesim::models {
namespace {

// nodes per column of the structured insert mesh (base node first, top node last)
int column_nodes(const engine::Model& m) {
  const int n = m.insert_solid.num_nodes(), columns = static_cast<int>(m.insert_base_nodes.size());
  if (columns == 0 || n % columns != 0) {
    throw std::logic_error("deformable insert: the mesh is not made of whole columns");
  }
  return n / columns;
}

}  // namespace

std::vector<Eigen::Vector3d> calc_top_node_normals(const engine::Model& m,
                                                   const std::vector<Eigen::Vector3d>& x) {
  const engine::solid::SurfaceContact& c = m.insert_contact;
  std::vector<Eigen::Vector3d> by_node(x.size(), Eigen::Vector3d::Zero());
  for (const auto& q : m.insert_top_faces) {
    // the quad's area-weighted normal: half the cross product of its diagonals
    const Eigen::Vector3d n = 0.5 * (x[q[2]] - x[q[0]]).cross(x[q[3]] - x[q[1]]);
    for (int a = 0; a < 4; ++a) by_node[q[a]] += n;
  }
  std::vector<Eigen::Vector3d> normal(c.size());
  for (int i = 0; i < c.size(); ++i) {
    const Eigen::Vector3d& n = by_node[c.nodes[i]];
    normal[i] = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitY();
  }
  return normal;
}

std::vector<Eigen::Vector3d> recede_insert_columns(const engine::Model& pristine,
                                                   const std::vector<Eigen::Vector3d>& nodes,
                                                   const std::vector<Eigen::Vector3d>& normal,
                                                   const std::vector<double>& depth) {
  const engine::solid::SurfaceContact& c = pristine.insert_contact;
  const std::vector<Eigen::Vector3d>& X0 = pristine.insert_solid.reference_positions;
  const int per_column = column_nodes(pristine);
  std::vector<Eigen::Vector3d> out = nodes;
  for (int i = 0; i < c.size(); ++i) {
    const int top = c.nodes[i], base = top - (per_column - 1);
    const Eigen::Vector3d new_top = nodes[top] - depth[i] * normal[i];
    const double h0 = X0[top].y() - X0[base].y();
    for (int k = base + 1; k < top; ++k) {
      const double s = (X0[k].y() - X0[base].y()) / h0;  // pristine layer fraction
      out[k] = nodes[base] + s * (new_top - nodes[base]);
    }
    out[top] = new_top;
  }
  return out;
}

int count_collapsed_elements(const engine::Model& pristine, const std::vector<Eigen::Vector3d>& x) {
  const engine::solid::SolidModel& s = pristine.insert_solid;
  int bad = 0;
  for (int e = 0; e < s.num_elements(); ++e) {
    engine::solid::HexPoints p;
    for (int a = 0; a < engine::solid::kHexNodes; ++a) p[a] = x[s.elements[e][a]];
    const auto j = engine::solid::calc_corner_jacobians(p);
    if (*std::min_element(j.begin(), j.end()) <= 0.01 * s.reference[e].min_jacobian) ++bad;
  }
  return bad;
}

double calc_hex_volume(const engine::Model& m, const std::vector<Eigen::Vector3d>& x) {
  // V = int det J over the element: the 2x2x2 Gauss rule is exact for the trilinear hex
  const engine::solid::SolidModel& s = m.insert_solid;
  const double g = 1.0 / std::sqrt(3.0);
  double volume = 0.0;
  for (int e = 0; e < s.num_elements(); ++e) {
    for (int q = 0; q < engine::solid::kHexNodes; ++q) {
      const auto& xi = engine::solid::kHexNatural[q];
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int a = 0; a < engine::solid::kHexNodes; ++a) {
        const auto& na = engine::solid::kHexNatural[a];
        const double r = 1 + na[0] * g * xi[0], t = 1 + na[1] * g * xi[1],
                     u = 1 + na[2] * g * xi[2];
        const Eigen::Vector3d dN(0.125 * na[0] * t * u, 0.125 * na[1] * r * u,
                                 0.125 * na[2] * r * t);
        J += x[s.elements[e][a]] * dN.transpose();
      }
      volume += J.determinant();
    }
  }
  return volume;
}

void apply_worn_deformable_insert(const engine::Model& pristine, double dt_safety,
                                  const std::vector<Eigen::Vector3d>& worn,
                                  engine::Model& m, engine::State* state) {
  const engine::solid::SolidModel& s0 = pristine.insert_solid;
  engine::solid::SolidOptions options;
  // every element of a mass-scaled insert was raised to the target step, so the pristine
  // limit is the target; an unscaled insert keeps its physical mass
  options.mass_scaling_dt = s0.added_mass > 0.0 ? s0.dt_critical : 0.0;
  options.damping_alpha = s0.damping_alpha;
  options.threads = s0.threads;
  const std::vector<Eigen::Vector3d> before = m.insert_solid.reference_positions;
  m.insert_solid = engine::solid::make_solid_model(worn, s0.elements, s0.material, options,
                                                   s0.constraint);
  m.insert_contact = engine::solid::make_surface_contact(
      m.insert_solid, pristine.insert_top_faces, pristine.insert_top_face_element,
      pristine.insert_contact.friction, pristine.insert_contact.slip_regularization);
  // the scaled limit reproduces the target to rounding: shorten the step only for more
  const double dt_solid = dt_safety * m.insert_solid.dt_critical;
  if (dt_solid < m.dt * (1.0 - 1e-9)) {
    const long steps = static_cast<long>(std::ceil(m.period / dt_solid));
    m.dt = m.period / steps;
  }
  m.dt_critical = std::min(pristine.dt_critical, m.insert_solid.dt_critical);
  // the displacement field carries over onto the worn reference
  if (!state) return;
  for (size_t n = 0; n < worn.size(); ++n) {
    state->insert_solid.position[n] = worn[n] + (state->insert_solid.position[n] - before[n]);
  }
}

}  // namespace kneesim::models
