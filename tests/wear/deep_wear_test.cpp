// Deep wear (issue 3 acceptance: "an update never inverts a face on a test case that drives
// deep wear"). The coarse generic insert (2 mm elements, 8 mm thick at the dwell points) worn
// with k = 1e-7 mm^3/(N mm), ~400x UHMWPE's: a 50 000-cycle update recedes the dwell region
// by ~2.5 mm, more than an element is long. References:
//  - validity: every worn insert is watertight (closed, manifold, consistently oriented, no
//    degenerate face) and no face is reversed or collapsed against the pristine insert;
//  - refinement bookkeeping: replaying the loop's recession from the reported depth field
//    (normals of the current worn surface, per-cycle depth = increment / cycles applied)
//    reproduces the worn mesh, and an update reports refinements exactly when its full
//    interval would have inverted a face (the rule of wear/wear_loop.h);
//  - wear-through: a single update deeper than the insert must not leave articular vertices
//    below the base plane (the mesh would intersect itself) in a run reported as complete.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "models/build_model.h"
#include "tests/wear/wear_fixtures.h"
#include "wear/archard.h"
#include "wear/geometry_update.h"
#include "wear/wear_loop.h"

using namespace kneesim;

namespace {

constexpr double kDeepWearFactor = 1e-7;  // mm^3/(N mm)

wear::WearOptions deep_options(const models::BuiltModel& built, long cycles, long every) {
  wear::WearOptions o;
  o.total_cycles = cycles;
  o.update_every = every;
  o.law.wear_factor = kDeepWearFactor * wear::kWearFactorSI;
  o.law.friction = built.model.contact.friction;
  return o;
}

const models::BuiltModel& deep_model() {
  static const models::BuiltModel built = models::build_model(
      test::coarse_config({{"material.wear_factor_mm3_per_Nmm", "1e-7"}}));
  return built;
}

double lowest_articular_y(const models::BuiltModel& built, const models::TriMesh& worn) {
  double y = 1.0;
  for (int v : built.implant.articular_vertex_to_insert) y = std::min(y, worn.vertices[v].y());
  return y;
}

}  // namespace

TEST_CASE("deep wear never inverts a face; refinements are reported exactly when needed") {
  const auto t0 = std::chrono::steady_clock::now();
  const models::BuiltModel& built = deep_model();
  wear::WearOptions o = deep_options(built, 150'000, 50'000);
  std::vector<std::vector<double>> depths;  // cumulative vertex depth after each update
  o.on_update = [&](const std::vector<wear::UpdateRecord>&, const std::vector<double>& d) {
    depths.push_back(d);
  };
  const wear::WearResult r = wear::run_wear(built, o);
  REQUIRE(r.status == engine::StepStatus::kOk);
  REQUIRE(r.records.size() >= 4);
  REQUIRE(depths.size() == r.records.size());
  const double base_y = 0.0;  // the generic insert sits on y = 0
  std::printf("[wear] deep wear (k = %g mm^3/(N mm), %ld cycles): max depth %.3f mm, volume "
              "%.1f mm^3 (depth integral %.1f), lowest articular point %.2f mm above the base, "
              "%.2f s\n",
              kDeepWearFactor, o.total_cycles, r.records.back().max_depth * 1e3,
              r.records.back().volume * 1e9, r.records.back().volume_depth * 1e9,
              (lowest_articular_y(built, r.worn) - base_y) * 1e3,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  // the run is deep: well past an element length (2 mm) but inside the 8 mm insert
  CHECK(r.records.back().max_depth > 2e-3);
  CHECK(lowest_articular_y(built, r.worn) > base_y);

  // replay the recessions from the reported depth field
  models::TriMesh insert = built.implant.insert;
  int refinements = 0;
  for (size_t u = 1; u < r.records.size(); ++u) {
    CAPTURE(u);
    const engine::InsertSurface surface = models::make_worn_insert_surface(built, insert);
    const std::vector<Eigen::Vector3d> normals = wear::articular_vertex_normals(surface);
    const double applied = r.records[u].cycles - r.records[u - 1].cycles;
    const double full = static_cast<double>(std::min(
        wear::update_interval(o, static_cast<int>(u) - 1),
        o.total_cycles - static_cast<long>(r.records[u - 1].cycles)));
    std::vector<double> increment(depths[u].size()), full_increment(depths[u].size());
    for (size_t v = 0; v < increment.size(); ++v) {
      increment[v] = depths[u][v] - depths[u - 1][v];
      full_increment[v] = increment[v] / applied * full;
      CHECK(increment[v] >= 0.0);  // Archard wear only removes material
    }
    const int full_inverted =
        wear::recede(insert, built.implant.articular_vertex_to_insert, normals, full_increment)
            .inverted_faces;
    CHECK((r.records[u].refinements > 0) == (full_inverted > 0));
    CHECK(applied * std::pow(2.0, r.records[u].refinements) == doctest::Approx(full));
    refinements += static_cast<int>(r.records[u].refinements);
    const wear::RecessionResult step =
        wear::recede(insert, built.implant.articular_vertex_to_insert, normals, increment);
    CHECK(step.inverted_faces == 0);
    insert = step.insert;
    const models::MeshCheck c = models::check_mesh(insert);
    CHECK(c.watertight());
  }
  std::printf("[wear] deep wear: %d refinement(s) reported\n", refinements);
  // the replay reproduces the loop's worn insert (to rounding of the depth differences)
  double worst = 0.0;
  for (size_t v = 0; v < insert.vertices.size(); ++v)
    worst = std::max(worst, (insert.vertices[v] - r.worn.vertices[v]).norm());
  CHECK(worst < 1e-12);
  const models::MeshCheck c = models::check_mesh(r.worn);
  CHECK(c.watertight());
  CHECK(wear::count_inverted_faces(built.implant.insert, r.worn) == 0);
}

TEST_CASE("an update deeper than the insert is not accepted as a complete run") {
  // 200 000 cycles in one update at k = 1e-7 recede the dwell vertices by ~10 mm, more than
  // the 8 mm insert: the articular surface would pass through the base plane (a
  // self-intersecting mesh the inversion counter cannot see, since a vertical recession keeps
  // every face's orientation). Accepted: the run stops with a non-ok status, or it refines
  // the update so that the insert keeps material under every articular vertex.
  const models::BuiltModel& built = deep_model();
  const wear::WearResult r = wear::run_wear(built, deep_options(built, 200'000, 200'000));
  const double lowest = lowest_articular_y(built, r.worn);
  std::printf("[wear] wear-through case: status %s (%s), lowest articular point %.2f mm above "
              "the base, max depth %.2f mm\n",
              engine::to_string(r.status), r.message.c_str(), lowest * 1e3,
              r.records.back().max_depth * 1e3);
  CHECK((r.status != engine::StepStatus::kOk || lowest > 0.0));
}
