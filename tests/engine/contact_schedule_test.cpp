// The contact search's sleep schedule (engine/contact.h: an element found at distance phi is
// not evaluated again until the accumulated relative motion could have closed kLipschitz * phi)
// must never miss a contact. Reference: at every step of a gait cycle of the default model,
// the contact evaluated with the schedule equals, bit for bit, a fresh evaluation of every
// element at the same state (same elements in contact, same total force; the reduction runs
// over the elements in contact in index order, so any missed or extra element would show).
#include <doctest/doctest.h>

#include "engine/step.h"
#include "engine_fixtures.h"

using namespace kneesim;

TEST_CASE("the contact sleep schedule never misses a contact over a gait cycle") {
  const models::BuiltModel built =
      models::build_model(test::default_config({"implant.edge_length_mm=2"}));
  const engine::Model& model = built.model;
  engine::State state = engine::make_initial_state(model);
  engine::Data data = engine::make_data(model);
  engine::Data fresh = engine::make_data(model);
  const int steps = static_cast<int>(1.2 * model.period / model.dt);
  int count_mismatch = 0, force_mismatch = 0, worst_step = -1;
  long scheduled = 0, all = 0;
  for (int i = 0; i < steps; ++i) {
    // every element evaluated: a Data whose schedule is reset
    fresh.schedule_valid = false;
    engine::calc_forces(model, state, fresh);
    REQUIRE(engine::step(model, state, data) == engine::StepStatus::kOk);
    scheduled += static_cast<long>(data.due.size());
    all += model.insert.size();
    if (data.contact.elements_in_contact != fresh.contact.elements_in_contact) {
      ++count_mismatch;
      if (worst_step < 0) worst_step = i;
    }
    if (data.contact.force_W != fresh.contact.force_W) ++force_mismatch;
  }
  MESSAGE("sleep schedule: " << steps << " steps, " << count_mismatch
          << " with a different contact set (first at step " << worst_step << "), "
          << force_mismatch << " with a different force; evaluated "
          << 100.0 * scheduled / all << " % of element-steps");
  CHECK(count_mismatch == 0);
  CHECK(force_mismatch == 0);
}
