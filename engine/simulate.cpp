#include "engine/simulate.h"

#include <algorithm>
#include <cmath>

#include "engine/contact_line.h"
#include "engine/reference_integrator.h"

namespace kneesim::engine {

Frame make_frame(const Model& model, const State& state, const Data& data) {
  Frame f;
  f.gait_pct = data.gait_pct;
  f.time = state.time;
  f.q = data.q;
  f.joint = calc_joint_coordinates(data.X_WF, data.X_WT);
  f.applied = data.applied;
  f.restraint = data.restraint_force;
  f.contact = data.contact;
  f.contact_line_area = calc_contact_line_area(model, data);
  return f;
}

RunResult simulate(const Model& model, State& state, Data& data, const RunOptions& options) {
  if (model.integrator == IntegratorKind::kCvode) {
    return simulate_reference(model, state, data, options);
  }
  RunResult result;
  const double t0 = state.time;
  const double t_end = t0 + options.cycles * model.period;
  const double last_start = t_end - model.period;
  const long total_steps = std::lround((t_end - t0) / model.dt);
  const double frame_dt = model.period / options.frames_per_cycle;
  int next_frame = 0;
  size_t next_map = 0;
  result.maps.reserve(options.map_pcts.size());
  long report_every = std::max(1L, total_steps / 200);
  for (long n = 0; n < total_steps; ++n) {
    const double t = state.time;
    const StepStatus status = step(model, state, data);
    result.max_stability_ratio =
        std::max(result.max_stability_ratio, calc_stability_ratio(model, data));
    result.omega_max = std::max(result.omega_max, data.contact.omega_max);
    // data now describes time t (forces at the start of the step)
    if (t >= last_start - 0.5 * model.dt) {
      const double local = t - last_start;
      if (next_frame < options.frames_per_cycle && local >= next_frame * frame_dt - 0.5 * model.dt) {
        result.frames.push_back(make_frame(model, state, data));
        result.frames.back().time = t;
        result.frames.back().gait_pct = std::max(0.0, 100.0 * local / model.period);
        ++next_frame;
      }
      if (next_map < options.map_pcts.size() &&
          local >= options.map_pcts[next_map] / 100.0 * model.period - 0.5 * model.dt) {
        // rigid insert: per articular element; deformable: per top-surface node
        result.maps.push_back(model.insert_solid.empty() ? data.pressure
                                                         : data.insert_contact.pressure);
        ++next_map;
      }
      if (options.observer) options.observer(model, state, data);
    }
    if (status != StepStatus::kOk) {
      result.status = status;
      result.failed_at = state.time;
      break;
    }
    if (options.progress && n % report_every == 0) {
      options.progress(static_cast<double>(n) / total_steps);
    }
  }
  result.steps = state.step;
  result.evaluations = data.evaluations;
  return result;
}

double find_step_for_frequency(const Model& model, double omega, double safety) {
  const double z = 0.5 * model.contact.damping_beta * omega;
  return safety * 2.0 / omega * (std::sqrt(1.0 + z * z) - z);
}

double find_whole_cycle_step(const Model& model, double dt) {
  return model.period / std::ceil(model.period / dt);
}

RunResult simulate_with_retry(Model& model, State& state, const RunOptions& options,
                              double dt_safety, int max_retries,
                              const std::function<void()>& before_attempt) {
  for (int attempt = 0;; ++attempt) {
    if (before_attempt) before_attempt();
    State trial = state;
    Data data = make_data(model);
    RunResult run = simulate(model, trial, data, options);
    if (run.status == StepStatus::kUnstableStep && attempt < max_retries &&
        run.omega_max > 0.0) {
      model.dt = find_whole_cycle_step(
          model, std::min(model.dt, find_step_for_frequency(model, run.omega_max, dt_safety)));
      continue;
    }
    run.step_retries = attempt;
    state = trial;
    return run;
  }
}

}  // namespace kneesim::engine
