// hex8 element and material kernels alone (engine/solid). References: the patch test (a
// linear displacement field reproduced exactly on a distorted mesh: every interior node in
// equilibrium), rigid-body invariance (zero internal force), lumped mass = rho V, the
// dilatational-wave step h / c of a regular element, and the J2 radial return against the
// closed-form uniaxial response (yield at sigma_y0, tangent E H / (E + H), flat at the cap).
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "solid_fixtures.h"

using namespace kneesim;
using namespace kneesim::engine::solid;

namespace {

const Eigen::Vector3d kSize(0.012, 0.010, 0.008);  // a 12 x 10 x 8 mm block [m]

SolidModel distorted_block(const SolidMaterial& mat) {
  test::BoxMesh mesh = test::make_box(3, 3, 3, kSize);
  test::distort_interior(mesh, 0.3, kSize);
  return make_solid_model(mesh.nodes, mesh.elements, mat, {});
}

double max_force(const SolidData& d) {
  double m = 0.0;
  for (const auto& f : d.internal_force) m = std::max(m, f.norm());
  return m;
}

}  // namespace

TEST_CASE("hex8 patch test: a constant strain field is reproduced exactly on a distorted mesh") {
  const SolidMaterial mat = test::make_elastic(685e6, 0.47, 935.0);
  const SolidModel model = distorted_block(mat);
  SolidState state = make_solid_state(model);
  SolidData data = make_solid_data(model);
  // a general linear field x = A X + c: stretch, shear and a rotation part, 0.2 % strain
  Eigen::Matrix3d A;
  A << 1.002, 0.0007, -0.0004, 0.0003, 0.9985, 0.0009, -0.0006, 0.0002, 1.0011;
  const Eigen::Vector3d c(1e-3, -2e-3, 5e-4);
  for (int n = 0; n < model.num_nodes(); ++n) state.position[n] = A * model.reference_positions[n] + c;
  calc_solid_forces(model, state, data);
  // every element carries the stress of the exact field
  const Eigen::Matrix3d E = 0.5 * (A.transpose() * A - Eigen::Matrix3d::Identity());
  const Sym6 S = calc_stress(mat, to_voigt(E), Sym6::Zero(), 0.0).stress;
  for (int e = 0; e < model.num_elements(); ++e) {
    CHECK((data.stress[e] - S).norm() <= 1e-9 * S.norm());
    CHECK(data.hourglass_energy[e] <= 1e-12 * data.strain_energy[e]);
  }
  // interior nodes are in equilibrium: the residual is rounding against the nodal force scale
  const double scale = max_force(data);
  test::BoxMesh mesh = test::make_box(3, 3, 3, kSize);
  for (int k = 1; k < 3; ++k)
    for (int j = 1; j < 3; ++j)
      for (int i = 1; i < 3; ++i) {
        CHECK(data.internal_force[mesh.node(i, j, k)].norm() <= 1e-10 * scale);
      }
  CHECK(scale > 0.0);
}

TEST_CASE("hex8 rigid-body translation and rotation give zero internal force") {
  SolidMaterial mat = test::make_uhmwpe_plastic();
  const SolidModel model = distorted_block(mat);
  SolidState state = make_solid_state(model);
  SolidData data = make_solid_data(model);
  // a large rotation (40 deg about a skew axis) and a translation
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(40.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.03, -0.01, 0.02);
  for (int n = 0; n < model.num_nodes(); ++n) state.position[n] = R * model.reference_positions[n] + t;
  calc_solid_forces(model, state, data);
  // force scale of a 0.1 % strain on an element face: E * 1e-3 * h^2
  const double scale = mat.youngs_modulus * 1e-3 * 0.004 * 0.004;
  CHECK(max_force(data) <= 1e-9 * scale);
  CHECK(data.total_strain_energy <= 1e-18);
  for (int e = 0; e < model.num_elements(); ++e) CHECK(data.next_alpha[e] == 0.0);
}

TEST_CASE("hex8 lumped mass sums to rho V on a distorted mesh") {
  const SolidMaterial mat = test::make_elastic(3500e6, 0.30, 1300.0);
  const SolidModel model = distorted_block(mat);
  double sum = 0.0, volume = 0.0;
  for (double m : model.nodal_mass) sum += m;
  for (const auto& r : model.reference) volume += r.volume;
  const double exact = mat.density * kSize.prod();  // interior distortion keeps the box volume
  CHECK(volume == doctest::Approx(kSize.prod()).epsilon(1e-12).scale(0));
  CHECK(sum == doctest::Approx(exact).epsilon(1e-12).scale(0));
  CHECK(model.physical_mass == doctest::Approx(exact).epsilon(1e-12).scale(0));
  CHECK(model.added_mass == 0.0);
}

TEST_CASE("hex8 stable step of a regular element is the dilatational-wave estimate h / c") {
  const SolidMaterial mat = test::make_elastic(685e6, 0.47, 935.0);
  const double h = 0.002;
  const test::BoxMesh mesh = test::make_box(1, 1, 1, Eigen::Vector3d(h, h, h));
  const SolidModel model = make_solid_model(mesh.nodes, mesh.elements, mat, {});
  // c = sqrt((lambda + 2 mu) / rho), lambda + 2 mu = (1 - nu) E / ((1 + nu)(1 - 2 nu))
  const double M = (1 - 0.47) * 685e6 / ((1 + 0.47) * (1 - 2 * 0.47));
  CHECK(model.dt_critical == doctest::Approx(h / std::sqrt(M / 935.0)).epsilon(1e-12).scale(0));
  // a flat element (h x h x h/4): the shortest dimension governs
  const test::BoxMesh flat = test::make_box(1, 1, 1, Eigen::Vector3d(h, h, h / 4));
  const SolidModel fm = make_solid_model(flat.nodes, flat.elements, mat, {});
  CHECK(fm.dt_critical == doctest::Approx(h / 4 / std::sqrt(M / 935.0)).epsilon(1e-12).scale(0));
}

TEST_CASE("hex8 mass scaling raises the stable step to the target and reports the added mass") {
  const SolidMaterial mat = test::make_elastic(685e6, 0.47, 935.0);
  const Eigen::Vector3d size(0.004, 0.004, 0.002);
  const test::BoxMesh mesh = test::make_box(2, 2, 2, size);
  SolidOptions options;
  const SolidModel plain = make_solid_model(mesh.nodes, mesh.elements, mat, options);
  options.mass_scaling_dt = 2.0 * plain.dt_critical;
  const SolidModel scaled = make_solid_model(mesh.nodes, mesh.elements, mat, options);
  CHECK(scaled.dt_critical == doctest::Approx(options.mass_scaling_dt).epsilon(1e-12).scale(0));
  // dt ~ sqrt(rho): doubling dt quadruples the density, adding three times the mass
  CHECK(scaled.added_mass == doctest::Approx(3.0 * plain.physical_mass).epsilon(1e-12).scale(0));
}

TEST_CASE("J2 radial return in uniaxial stress: yield at sigma_y0, hardening slope, cap") {
  const SolidMaterial mat = test::make_uhmwpe_plastic();
  const double E = mat.youngs_modulus, H = mat.hardening_modulus;
  // drive eps_xx in small increments; the lateral strains are solved (secant iterations)
  // so that sigma_yy = sigma_zz = 0, as in a tension bar
  Sym6 ep = Sym6::Zero();
  double alpha = 0.0, lateral = 0.0, previous_stress = 0.0, previous_strain = 0.0;
  double first_yield_stress = -1.0;
  const double d_eps = 2e-5;
  for (int i = 1; i <= 30000; ++i) {
    const double exx = i * d_eps;
    StressUpdate u;
    for (int it = 0; it < 50; ++it) {
      Sym6 strain = Sym6::Zero();
      strain << exx, lateral, lateral, 0, 0, 0;
      u = calc_stress(mat, strain, ep, alpha);
      if (std::abs(u.stress[1]) < 1e-9 * E * d_eps) break;
      // d sigma_yy / d lateral is at least the elastic 2 (lambda + mu) minus plastic coupling;
      // the elastic value converges monotonically (a contraction)
      lateral -= u.stress[1] / (2.0 * (mat.lame_lambda() + mat.shear_modulus()));
    }
    const double s = u.stress[0];
    if (first_yield_stress < 0.0 && u.alpha > 0.0) {
      first_yield_stress = previous_stress;
      // the first plastic increment starts within one elastic increment of sigma_y0
      CHECK(previous_stress <= mat.yield_stress);
      CHECK(previous_stress >= mat.yield_stress - E * d_eps);
    }
    const double alpha_before = alpha;
    ep = u.plastic_strain;
    alpha = u.alpha;
    // hardening branch, well inside it: tangent E H / (E + H)
    if (alpha_before > 0.02 && alpha < 0.25) {
      const double slope = (s - previous_stress) / (exx - previous_strain);
      CHECK(slope == doctest::Approx(E * H / (E + H)).epsilon(1e-6));
      // on the yield surface: the von Mises stress is the current yield stress
      CHECK(calc_von_mises(u.stress) == doctest::Approx(calc_yield_stress(mat, alpha)).epsilon(1e-9));
    }
    // beyond 0.32 plastic strain: flat at the cap
    if (alpha_before > 0.33) CHECK(s == doctest::Approx(mat.yield_cap).epsilon(1e-9));
    previous_stress = s;
    previous_strain = exx;
  }
  CHECK(first_yield_stress > 0.0);
  CHECK(alpha > 0.33);
}

TEST_CASE("J2 elastic unloading after yield keeps the plastic strain") {
  const SolidMaterial mat = test::make_uhmwpe_plastic();
  Sym6 strain = Sym6::Zero();
  strain[3] = 0.03;  // simple shear beyond yield (von Mises sqrt(3) 2 mu 0.03 = 24 MPa)
  const StressUpdate loaded = calc_stress(mat, strain, Sym6::Zero(), 0.0);
  CHECK(loaded.alpha > 0.0);
  CHECK(loaded.plastic_work > 0.0);
  strain[3] = 0.029;
  const StressUpdate unloaded = calc_stress(mat, strain, loaded.plastic_strain, loaded.alpha);
  CHECK(unloaded.alpha == loaded.alpha);
  CHECK(unloaded.plastic_work == 0.0);
  CHECK(unloaded.stress[3] == doctest::Approx(loaded.stress[3] - 2 * mat.shear_modulus() * 0.001));
}

TEST_CASE("solid input errors name the element or field, the value and the allowed range") {
  const test::BoxMesh mesh = test::make_box(2, 1, 1, Eigen::Vector3d(0.002, 0.001, 0.001));
  SolidMaterial mat = test::make_elastic(685e6, 0.5, 935.0);
  CHECK_THROWS_WITH_AS(make_solid_model(mesh.nodes, mesh.elements, mat, {}),
                       doctest::Contains("Poisson ratio 0.5 is out of range (0 <= nu < 0.5"),
                       InputError);
  mat.poisson = 0.3;
  auto inverted = mesh.elements;
  std::swap(inverted[1][0], inverted[1][4]);  // a face turned inside out
  std::swap(inverted[1][1], inverted[1][5]);
  std::swap(inverted[1][2], inverted[1][6]);
  std::swap(inverted[1][3], inverted[1][7]);
  CHECK_THROWS_WITH_AS(make_solid_model(mesh.nodes, inverted, mat, {}),
                       doctest::Contains("element 1 is inverted or degenerate"), InputError);
}
