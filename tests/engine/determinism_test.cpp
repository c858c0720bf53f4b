// Determinism (design.md): the same inputs give bit-identical results for any thread count.
// Reference: equality of engine::hash_state (FNV-1a over every bit of the State) after a run
// with model.threads = 1 and 2, and bit equality of the femoral distance field built with 1
// and 2 OpenMP threads (the build's z-slab ownership, engine/sdf.h). With 2 threads the
// contact loop goes parallel above a candidate count (engine/contact.cpp), with 1 it stays in
// the batched loop: those steps compare the two loops. They are counted and reported, and at
// least the first step (every element due) must be one.
#include <doctest/doctest.h>

#include <omp.h>

#include <cstring>

#include "engine/contact.h"
#include "engine/sdf.h"
#include "engine/step.h"
#include "engine_fixtures.h"
#include "models/generic_tkr.h"

using namespace kneesim;

namespace {


struct RunOutcome {
  uint64_t hash = 0;
  int parallel_steps = 0;   // steps whose due list exceeded the parallel threshold
  double contact_y = 0.0;   // last contact force [N]
};

RunOutcome run_steps(const engine::Model& model, int steps) {
  engine::State s = engine::make_initial_state(model);
  engine::Data d = engine::make_data(model);
  RunOutcome out;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(engine::step(model, s, d) == engine::StepStatus::kOk);
    if (d.due.size() > static_cast<size_t>(engine::kParallelAbove)) ++out.parallel_steps;
  }
  out.hash = engine::hash_state(s);
  out.contact_y = d.contact.force_W.y();
  return out;
}

}  // namespace

TEST_CASE("final state hash is identical with 1 and 2 threads") {
  // 1 mm insert edges: about 6600 articular elements, so every full re-evaluation of the
  // contact schedule runs in parallel; 0.15 s of gait (heel strike and the load rise to the
  // 13 % peak); a 0.6 mm distance field to keep the build short
  models::BuiltModel built = models::build_model(
      test::default_config({"implant.edge_length_mm=1", "contact.sdf_spacing_mm=0.6"}));
  engine::Model& model = built.model;
  const int steps = static_cast<int>(0.15 / model.dt);
  model.threads = 1;
  const RunOutcome one = run_steps(model, steps);
  model.threads = 2;
  const RunOutcome two = run_steps(model, steps);
  MESSAGE("determinism: " << model.insert.size() << " elements, " << steps << " steps; "
          << "parallel contact loop taken in " << two.parallel_steps << " steps; hash 1 thread "
          << std::to_string(one.hash) << ", 2 threads " << std::to_string(two.hash)
          << "; contact force " << one.contact_y << " N");
  CHECK(one.parallel_steps == two.parallel_steps);
  CHECK(two.parallel_steps >= 1);
  CHECK(one.hash == two.hash);
  CHECK(one.contact_y == two.contact_y);
  // and the hash sees a change: one more step differs
  CHECK(run_steps(model, steps + 1).hash != two.hash);
}

TEST_CASE("distance field is bit-identical for 1 and 2 OpenMP threads") {
  const models::TriMesh femur = models::make_generic_femur(models::GenericTkrParams{}, 1.5e-3);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const engine::SignedDistanceField a =
      engine::make_signed_distance_field(femur.vertices, femur.triangles, 0.5e-3, 1.5e-3);
  omp_set_num_threads(2);
  const engine::SignedDistanceField b =
      engine::make_signed_distance_field(femur.vertices, femur.triangles, 0.5e-3, 1.5e-3);
  omp_set_num_threads(saved);
  REQUIRE(a.storage->values.size() == b.storage->values.size());
  CHECK(a.dims == b.dims);
  CHECK(a.storage->brick_of == b.storage->brick_of);
  CHECK(std::memcmp(a.storage->values.data(), b.storage->values.data(),
                    a.storage->values.size() * sizeof(float)) == 0);
}
