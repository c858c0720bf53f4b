// Contact of the hex8 solid's surface against rigid bodies (engine/solid/surface_contact.h).
// References: a rigid cylinder pressed into a thick elastic block against Hertz line contact
// (plane strain; half-width b = sqrt(4 P' R / (pi E*)), peak p0 = 2 P' / (pi b), E* = E /
// (1 - nu^2); within 5 %), and a rigid flat punch on a thin layer bonded to a rigid base
// against the confined-layer solution p = K d / h, K = (1 - nu) E / ((1 + nu)(1 - 2 nu)) (the
// layer under a punch 20 h wide is in uniaxial strain away from the punch edges; within 3 %
// at the centre). The penalty does not lower the stable step (the run is stable at the solid's
// own step), and the friction kernel is the regularized Coulomb law.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/solid/surface_contact.h"
#include "solid_fixtures.h"

using namespace kneesim;
using namespace kneesim::engine::solid;

namespace {

// plane strain: every node fixed in z; the base (y = min) fixed completely
std::vector<uint8_t> plane_strain_on_rigid_base(const models::HexMesh& mesh) {
  std::vector<uint8_t> fix(mesh.nodes.size(), kFixZ);
  for (int n : mesh.base_nodes) fix[n] = kFixAll;
  return fix;
}

struct Indentation {
  double force_per_length = 0.0;  // P' [N/m]
  double half_width = 0.0;        // from the second moment of the nodal forces [m]
  double peak_pressure = 0.0;     // [Pa]
  double centre_pressure = 0.0;   // at the node nearest x = 0 [Pa]
  double kinetic_ratio = 0.0;     // kinetic / strain energy at the end [-]
};

// presses a rigid body down by `depth` over the first half of `steps`, holds it, returns the
// contact measures; `body(p, offset)` samples the body lowered by offset
template <class Body>
Indentation indent(const models::HexMesh& mesh, const SolidModel& model, double width_z,
                   double depth, int steps, const Body& body) {
  SolidState state = make_solid_state(model);
  SolidData data = make_solid_data(model);
  const SurfaceContact contact = make_surface_contact(model, mesh.top_faces, mesh.top_face_element, 0.0, 1e-3);
  SurfaceContactData out = make_surface_contact_data(contact);
  const double dt = 0.8 * model.dt_critical;
  for (int s = 0; s < steps; ++s) {
    const double ramp = std::min(1.0, 2.0 * s / steps);
    const double offset = depth * 0.5 * (1.0 - std::cos(M_PI * ramp));
    for (auto& f : data.external_force) f.setZero();
    apply_surface_contact(model, contact, state, data, out,
                          [&](const Eigen::Vector3d& p) { return body(p, offset); });
    REQUIRE(step_solid(model, state, data, dt) == SolidStatus::kOk);
  }
  Indentation r;
  double f = 0.0, fx2 = 0.0, nearest = INFINITY;
  for (int i = 0; i < contact.size(); ++i) {
    const Eigen::Vector3d& x = state.position[contact.nodes[i]];
    const double fy = -out.force[i].y();  // the load the body carries, upwards
    f += fy;
    fx2 += fy * x.x() * x.x();
    r.peak_pressure = std::max(r.peak_pressure, out.pressure[i]);
    if (std::abs(x.x()) < nearest) {
      nearest = std::abs(x.x());
      r.centre_pressure = out.pressure[i];
    }
  }
  r.force_per_length = f / width_z;
  r.half_width = 2.0 * std::sqrt(fx2 / f);  // Hertz: int p x^2 / int p = b^2 / 4
  r.kinetic_ratio = data.kinetic_energy / data.total_strain_energy;
  return r;
}

}  // namespace

TEST_CASE("contact: rigid cylinder on a thick elastic block matches Hertz line contact") {
  // the block-on-ring's ring (R 17.5 mm) on its UHMWPE block (E 690 MPa, nu 0.317), 12 mm
  // deep and 18 mm long: b / depth = 0.07, close to the half-space; mesh 0.06 mm under the
  // contact, growing by 1.25 per element away from it
  const double R = 0.0175, E = 690e6, nu = 0.317, w = 5e-4;
  const auto xs = models::make_graded_lines(-0.009, 0.009, 0.0, 0.0014, 6e-5, 1.25);
  const auto ys = models::make_graded_lines(-0.012, 0.0, 0.0, 0.0010, 6e-5, 1.25);
  const models::HexMesh mesh = models::make_graded_box_hex_mesh(xs, ys, {0.0, w});
  SolidOptions options;
  options.damping_alpha = 2e5;  // about the block's lowest compression mode, pi c / (2 depth)
  const SolidModel model = make_solid_model(mesh.nodes, mesh.elements, test::make_elastic(E, nu, 945.0),
                                            options, plane_strain_on_rigid_base(mesh));
  auto cylinder = [R](const Eigen::Vector3d& p, double offset) {
    const Eigen::Vector2d c(0.0, R - offset);
    const Eigen::Vector2d d = Eigen::Vector2d(p.x(), p.y()) - c;
    RigidSample s;
    s.phi = d.norm() - R;
    s.normal = Eigen::Vector3d(d.x(), d.y(), 0.0) / d.norm();
    return s;
  };
  const Indentation r = indent(mesh, model, w, 4e-5, 6000, cylinder);
  const double Estar = E / (1.0 - nu * nu);
  const double b = std::sqrt(4.0 * r.force_per_length * R / (M_PI * Estar));
  const double p0 = 2.0 * r.force_per_length / (M_PI * b);
  MESSAGE("Hertz: " << model.num_elements() << " elements, P' " << r.force_per_length * 1e-3
          << " N/mm; b " << r.half_width * 1e3 << " mm vs " << b * 1e3 << " mm; p0 "
          << r.peak_pressure * 1e-6 << " MPa vs " << p0 * 1e-6 << " MPa; kinetic/strain "
          << r.kinetic_ratio);
  CHECK(r.half_width == doctest::Approx(b).epsilon(0.05).scale(0));
  CHECK(r.peak_pressure == doctest::Approx(p0).epsilon(0.05));
  CHECK(b > 10.0 * 6e-5);  // the contact is resolved: ten or more elements per half-width
  CHECK(r.kinetic_ratio < 1e-3);
}

TEST_CASE("contact: rigid flat punch on a thin bonded layer matches the confined-layer solution") {
  const double E = 690e6, nu = 0.3, h = 0.001, a = 0.010, d = 1e-5, w = 5e-4;
  const models::HexMesh mesh =
      models::make_box_hex_mesh(160, 4, 1, Eigen::Vector3d(0.04, h, w), Eigen::Vector3d(-0.02, 0, 0));
  SolidOptions options;
  options.damping_alpha = 5e4;
  const SolidModel model = make_solid_model(mesh.nodes, mesh.elements, test::make_elastic(E, nu, 945.0),
                                            options, plane_strain_on_rigid_base(mesh));
  auto punch = [h, a](const Eigen::Vector3d& p, double offset) {
    RigidSample s;  // the punch's flat face at y = h - offset over |x| <= a
    s.phi = std::abs(p.x()) <= a + 1e-12 ? (h - offset) - p.y() : INFINITY;
    s.normal = -Eigen::Vector3d::UnitY();
    return s;
  };
  const Indentation r = indent(mesh, model, w, d, 4000, punch);
  const double K = (1.0 - nu) * E / ((1.0 + nu) * (1.0 - 2.0 * nu));
  MESSAGE("flat punch: centre pressure " << r.centre_pressure * 1e-6 << " MPa vs K d / h = "
          << K * d / h * 1e-6 << " MPa");
  // the penalty layer (as compliant as one surface element) shares the punch depth: its
  // compliance L_top / K against the layer's h / K is one quarter here, so compare with the
  // penetration the penalty leaves, p = K (d - p L_top / K) / h, i.e. p = K d / (h + L_top)
  const double L_top = h / 4;
  CHECK(r.centre_pressure == doctest::Approx(K * d / (h + L_top)).epsilon(0.03));
  CHECK(r.kinetic_ratio < 1e-3);
}

TEST_CASE("contact kernel: penalty pressure and regularized Coulomb friction") {
  RigidSample s;
  s.phi = -2e-6;
  s.normal = Eigen::Vector3d(0, 1, 0);
  s.velocity = Eigen::Vector3d(0.01, 0, 0);
  double p = 0, slip = 0, c = 0;
  const Eigen::Vector3d f = calc_node_contact_force(s, Eigen::Vector3d(0.0, -0.3, 0.0), 1e7, 1e-6,
                                                    0.07, 5e-3, p, slip, c);
  CHECK(f.y() == doctest::Approx(20.0));       // k (-phi) along the normal
  CHECK(p == doctest::Approx(20.0 / 1e-6));    // over the tributary area
  CHECK(slip == doctest::Approx(0.01).scale(0));  // tangential only: the normal velocity drops out
  // viscosity times slip is mu f_n |v| / sqrt(|v|^2 + eps^2)
  CHECK(c * slip == doctest::Approx(0.07 * 20.0 * 0.01 / std::sqrt(1e-4 + 25e-6)));
  s.phi = 1e-6;
  CHECK(calc_node_contact_force(s, Eigen::Vector3d::Zero(), 1e7, 1e-6, 0.07, 5e-3, p, slip, c).norm() == 0.0);
  CHECK(c == 0.0);
}
