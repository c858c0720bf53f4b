// The deformable insert in the knee step (engine/insert_solid.h, models/deformable_insert.h):
// the model it builds, the load balance between the femur, the solid and the tray, determinism
// across thread counts, the stop on an inverted element, and the config's bad-input errors.
// References: invariants (base nodes fixed, forces balanced up to the insert's inertia, equal
// hashes), and the error contract (one sentence naming the key, value and allowed range).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "engine/errors.h"
#include "engine/solid/solid_build.h"
#include "engine/step.h"
#include "engine_fixtures.h"

using namespace kneesim;

namespace {

// a coarse deformable insert (3 mm elements, 3 layers) on the default implant at 2 mm edges
models::Config coarse_deformable(std::vector<std::string> extra = {}) {
  std::vector<std::string> sets = {"insert=deformable", "deformable.element_size_mm=3",
                                   "deformable.layers=3", "implant.edge_length_mm=2"};
  sets.insert(sets.end(), extra.begin(), extra.end());
  return test::default_config(sets);
}

}  // namespace

TEST_CASE("deformable insert: the model ties the base to the tray and starts at first touch") {
  const models::BuiltModel built = models::build_model(coarse_deformable());
  const engine::Model& m = built.model;
  const engine::solid::SolidModel& s = m.insert_solid;
  REQUIRE(!s.empty());
  // every base node lies on the base plane and is fixed in all three directions
  REQUIRE(!m.insert_base_nodes.empty());
  for (int b : m.insert_base_nodes) {
    CHECK(std::abs(s.reference_positions[b].y()) < 1e-12);
    CHECK(s.constraint[b] == engine::solid::kFixAll);
  }
  // the contact nodes are the top nodes, none of them fixed
  CHECK(m.insert_contact.size() > 0);
  for (int node : m.insert_contact.nodes) CHECK(s.constraint[node] == 0);
  // one global step within the solid's limit and the rigid rig's, a whole number per cycle
  CHECK(m.dt <= built.dt_safety * s.dt_critical * (1.0 + 1e-12));
  CHECK(m.dt <= built.stable_step.dt * (1.0 + 1e-12));
  CHECK(std::abs(m.period / m.dt - std::round(m.period / m.dt)) < 1e-6);
  // mass scaling reached the configured 20 us and is reported
  CHECK(m.dt == doctest::Approx(20e-6).epsilon(1e-3).scale(0));
  CHECK(s.added_mass > 0.0);
  // the femur starts at first touch: no penetration deeper than a micrometre
  engine::State state = engine::make_initial_state(m);
  engine::Data data = engine::make_data(m);
  engine::calc_forces(m, state, data);
  CHECK(data.contact.max_penetration < 1e-6);
}

TEST_CASE("deformable insert: femur, solid and tray balance the applied load") {
  // 0.06 s of the gait (the axial load from 168 N to 1890 N at 3 % and 1530 N at 6 %):
  // the tray carries exactly the opposite of the femur's contact load at every step (the
  // insert is massless to the carriages, engine/insert_solid.h; reference: momentum exchange);
  // averaged over the last 0.02 s, the base nodes' reaction matches it up to the insert's own
  // inertia and damping (reference: momentum balance of the solid; the scaled insert's kinetic
  // energy is small), and the contact force the applied load up to the femur's acceleration
  const models::BuiltModel built = models::build_model(coarse_deformable());
  const engine::Model& m = built.model;
  engine::State state = engine::make_initial_state(m);
  engine::Data data = engine::make_data(m);
  const int steps = static_cast<int>(std::lround(0.06 / m.dt));
  const int window = static_cast<int>(std::lround(0.02 / m.dt));
  double femur = 0.0, base = 0.0, applied = 0.0, worst_exchange = 0.0;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(engine::step(m, state, data) == engine::StepStatus::kOk);
    const Eigen::Vector3d exchange = data.contact.tray_force_W + data.contact.force_W;
    worst_exchange = std::max(worst_exchange, exchange.norm());
    if (i >= steps - window) {
      Eigen::Vector3d reaction = Eigen::Vector3d::Zero();
      for (int b : m.insert_base_nodes) {
        reaction -= data.X_WT.linear() * data.insert_solid.internal_force[b].head<3>();
      }
      femur += data.contact.force_W.y() / window;
      base += reaction.y() / window;
      applied += -data.applied[0][1] / window;
    }
  }
  MESSAGE("mean over 0.04-0.06 s: applied " << applied << " N, contact on the femur " << femur
          << " N, base reaction " << base << " N; largest |tray + femur| " << worst_exchange
          << " N");
  CHECK(applied > 1000.0);
  CHECK(femur == doctest::Approx(applied).epsilon(0.05));
  CHECK(worst_exchange < 1e-9 * applied);
  CHECK(-base == doctest::Approx(femur).epsilon(0.05));
  // what the node update relies on to skip reading them (engine/insert_solid.cpp): only top
  // nodes carry an external force, and no node a friction viscosity
  std::vector<char> top(m.insert_solid.num_nodes(), 0);
  for (int i = 0; i < m.insert_contact.size(); ++i) top[m.insert_contact.nodes[i]] = 1;
  int loaded_elsewhere = 0, with_viscosity = 0;
  for (int n = 0; n < m.insert_solid.num_nodes(); ++n) {
    if (!top[n] && data.insert_solid.external_force[n] != Eigen::Vector3d::Zero()) ++loaded_elsewhere;
    if (data.insert_solid.friction_viscosity[n] != 0.0) ++with_viscosity;
  }
  CHECK(loaded_elsewhere == 0);
  CHECK(with_viscosity == 0);
}

TEST_CASE("deformable insert: bit-identical for any thread and range count, with or without "
          "the node sleep schedule") {
  // reference: engine::hash_state over every bit of the State (carriages and solid nodes) of
  // the one-thread run; the ranges (solid.h) only move where nodal sums are formed, and a top
  // node asleep is one the femur cannot have reached, so its outputs are the zeros it had
  struct Variant {
    int threads, ranges;
    bool sleep;
  };
  auto run = [](Variant v) {
    models::BuiltModel built = models::build_model(
        coarse_deformable({"solver.threads=" + std::to_string(v.threads)}));
    if (v.ranges > 0) engine::solid::cut_solid_ranges(built.model.insert_solid, v.ranges);
    engine::State state = engine::make_initial_state(built.model);
    engine::Data data = engine::make_data(built.model);
    data.insert_contact.sleep = v.sleep;
    long contact_node_steps = 0;
    for (int i = 0; i < 1500; ++i) {
      REQUIRE(engine::step(built.model, state, data) == engine::StepStatus::kOk);
      contact_node_steps += data.contact.elements_in_contact;
    }
    CHECK(data.contact.elements_in_contact > 0);
    CHECK(contact_node_steps > 0);
    return engine::hash_state(state);
  };
  const uint64_t reference = run({1, 0, false});
  for (Variant v : {Variant{1, 0, true}, Variant{2, 0, true}, Variant{2, 3, true},
                    Variant{3, 7, false}, Variant{2, 2, true}}) {
    CAPTURE(v.threads);
    CAPTURE(v.ranges);
    CAPTURE(v.sleep);
    CHECK(run(v) == reference);
  }
}

TEST_CASE("deformable insert: most top nodes sleep through a step out of contact") {
  // the schedule is worth having: over 0.05-0.06 s of the gait (stance) fewer than half of the
  // top nodes are sampled per step (counted from the schedule's own state)
  const models::BuiltModel built = models::build_model(coarse_deformable());
  const engine::Model& m = built.model;
  engine::State state = engine::make_initial_state(m);
  engine::Data data = engine::make_data(m);
  const int n = m.insert_contact.size();
  long awake = 0, steps = 0;
  while (state.time < 0.06) {
    REQUIRE(engine::step(m, state, data) == engine::StepStatus::kOk);
    if (state.time < 0.05) continue;
    for (int i = 0; i < n; ++i) awake += data.insert_contact.wake_at[i] <= data.motion;
    ++steps;
  }
  const double fraction = static_cast<double>(awake) / (static_cast<double>(n) * steps);
  MESSAGE("top nodes due per step: ", fraction * 100.0, " % of ", n);
  CHECK(fraction < 0.5);
}

TEST_CASE("deformable insert: an inverted element stops the step before anything moves") {
  const models::BuiltModel built = models::build_model(coarse_deformable());
  const engine::Model& m = built.model;
  engine::State state = engine::make_initial_state(m);
  engine::Data data = engine::make_data(m);
  for (int i = 0; i < 10; ++i) REQUIRE(engine::step(m, state, data) == engine::StepStatus::kOk);
  // push the top nodes of one column below its base: every element of the column inverts
  const int element = m.insert_top_face_element[m.insert_top_face_element.size() / 2];
  for (int a : m.insert_solid.elements[element]) {
    if (m.insert_solid.constraint[a] == 0) state.insert_solid.position[a].y() = -1e-3;
  }
  const uint64_t before = engine::hash_state(state);
  CHECK(engine::step(m, state, data) == engine::StepStatus::kInvertedElement);
  CHECK(engine::hash_state(state) == before);
  CHECK(data.insert_solid.inverted_element >= 0);
  CHECK(data.insert_solid.inverted_element <= element);
  CHECK(std::string(engine::to_string(engine::StepStatus::kInvertedElement)).find("inverted") !=
        std::string::npos);
}

TEST_CASE("deformable insert: bad config values are refused with one sentence") {
  auto message = [](std::vector<std::string> sets) -> std::string {
    try {
      models::build_model(coarse_deformable(sets));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  // each names the key, the value and the allowed range
  const std::string layers = message({"deformable.layers=41"});
  CHECK(layers.find("deformable.layers") != std::string::npos);
  CHECK(layers.find("[0, 40]") != std::string::npos);
  const std::string size = message({"deformable.element_size_mm=0"});
  CHECK(size.find("deformable.element_size_mm") != std::string::npos);
  const std::string kind = message({"insert=solid"});
  CHECK(kind.find("\"deformable\"") != std::string::npos);
  const std::string poisson = message({"material.poisson=0.5"});
  CHECK(poisson.find("material.poisson") != std::string::npos);
  const std::string cvode = message({"solver.integrator=cvode"});
  CHECK(cvode.find("central_difference") != std::string::npos);
  // a step above the stable limit cannot be asked for: the step is dt_safety times the limit
  // (the solid's reached by mass scaling), and a safety factor above 1 is refused
  const std::string unstable = message({"solver.dt_safety=1.5"});
  INFO(unstable);
  CHECK(unstable.find("solver.dt_safety") != std::string::npos);
  CHECK(unstable.find("1.5") != std::string::npos);
  CHECK(unstable.find("1]") != std::string::npos);
}
