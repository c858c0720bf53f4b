// The Grand Challenge DM implant (models/examples/dm_stanmore.toml, real meshes through
// assimp; ../shared/data/gc6_dm, skipped with the reason when absent). Long suite: its
// distance field takes a few seconds. References: the contact sleep schedule equals a full
// evaluation bit for bit at every step (as contact_schedule_test.cpp on the generic implant),
// and the quasi-static stance balance (axial contact force within 2 % of the applied load at
// the 13 % peak).
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>

#include "engine/io/source_tree.h"
#include "engine/simulate.h"
#include "engine_fixtures.h"

using namespace kneesim;
namespace fs = std::filesystem;

namespace {

// the example config, or "" when the data folder is absent
fs::path dm_config() {
  const char* data = std::getenv("KNEESIM_DATA");
  const fs::path dir = data ? fs::path(data) : kneesim::io::source_dir() / "../shared/data";
  if (!fs::exists(dir / "gc6_dm" / "femoral_component.stl")) return {};
  return kneesim::io::source_dir() / "models/examples/dm_stanmore.toml";
}

}  // namespace

TEST_CASE("DM implant: sleep schedule equals a full evaluation; stance load balance") {
  const fs::path config = dm_config();
  if (config.empty()) {
    MESSAGE("skipped: gc6_dm data not found (set KNEESIM_DATA)");
    return;
  }
  const models::BuiltModel built = models::build_model(models::load_config(config, {}));
  const engine::Model& model = built.model;
  engine::State state = engine::make_initial_state(model);
  engine::Data data = engine::make_data(model);
  engine::Data fresh = engine::make_data(model);
  // 0.3 s: heel strike, the 13 % peak and the mid-stance valley
  const int steps = static_cast<int>(0.3 * model.period / model.dt);
  int mismatches = 0;
  double best_balance = 1e9;
  for (int i = 0; i < steps; ++i) {
    fresh.schedule_valid = false;
    engine::calc_forces(model, state, fresh);
    REQUIRE(engine::step(model, state, data) == engine::StepStatus::kOk);
    if (data.contact.force_W != fresh.contact.force_W ||
        data.contact.elements_in_contact != fresh.contact.elements_in_contact) {
      ++mismatches;
    }
    // at the peak-load step (gait 13 %)
    if (std::abs(data.gait_pct - 13.0) < 50.0 * model.dt / model.period) {
      best_balance = data.contact.force_W.y() / -data.applied[0][1] - 1.0;
    }
  }
  MESSAGE("DM implant: " << model.insert.size() << " elements, " << steps << " steps, "
          << mismatches << " schedule mismatches; contact/applied - 1 at 13 % = " << best_balance);
  CHECK(mismatches == 0);
  CHECK(std::abs(best_balance) < 0.02);
}
