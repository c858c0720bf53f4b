// The batched hex8 kernel (engine/solid/hex8_batch.h) against the one-element kernel
// calc_hex8_response (hex8.h, solid_step.h). Reference: the batch evaluates the same element
// with rearranged algebra (the hourglass terms through hX and G instead of the FB vectors), so
// forces, stress and energies agree to rounding: 1e-11 of the largest nodal force (a few
// hundred operations of relative rounding 1e-16 on terms of that size), and the plastic state
// agrees where the trial stress is beyond yield. The baseline (SSE2), AVX2 and AVX-512 builds
// of the kernel do the same IEEE operations in the same order, so they agree bit for bit, and
// the scattering form adds each element's forces into the nodes in ascending element order,
// so the nodes get bit for bit the sums of the batch buffers taken in that order.
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

// 4 x 3 x 1 distorted elements (12: one full batch and one padded), deformed by a rotation,
// a homogeneous strain of `strain` and a random nodal perturbation (hourglass modes)
Case make_case(const SolidMaterial& mat, double strain, bool plastic_history) {
  const Eigen::Vector3d size(0.006, 0.004, 0.002);
  test::BoxMesh mesh = test::make_box(4, 3, 1, size, Eigen::Vector3d(0.01, -0.02, 0.005));
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

TEST_CASE("hex8 batch kernel: baseline, AVX2 and AVX-512 builds agree bit for bit") {
  const SolidMaterial mat = test::make_uhmwpe_plastic();
  int compared = 0;
  for (Hex8Isa isa : {Hex8Isa::kAvx2, Hex8Isa::kAvx512}) {
    if (!hex8_batch_supports(isa)) continue;  // nothing to compare on this CPU
    CAPTURE(to_string(isa));
    for (double strain : {2e-3, 5e-2}) {
      const Case c = make_case(mat, strain, true);
      for (int b = 0; b < c.model.num_batches(); ++b) {
        const int e0 = b * kBatchLanes, count = std::min(kBatchLanes, c.model.num_elements() - e0);
        Hex8BatchForce f1, f2;
        Hex8BatchResult r1, r2;
        calc_hex8_batch(c.model.batches[b], mat, c.x.data(), &c.plastic_strain[e0],
                        &c.alpha[e0], count, f1, r1, Hex8Isa::kBaseline);
        calc_hex8_batch(c.model.batches[b], mat, c.x.data(), &c.plastic_strain[e0],
                        &c.alpha[e0], count, f2, r2, isa);
        // the lanes that hold elements (the padding lanes' outputs are never read; the 4-lane
        // paths do not compute an empty half)
        const auto same = [count](const double* a, const double* b) {
          return std::memcmp(a, b, sizeof(double) * count) == 0;
        };
        for (int a = 0; a < kHexNodes; ++a)
          for (int i = 0; i < 3; ++i) CHECK(same(f1.f[a][i], f2.f[a][i]));
        for (int v = 0; v < 6; ++v) CHECK(same(r1.stress[v], r2.stress[v]));
        CHECK(same(r1.von_mises, r2.von_mises));
        CHECK(same(r1.strain_energy, r2.strain_energy));
        CHECK(same(r1.hourglass_energy, r2.hourglass_energy));
        CHECK(same(r1.det_F, r2.det_F));
        for (int l = 0; l < count; ++l) {
          CHECK(r1.yielded[l] == r2.yielded[l]);
          if (r1.yielded[l]) {
            CHECK(std::memcmp(&r1.update[l], &r2.update[l], sizeof r1.update[l]) == 0);
          }
        }
        ++compared;
      }
    }
  }
  MESSAGE("batches compared with the baseline build: ", compared);
}

TEST_CASE("hex8 batch kernel: the scattering form sums into the nodes in element order") {
  // reference: the batch buffers summed per node in ascending element order from 0.0 (the
  // gather loop the scatter replaces), compared bit for bit; the shared-node slots get each
  // element's force itself
  const SolidMaterial mat = test::make_uhmwpe_plastic();
  Case c = make_case(mat, 5e-2, true);
  const SolidModel& model = c.model;
  const int ne = model.num_elements(), nn = model.num_nodes();
  std::vector<double> expected(3 * nn, 0.0);
  std::vector<std::array<double, 3>> element_force(ne * kHexNodes);
  for (int b = 0; b < model.num_batches(); ++b) {
    const int e0 = b * kBatchLanes, count = std::min(kBatchLanes, ne - e0);
    Hex8BatchForce f;
    Hex8BatchResult r;
    calc_hex8_batch(model.batches[b], mat, c.x.data(), &c.plastic_strain[e0], &c.alpha[e0],
                    count, f, r);
    for (int l = 0; l < count; ++l)
      for (int a = 0; a < kHexNodes; ++a)
        element_force[(e0 + l) * kHexNodes + a] = {f.f[a][0][l], f.f[a][1][l], f.f[a][2][l]};
  }
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < kHexNodes; ++a)
      for (int i = 0; i < 3; ++i)
        expected[3 * model.elements[e][a] + i] += element_force[e * kHexNodes + a][i];
  // every node of element 5 goes to a slot of its own (numbered 10 + a), the rest in place
  std::vector<Hex8Batch> batches = model.batches;
  for (int a = 0; a < kHexNodes; ++a) batches[0].scatter[a][5] = ~(10 + a);
  // on every path the CPU has (the AVX-512 one scatters by its own transpose); the nodes are
  // 4 doubles (x, y, z, 0)
  std::vector<std::vector<double>> node_forces;
  for (const Hex8Isa isa : {Hex8Isa::kBaseline, Hex8Isa::kAvx2, Hex8Isa::kAvx512}) {
    if (!hex8_batch_supports(isa)) continue;
    std::vector<double> node_force(4 * nn, 0.0), slots(3 * 20, -1.0);
    for (int b = 0; b < model.num_batches(); ++b) {
      const int e0 = b * kBatchLanes, count = std::min(kBatchLanes, ne - e0);
      Hex8BatchResult r;
      calc_hex8_batch_scatter(batches[b], mat, c.x.data(), &c.plastic_strain[e0], &c.alpha[e0],
                              count, node_force.data(), slots.data(), r, isa);
    }
    for (int a = 0; a < kHexNodes; ++a)
      for (int i = 0; i < 3; ++i)
        CHECK(slots[3 * (10 + a) + i] == element_force[5 * kHexNodes + a][i]);
    for (int n = 0; n < nn; ++n) CHECK(node_force[4 * n + 3] == 0.0);  // the pad stays zero
    node_forces.push_back(node_force);
  }
  MESSAGE("scatter paths compared: ", node_forces.size());
  for (int a = 0; a < kHexNodes; ++a)
    for (int i = 0; i < 3; ++i) expected[3 * model.elements[5][a] + i] = 0.0;  // below, without element 5
  // the nodes of element 5 summed without it, in element order
  std::vector<double> without(3 * nn, 0.0);
  for (int e = 0; e < ne; ++e) {
    if (e == 5) continue;
    for (int a = 0; a < kHexNodes; ++a)
      for (int i = 0; i < 3; ++i)
        without[3 * model.elements[e][a] + i] += element_force[e * kHexNodes + a][i];
  }
  for (int a = 0; a < kHexNodes; ++a)
    for (int i = 0; i < 3; ++i) {
      const int k = 3 * model.elements[5][a] + i;
      expected[k] = without[k];
    }
  for (const std::vector<double>& node_force : node_forces) {
    std::vector<double> xyz(3 * nn);
    for (int n = 0; n < nn; ++n)
      for (int i = 0; i < 3; ++i) xyz[3 * n + i] = node_force[4 * n + i];
    CHECK(std::memcmp(xyz.data(), expected.data(), expected.size() * sizeof(double)) == 0);
  }
}
