// The batched hex8 kernel (engine/solid/hex8_batch.h) against the one-element kernel
// calc_hex8_response (hex8.h, solid_step.h). Reference: the batch evaluates the same element
// with rearranged algebra (the hourglass terms through hX and G instead of the FB vectors), so
// forces, stress and energies agree to rounding: 1e-11 of the largest nodal force (a few
// hundred operations of relative rounding 1e-16 on terms of that size), and the plastic state
// agrees where the trial stress is beyond yield. The baseline (SSE2) and AVX2 builds of the
// kernel do the same IEEE operations in the same order, so they agree bit for bit.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cstring>
#include <random>

#include "solid_fixtures.h"

using namespace kneesim;
using namespace kneesim::engine::solid;

namespace {

struct Case {
  SolidModel model;
  std::vector<Eigen::Vector3d> x;  // deformed positions
  std::vector<Sym6> plastic_strain;
  std::vector<double> alpha;
};

// 3 x 2 x 1 distorted elements (6: one full batch and one padded), deformed by a rotation,
// a homogeneous strain of `strain` and a random nodal perturbation (hourglass modes)
Case make_case(const SolidMaterial& mat, double strain, bool plastic_history) {
  const Eigen::Vector3d size(0.006, 0.004, 0.002);
  test::BoxMesh mesh = test::make_box(3, 2, 1, size, Eigen::Vector3d(0.01, -0.02, 0.005));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& n : mesh.nodes) n += 0.2e-3 * Eigen::Vector3d(u(rng), u(rng), u(rng));
  Case c{make_solid_model(mesh.nodes, mesh.elements, mat, {}), {}, {}, {}};
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  A(0, 0) += strain;
  A(1, 1) -= 0.4 * strain;
  A(0, 1) += 0.3 * strain;
  for (const auto& X : mesh.nodes)
    c.x.push_back(R * A * X + 1e-3 * strain * Eigen::Vector3d(u(rng), u(rng), u(rng)));
  const int ne = c.model.num_elements();
  c.plastic_strain.assign(ne, Sym6::Zero());
  c.alpha.assign(ne, 0.0);
  if (plastic_history) {
    for (int e = 0; e < ne; e += 2) {  // every other element has yielded before
      for (int v = 0; v < 6; ++v) c.plastic_strain[e][v] = 0.3 * strain * u(rng);
      c.alpha[e] = 0.5 * strain;
    }
  }
  return c;
}

void check_against_scalar(const Case& c, const SolidMaterial& mat) {
  const SolidModel& model = c.model;
  const int ne = model.num_elements();
  for (int b = 0; b < model.num_batches(); ++b) {
    const int e0 = b * kBatchLanes, count = std::min(kBatchLanes, ne - e0);
    Hex8BatchForce force;
    Hex8BatchResult r;
    calc_hex8_batch(model.batches[b], mat, c.x.data(), &c.plastic_strain[e0], &c.alpha[e0], count,
                    force, r);
    for (int l = 0; l < count; ++l) {
      const int e = e0 + l;
      HexPoints x;
      for (int a = 0; a < kHexNodes; ++a) x[a] = c.x[model.elements[e][a]];
      Hex8Response s;
      calc_hex8_response(model.reference[e], mat, x, c.plastic_strain[e], c.alpha[e], s);
      double scale = 0.0;
      for (const auto& f : s.force) scale = std::max(scale, f.norm());
      REQUIRE(scale > 0.0);
      for (int a = 0; a < kHexNodes; ++a) {
        const Eigen::Vector3d f(force.f[a][0][l], force.f[a][1][l], force.f[a][2][l]);
        CHECK((f - s.force[a]).norm() <= 1e-11 * scale);
      }
      Sym6 stress;
      for (int v = 0; v < 6; ++v) stress[v] = r.stress[v][l];
      CHECK((stress - s.update.stress).norm() <= 1e-11 * s.update.stress.norm());
      CHECK(r.von_mises[l] == doctest::Approx(calc_von_mises(s.update.stress)).epsilon(1e-11));
      CHECK(r.det_F[l] == doctest::Approx(s.det_F).epsilon(1e-13));
      CHECK(r.strain_energy[l] == doctest::Approx(s.strain_energy).epsilon(1e-10).scale(0));
      CHECK(r.hourglass_energy[l] == doctest::Approx(s.hourglass_energy).epsilon(1e-8).scale(0));
      const bool yielded = s.update.alpha != c.alpha[e];
      CHECK(r.yielded[l] == yielded);
      if (yielded) {
        CHECK(r.update[l].alpha == doctest::Approx(s.update.alpha).epsilon(1e-10).scale(0));
        CHECK((r.update[l].plastic_strain - s.update.plastic_strain).norm() <=
              1e-10 * s.update.plastic_strain.norm());
      }
    }
  }
}

}  // namespace

TEST_CASE("hex8 batch kernel matches the one-element kernel: elastic material") {
  const SolidMaterial mat = test::make_elastic(685e6, 0.47, 935.0);
  check_against_scalar(make_case(mat, 2e-3, false), mat);
}

TEST_CASE("hex8 batch kernel matches the one-element kernel: J2, below and beyond yield") {
  const SolidMaterial mat = test::make_uhmwpe_plastic();
  // 0.2 % strain stays elastic (about 1.4 MPa of 17), 5 % yields; with and without history
  for (double strain : {2e-3, 5e-2}) {
    for (bool history : {false, true}) {
      CAPTURE(strain);
      CAPTURE(history);
      const Case c = make_case(mat, strain, history);
      check_against_scalar(c, mat);
    }
  }
  // the yielding case does yield somewhere (the test covers the radial return lanes)
  const Case c = make_case(mat, 5e-2, false);
  Hex8BatchForce force;
  Hex8BatchResult r;
  calc_hex8_batch(c.model.batches[0], mat, c.x.data(), c.plastic_strain.data(), c.alpha.data(),
                  kBatchLanes, force, r);
  CHECK(r.yielded[0]);
}

TEST_CASE("hex8 batch kernel: baseline and AVX2 builds agree bit for bit") {
  if (!hex8_batch_has_avx2()) return;  // nothing to compare on this CPU
  const SolidMaterial mat = test::make_uhmwpe_plastic();
  for (double strain : {2e-3, 5e-2}) {
    const Case c = make_case(mat, strain, true);
    for (int b = 0; b < c.model.num_batches(); ++b) {
      const int e0 = b * kBatchLanes, count = std::min(kBatchLanes, c.model.num_elements() - e0);
      Hex8BatchForce f1, f2;
      Hex8BatchResult r1, r2;
      calc_hex8_batch_baseline(c.model.batches[b], mat, c.x.data(), &c.plastic_strain[e0],
                               &c.alpha[e0], count, f1, r1);
      calc_hex8_batch_avx2(c.model.batches[b], mat, c.x.data(), &c.plastic_strain[e0],
                           &c.alpha[e0], count, f2, r2);
      CHECK(std::memcmp(f1.f, f2.f, sizeof f1.f) == 0);
      CHECK(std::memcmp(r1.stress, r2.stress, sizeof r1.stress) == 0);
      CHECK(std::memcmp(r1.strain_energy, r2.strain_energy, sizeof r1.strain_energy) == 0);
      CHECK(std::memcmp(r1.hourglass_energy, r2.hourglass_energy, sizeof r1.hourglass_energy) == 0);
      CHECK(std::memcmp(r1.det_F, r2.det_F, sizeof r1.det_F) == 0);
    }
  }
}
