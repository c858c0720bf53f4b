// The femoral distance field is built once per (femoral mesh, spacing, band) in a process and
// shared const by every Model built from it (models/distance_field_cache.h). References: a
// second build with another material and rig reuses the very storage and counts
// no new build; a different spacing builds anew; the shared field is bit-identical to a fresh
// build; concurrent first requests build once.
#include <doctest/doctest.h>

#include <cstring>
#include <thread>

#include "models/build_model.h"
#include "models/distance_field_cache.h"
#include "models/generic_tkr.h"

using namespace kneesim;

namespace {

models::BuiltModel build(const std::vector<models::Override>& o) {
  return models::build_model(models::load_config("", o));
}

bool same_values(const engine::SignedDistanceField& a, const engine::SignedDistanceField& b) {
  return a.dims == b.dims && a.origin == b.origin && a.storage->brick_of == b.storage->brick_of &&
         a.storage->values.size() == b.storage->values.size() &&
         std::memcmp(a.storage->values.data(), b.storage->values.data(),
                     a.storage->values.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("Models of one femur share one distance field across materials and rigs") {
  const models::BuiltModel a = build({{"implant.edge_length_mm", "2.0"}});
  const long builds = models::count_distance_field_builds();
  const models::BuiltModel b = build({{"implant.edge_length_mm", "2.0"},
                                      {"material.name", "\"peek\""},
                                      {"rig.preset", "\"iso\""}});
  CHECK(models::count_distance_field_builds() == builds);
  CHECK(a.model.femur_sdf.storage == b.model.femur_sdf.storage);
  CHECK(a.model.femur_far_sdf.storage == b.model.femur_far_sdf.storage);
  // the shared field is the field a fresh build gives, bit for bit
  const auto fresh = engine::make_signed_distance_field(
      a.implant.femur.vertices, a.implant.femur.triangles, a.model.femur_sdf.spacing,
      a.model.femur_sdf.band);
  CHECK(same_values(fresh, b.model.femur_sdf));
  // another spacing is another field (the coarse far field is still shared)
  const models::BuiltModel c = build({{"implant.edge_length_mm", "2.0"},
                                      {"contact.sdf_spacing_mm", "0.5"}});
  CHECK(models::count_distance_field_builds() == builds + 1);
  CHECK(c.model.femur_sdf.storage != a.model.femur_sdf.storage);
  CHECK(c.model.femur_far_sdf.storage == a.model.femur_far_sdf.storage);
}

TEST_CASE("concurrent first requests of one field build it once") {
  // a mesh no other test uses: the generic femur at a coarse facet size, moved by 1 mm
  models::TriMesh femur = models::make_generic_femur(models::GenericTkrParams{}, 3e-3);
  for (auto& v : femur.vertices) v.x() += 1e-3;
  const long builds = models::count_distance_field_builds();
  engine::SignedDistanceField fields[2];
  std::thread t0([&] {
    fields[0] = models::find_or_make_distance_field(femur.vertices, femur.triangles, 1e-3, 2e-3);
  });
  std::thread t1([&] {
    fields[1] = models::find_or_make_distance_field(femur.vertices, femur.triangles, 1e-3, 2e-3);
  });
  t0.join();
  t1.join();
  CHECK(models::count_distance_field_builds() == builds + 1);
  CHECK(fields[0].storage == fields[1].storage);
  CHECK(!fields[0].empty());
}
