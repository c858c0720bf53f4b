// Runs the explicit and the CVODE integrators on the same default-config model and measures
// the agreement of the tibial AP and IE traces over the last cycle (shared by
// reference_integrator_test.cpp and reference_long.cpp).
#pragma once

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "engine/simulate.h"
#include "engine_fixtures.h"

namespace kneesim::test {

struct Agreement {
  double ap_rms_mm = 0.0, ie_rms_deg = 0.0, ap_max_mm = 0.0, ie_max_deg = 0.0;
  double explicit_s = 0.0, cvode_s = 0.0;
  long explicit_steps = 0, cvode_steps = 0;
  int elements = 0;
};

inline Agreement compare_integrators(const std::vector<std::string>& sets, int cycles) {
  models::BuiltModel built = models::build_model(default_config(sets));
  engine::Model& model = built.model;
  engine::RunOptions options;
  options.cycles = cycles;
  auto run = [&](engine::IntegratorKind kind, double& seconds) {
    model.integrator = kind;
    engine::State s = engine::make_initial_state(model);
    engine::Data d = engine::make_data(model);
    const auto t0 = std::chrono::steady_clock::now();
    engine::RunResult r = engine::simulate(model, s, d, options);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  Agreement a;
  a.elements = model.insert.size();
  const engine::RunResult ex = run(engine::IntegratorKind::kCentralDifference, a.explicit_s);
  const engine::RunResult cv = run(engine::IntegratorKind::kCvode, a.cvode_s);
  REQUIRE(ex.status == engine::StepStatus::kOk);
  REQUIRE(cv.status == engine::StepStatus::kOk);
  REQUIRE(ex.frames.size() == 100u);
  REQUIRE(cv.frames.size() == 100u);
  a.explicit_steps = ex.steps;
  a.cvode_steps = cv.steps;
  constexpr double kDeg = 180.0 / std::numbers::pi;
  double ap2 = 0.0, ie2 = 0.0;
  for (size_t i = 0; i < ex.frames.size(); ++i) {
    const engine::Frame& e = ex.frames[i];
    const engine::Frame& c = cv.frames[i];
    CHECK(std::abs(std::remainder(e.gait_pct - c.gait_pct, 100.0)) <=
          50.0 * model.dt / model.period + 1e-9);
    const double dap = (e.q[1][0] - c.q[1][0]) * 1e3, die = (e.q[1][4] - c.q[1][4]) * kDeg;
    ap2 += dap * dap;
    ie2 += die * die;
    a.ap_max_mm = std::max(a.ap_max_mm, std::abs(dap));
    a.ie_max_deg = std::max(a.ie_max_deg, std::abs(die));
  }
  a.ap_rms_mm = std::sqrt(ap2 / ex.frames.size());
  a.ie_rms_deg = std::sqrt(ie2 / ex.frames.size());
  MESSAGE("CVODE vs central difference (" << sets.back() << ", cycle " << cycles << ", " << a.elements
          << " elements): AP RMS " << a.ap_rms_mm << " mm (max " << a.ap_max_mm << "), IE RMS "
          << a.ie_rms_deg << " deg (max " << a.ie_max_deg << "); explicit " << a.explicit_s
          << " s (" << a.explicit_steps << " steps), CVODE " << a.cvode_s << " s ("
          << a.cvode_steps << " steps), CPU ratio explicit/CVODE " << a.explicit_s / a.cvode_s);
  return a;
}


}  // namespace kneesim::test
