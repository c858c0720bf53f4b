// Wear on the deformable insert (issue 11 item 4): the geometry update of the hex mesh and the
// wear loop on it.
//  - kernels: on a flat box insert a uniform depth d lowers the top by d exactly, the hex
//    volume falls by d A (to rounding) and every column keeps its layer fractions; on the
//    knee insert a smooth 0.4 mm scar in each dish folds no element, and the hex volume loss
//    matches the depth integral (pristine tributary areas) within 1 % (the rigid path's
//    acceptance); the rebuilt model keeps the state's displacements, the mass-scaled step and
//    the time step;
//  - the loop on a coarse knee (3 mm elements, 0.2 s cycle, 1 Mc in 2 updates): volume
//    bookkeeping within 1 %, wear in both dishes, stresses reported; resume after an
//    interruption equals the uninterrupted run bit for bit (the checkpoint carries the solid's
//    nodes and plastic state).
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "engine/state.h"
#include "engine/step.h"
#include "models/build_model.h"
#include "models/deformable_insert.h"
#include "tests/loads/temp_dir.h"
#include "tests/wear/wear_fixtures.h"
#include "wear/archard.h"
#include "wear/checkpoint.h"
#include "wear/wear_loop.h"
#include "wear/worn_insert.h"

using namespace kneesim;
namespace fs = std::filesystem;

namespace {

// the coarse deformable knee: 2 mm implant, 3 mm elements in 3 layers, a 0.2 s gait cycle
models::Config deformable_config() {
  return test::coarse_config({{"insert", "\"deformable\""},
                              {"deformable.element_size_mm", "3"},
                              {"deformable.layers", "3"},
                              {"gait.period_s", "0.2"}});
}

const models::BuiltModel& knee() {
  static const models::BuiltModel built = models::build_model(deformable_config());
  return built;
}

// a 20 x 20 x 8 mm flat box meshed in 2 mm columns of 4 layers (grading 0.5)
models::BuiltModel flat_box() {
  models::Config c = deformable_config();
  c.deformable_element_size_mm = 2.0;
  c.deformable_layers = 4;
  c.deformable_grading = 0.5;
  models::BuiltModel b;
  b.implant.insert = test::make_flat_box(0.02, 0.02, 0.008, 4);
  b.model.period = 1.0;
  b.model.dt = 1e-4;
  b.model.dt_critical = 1e-4;
  models::attach_deformable_insert(c, b);
  return b;
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

wear::WearOptions short_run(const models::BuiltModel& built) {
  wear::WearOptions o;
  o.total_cycles = 1'000'000;
  o.update_every = 500'000;
  o.law.wear_factor = built.material.wear_factor_mm3_per_Nmm * wear::kWearFactorSI;
  o.law.friction = built.model.contact.friction;
  o.identity = 0xdef0;
  return o;
}

const wear::WearResult& reference_run() {
  static const wear::WearResult r = [] {
    const auto t0 = std::chrono::steady_clock::now();
    wear::WearResult res = wear::run_wear(knee(), short_run(knee()));
    std::printf("[deformable wear] 1 Mc in 2 updates, %d elements: %.1f s\n",
                knee().model.insert_solid.num_elements(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    return res;
  }();
  return r;
}

bool same_bits(const void* a, const void* b, size_t bytes) { return std::memcmp(a, b, bytes) == 0; }

}  // namespace

TEST_CASE("a uniform depth on a flat insert lowers the top exactly and keeps the grading") {
  // reference: closed form. Normals are +y, so the top drops by d; the hex volume falls by
  // d * 400 mm^2; each interior node keeps its pristine fraction of the column height.
  const models::BuiltModel b = flat_box();
  const engine::Model& m = b.model;
  const std::vector<Eigen::Vector3d>& X0 = m.insert_solid.reference_positions;
  const double area = sum(m.insert_contact.area);
  CHECK(area == doctest::Approx(4e-4).epsilon(1e-6).scale(0));  // the grid is inset by 1e-7 of its span
  const std::vector<Eigen::Vector3d> n = models::calc_top_node_normals(m, X0);
  for (const auto& v : n) CHECK((v - Eigen::Vector3d::UnitY()).norm() < 1e-12);
  const double d = 1e-4;
  const std::vector<double> depth(m.insert_contact.size(), d);
  const std::vector<Eigen::Vector3d> X1 = models::recede_insert_columns(m, X0, n, depth);
  const double v0 = models::calc_hex_volume(m, X0), v1 = models::calc_hex_volume(m, X1);
  CHECK(v0 == doctest::Approx(0.02 * 0.02 * 0.008).epsilon(1e-6).scale(0));
  CHECK((v0 - v1) == doctest::Approx(d * area).epsilon(1e-9).scale(0));
  for (size_t k = 0; k < X0.size(); ++k) {
    // the box is 8 mm high: every node's height scales by (8 - 0.1) / 8
    CHECK(X1[k].y() == doctest::Approx(X0[k].y() * (0.008 - d) / 0.008).epsilon(1e-12));
    CHECK(X1[k].x() == X0[k].x());
    CHECK(X1[k].z() == X0[k].z());
  }
  CHECK(models::count_collapsed_elements(m, X1) == 0);
}

TEST_CASE("a smooth scar on the knee insert folds no element and keeps the volume bookkeeping") {
  // reference: the depth integral sum_i d_i A_i against the hex volume loss, within 1 % (the
  // rigid path's issue-3 acceptance); a Gaussian scar of 0.4 mm peak, 6 mm wide, in each dish
  const models::BuiltModel& b = knee();
  const engine::Model& m = b.model;
  const std::vector<Eigen::Vector3d>& X0 = m.insert_solid.reference_positions;
  const std::vector<Eigen::Vector3d> sites = wear::find_site_positions(b);
  std::vector<double> depth(sites.size());
  for (size_t i = 0; i < sites.size(); ++i) {
    const double x = sites[i].x(), z = std::abs(sites[i].z()) - 0.022;  // dish centres at +-22 mm
    depth[i] = 4e-4 * std::exp(-(x * x + z * z) / (2 * 0.003 * 0.003));
  }
  const std::vector<Eigen::Vector3d> n = models::calc_top_node_normals(m, X0);
  const std::vector<Eigen::Vector3d> X1 = models::recede_insert_columns(m, X0, n, depth);
  CHECK(models::count_collapsed_elements(m, X1) == 0);
  double integral = 0.0;
  for (size_t i = 0; i < depth.size(); ++i) integral += depth[i] * m.insert_contact.area[i];
  const double loss = models::calc_hex_volume(m, X0) - models::calc_hex_volume(m, X1);
  std::printf("[deformable wear] scar: depth integral %.4f mm^3, hex volume loss %.4f mm^3 "
              "(%+.3f %%)\n", integral * 1e9, loss * 1e9, 100.0 * (loss - integral) / integral);
  CHECK(integral > 1e-9);  // the scar lies on the insert: more than 1 mm^3
  CHECK(std::abs(loss - integral) < 0.01 * integral);

  // the rebuilt model: same step, same mass-scaled limit, the displacements carried over
  engine::Model worn = m;
  engine::State state = engine::make_initial_state(m);
  for (size_t k = 0; k < X0.size(); ++k) {
    state.insert_solid.position[k] += Eigen::Vector3d(1e-6 * (k % 7), -2e-6, 0.0);
  }
  const engine::State before = state;
  models::apply_worn_deformable_insert(m, b.dt_safety, X1, worn, &state);
  CHECK(worn.dt == m.dt);
  CHECK(worn.insert_solid.dt_critical ==
        doctest::Approx(m.insert_solid.dt_critical).epsilon(1e-9).scale(0));
  CHECK(worn.insert_contact.size() == m.insert_contact.size());
  for (size_t k = 0; k < X0.size(); ++k) {
    const Eigen::Vector3d u0 = before.insert_solid.position[k] - X0[k];
    const Eigen::Vector3d u1 = state.insert_solid.position[k] - X1[k];
    CHECK((u1 - u0).norm() < 1e-15);
  }
  // worn down to 5 % of its height in one place: worn through
  std::vector<double> deep(depth.size(), 0.0);
  const int top = m.insert_contact.nodes[0];
  const int base = top - m.insert_solid.num_nodes() / static_cast<int>(m.insert_base_nodes.size()) + 1;
  deep[0] = 0.95 * (X0[top].y() - X0[base].y()) / std::max(n[0].y(), 1e-3);
  wear::WornInsert w{wear::InsertKind::kDeformable,
                     models::recede_insert_columns(m, X0, n, deep)};
  CHECK(wear::find_worn_through_site(b, w) == 0);
}

TEST_CASE("the wear loop on the deformable insert: bookkeeping, both dishes, stresses") {
  // reference: the volume bookkeeping of the rigid path (hex volume loss against the depth
  // integral, within 1 %); wear where the condyles slide (both sides); the stress maxima of
  // every simulated cycle are reported and positive
  const wear::WearResult& r = reference_run();
  INFO(r.message);
  REQUIRE(r.status == engine::StepStatus::kOk);
  REQUIRE(r.records.size() == 3);
  const wear::UpdateRecord& last = r.records.back();
  CHECK(last.cycles == 1'000'000);
  CHECK(last.volume_depth > 0.0);
  CHECK(last.medial_volume > 0.0);
  CHECK(last.lateral_volume > 0.0);
  std::printf("[deformable wear] 1 Mc: volume %.4f mm^3, depth integral %.4f mm^3, max depth "
              "%.4f mm, von Mises surface %.2f / subsurface %.2f MPa\n",
              last.volume * 1e9, last.volume_depth * 1e9, last.max_depth * 1e3,
              last.von_mises_surface * 1e-6, last.von_mises_subsurface * 1e-6);
  CHECK(std::abs(last.volume - last.volume_depth) < 0.01 * last.volume_depth);
  for (const wear::UpdateRecord& rec : r.records) {
    CHECK(rec.von_mises_surface > 0.0);
    CHECK(rec.von_mises_subsurface > 0.0);
    CHECK(rec.peak_pressure > 0.0);
    CHECK(rec.refinements == 0);
  }
  REQUIRE(r.worn_insert.kind == wear::InsertKind::kDeformable);
  CHECK(models::count_collapsed_elements(knee().model, r.worn_insert.points) == 0);
  CHECK(r.von_mises_max.size() == static_cast<size_t>(knee().model.insert_solid.num_elements()));
}

TEST_CASE("deformable wear resumed after an interruption equals the uninterrupted run") {
  // reference: issue 3's checkpoint contract, now with the solid's state: zero tolerance
  const wear::WearResult& ref = reference_run();
  REQUIRE(ref.status == engine::StepStatus::kOk);
  test::TempDir dir;
  wear::WearOptions o = short_run(knee());
  o.checkpoint = dir.path / "wear.checkpoint";
  struct Interrupt : std::runtime_error {
    using std::runtime_error::runtime_error;
  };
  o.on_update = [](const std::vector<wear::UpdateRecord>& records, const std::vector<double>&) {
    if (records.size() == 2) throw Interrupt("killed during update 2");
  };
  CHECK_THROWS_AS(wear::run_wear(knee(), o), Interrupt);
  const wear::Checkpoint c = wear::read_checkpoint(o.checkpoint, o.identity);
  CHECK(c.next_update == 1);
  CHECK(c.state.insert_solid.position.size() ==
        static_cast<size_t>(knee().model.insert_solid.num_nodes()));
  o.on_update = nullptr;
  o.resume = true;
  const wear::WearResult res = wear::run_wear(knee(), o);
  REQUIRE(res.status == engine::StepStatus::kOk);
  REQUIRE(res.records.size() == ref.records.size());
  for (size_t i = 0; i < ref.records.size(); ++i) {
    CAPTURE(i);
    CHECK(same_bits(&res.records[i].cycles, &ref.records[i].cycles,
                    sizeof(double) * wear::UpdateRecord::kFields));
  }
  CHECK(same_bits(res.vertex_depth.data(), ref.vertex_depth.data(), 8 * ref.vertex_depth.size()));
  CHECK(engine::hash_state(res.final_state) == engine::hash_state(ref.final_state));
}
