#include "engine/reference_integrator.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "engine/kinematics.h"
#include "engine/sundials_adapter.h"

namespace kneesim::engine {
namespace {

struct DofRef {
  int carriage;
  int dof;
};

double gait_pct_at(const Model& model, double t) {
  double pct = std::fmod(100.0 * t / model.period, 100.0);
  return pct < 0.0 ? pct + 100.0 : pct;
}

// the state at time t from the ODE vector y = [q_free..., qdot_free...]
void fill_state(const Model& model, const std::vector<DofRef>& free, const Eigen::VectorXd& y,
                double t, State& state) {
  const int n = static_cast<int>(free.size());
  std::array<std::array<double, kNumDof>, 2> q{}, rate{};
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < kNumDof; ++i) {
      const DofModel& dof = model.carriages[c].dofs[i];
      q[c][i] = dof.initial;
      if (dof.mode == DofMode::kPrescribed && dof.channel >= 0) {
        const double pct = gait_pct_at(model, t);
        q[c][i] += dof.scale * model.gait.value(dof.channel, pct);
        rate[c][i] = dof.scale * model.gait.derivative(dof.channel, pct) * 100.0 / model.period;
      }
    }
  }
  for (int k = 0; k < n; ++k) {
    q[free[k].carriage][free[k].dof] = y[k];
    rate[free[k].carriage][free[k].dof] = y[n + k];
  }
  state.time = t;
  for (int c = 0; c < 2; ++c) {
    const CarriageModel& cm = model.carriages[c];
    state.carriages[c].pivot_W = cm.pivot0_W + Eigen::Vector3d(q[c][0], q[c][1], q[c][2]);
    state.carriages[c].R_WB = gimbal_rotation({q[c][3], q[c][4], q[c][5]});
    state.carriages[c].rate = rate[c];
  }
}

}  // namespace

RunResult simulate_reference(const Model& model, State& state, Data& data,
                             const RunOptions& options) {
  std::vector<DofRef> free;
  for (int c = 0; c < 2; ++c)
    for (int i = 0; i < kNumDof; ++i) {
      const DofMode m = model.carriages[c].dofs[i].mode;
      if (m == DofMode::kFree || m == DofMode::kForce) free.push_back({c, i});
    }
  const int n = static_cast<int>(free.size());
  Eigen::VectorXd y(2 * n);
  update_kinematics(model, state, data);
  for (int k = 0; k < n; ++k) {
    y[k] = data.q[free[k].carriage][free[k].dof];
    y[n + k] = state.carriages[free[k].carriage].rate[free[k].dof];
  }
  State work = state;
  auto rhs = [&](double t, const Eigen::VectorXd& yy, Eigen::VectorXd& ydot) {
    fill_state(model, free, yy, t, work);
    calc_forces(model, work, data);
    for (int k = 0; k < n; ++k) {
      const DofModel& dof = model.carriages[free[k].carriage].dofs[free[k].dof];
      ydot[k] = yy[n + k];
      ydot[n + k] = (data.generalized[free[k].carriage][free[k].dof] - dof.damping * yy[n + k]) /
                    dof.mass;
    }
  };
  OdeOptions ode;
  ode.rtol = 1e-7;
  ode.atol = 1e-10;
  ode.method = OdeMethod::bdf;
  ode.max_step = model.period / 400.0;
  ode.max_steps = 1000000;
  OdeIntegrator integrator(2 * n, rhs, ode);
  const double t0 = state.time;
  integrator.reset(t0, y);

  RunResult result;
  const int frames = options.frames_per_cycle;
  const double frame_dt = model.period / frames;
  const int total = options.cycles * frames;
  for (int f = 1; f <= total; ++f) {
    const double t = t0 + f * frame_dt;
    try {
      integrator.advance_to(t, y);
    } catch (const std::exception&) {
      result.status = StepStatus::kNotFinite;
      result.failed_at = integrator.time();
      break;
    }
    if (!y.allFinite()) {
      result.status = StepStatus::kNotFinite;
      result.failed_at = t;
      break;
    }
    fill_state(model, free, y, t, state);
    calc_forces(model, state, data);
    if (f > total - frames) result.frames.push_back(make_frame(model, state, data));
    // the explicit step's checks, at each frame: a rig that runs away stops here too rather
    // than returning ranges of motion of hundreds of mm or a full turn as a result
    if (const StepStatus runaway = find_runaway(model, data); runaway != StepStatus::kOk) {
      result.status = runaway;
      result.failed_at = t;
      break;
    }
    if (options.progress) options.progress(static_cast<double>(f) / total);
  }
  // the last cycle's frames are at t = k * frame_dt after each cycle start; the first frame of
  // the explicit run is at 0 %, so rotate: record 0 % as the end of the previous cycle
  if (!result.frames.empty() && result.status == StepStatus::kOk) {
    Frame last = result.frames.back();
    result.frames.pop_back();
    last.gait_pct = 0.0;
    result.frames.insert(result.frames.begin(), last);
  }
  result.steps = integrator.num_steps();
  result.evaluations = data.evaluations;
  return result;
}

}  // namespace kneesim::engine
