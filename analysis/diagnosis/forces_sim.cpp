#include "analysis/diagnosis/forces_sim.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <thread>

#include "analysis/diagnosis/text_format.h"
#include "engine/simulate.h"
#include "engine/stable_step.h"
#include "engine/step.h"
#include "models/gait_assembly.h"

namespace kneesim::diagnosis {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr size_t kCacheLimit = 4096;

}  // namespace

double ForcesTrace::at(bool medial, double pct) const {
  const std::vector<double>& y = medial ? medial_N : lateral_N;
  const size_t n = gait_pct.size();
  if (n == 0) return NAN;
  pct = std::fmod(pct, 100.0);
  if (pct < 0.0) pct += 100.0;
  // periodic: between the last sample and the first one of the next cycle
  if (pct >= gait_pct.back()) {
    const double span = gait_pct.front() + 100.0 - gait_pct.back();
    const double t = span > 0.0 ? (pct - gait_pct.back()) / span : 0.0;
    return y.back() + t * (y.front() - y.back());
  }
  if (pct <= gait_pct.front()) return y.front();
  size_t i = 1;
  while (i < n - 1 && gait_pct[i] < pct) ++i;
  const double t = (pct - gait_pct[i - 1]) / (gait_pct[i] - gait_pct[i - 1]);
  return y[i - 1] + t * (y[i] - y[i - 1]);
}

double ForcesTrace::share(double pct) const {
  const double m = at(true, pct), l = at(false, pct);
  return m + l > 0.0 ? m / (m + l) : 0.5;
}

ForcesSimulator::ForcesSimulator(const models::Config& config, std::vector<ForcesCycle> cycles)
    : config_(config), built_(models::build_model(config)), cycles_(std::move(cycles)) {
  tibia_vv_mode0_ = built_.model.carriages[1].dofs[3].mode;
  femur_vv0_ = built_.model.carriages[0].dofs[3].initial;
  friction0_ = built_.model.contact.friction;
  build_seconds_ = built_.build_seconds;
}

std::shared_ptr<const ForcesTrace> ForcesSimulator::run(Effect effect, double value, int cycle) {
  run_many({{effect, value, cycle}});
  return cache_.at(std::make_tuple(static_cast<int>(effect), effect == Effect::none ? 0.0 : value,
                                   cycle));
}

void ForcesSimulator::run_many(const std::vector<Key>& keys) {
  std::vector<Key> todo;
  for (Key k : keys) {
    if (k.effect == Effect::none) k.value = 0.0;
    const auto key = std::make_tuple(static_cast<int>(k.effect), k.value, k.cycle);
    bool queued = cache_.count(key) > 0;
    for (const Key& q : todo) {
      queued = queued || (q.effect == k.effect && q.value == k.value && q.cycle == k.cycle);
    }
    if (!queued) todo.push_back(k);
  }
  if (todo.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::shared_ptr<const ForcesTrace>> traces(todo.size());
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t i = next++; i < todo.size(); i = next++) {
      traces[i] = simulate(todo[i].effect, todo[i].value, todo[i].cycle);
    }
  };
  std::vector<std::thread> pool;
  const int n = std::max(1, std::min<int>(threads_, static_cast<int>(todo.size())));
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  if (cache_.size() + todo.size() > kCacheLimit) cache_.clear();
  for (size_t i = 0; i < todo.size(); ++i) {
    cache_[std::make_tuple(static_cast<int>(todo[i].effect), todo[i].value, todo[i].cycle)] =
        traces[i];
  }
  simulations_ += static_cast<int>(todo.size());
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::shared_ptr<const ForcesTrace> ForcesSimulator::simulate(Effect effect, double value,
                                                             int cycle) const {
  // a copy of the Model as built, with this cycle's loads and the effect applied
  engine::Model model = built_.model;
  const ForcesCycle& cyc = cycles_[static_cast<size_t>(cycle)];
  model.period = cyc.period_s;
  model.contact.friction = effect == Effect::friction ? value : friction0_;
  engine::DofModel& femur_vv = model.carriages[0].dofs[3];
  femur_vv.initial = effect == Effect::vv_alignment ? value * kDeg : femur_vv0_;
  const double arm_mm = effect == Effect::load_line ? value : config_.vv_torque_axial_arm_mm;
  const double stance_arm_mm = effect == Effect::vv_moment ? value : config_.vv_torque_stance_arm_mm;
  model.gait = models::with_vv_torque(cyc.gait, arm_mm, stance_arm_mm, config_.axial_force_scale);
  engine::DofModel& tibia_vv = model.carriages[1].dofs[3];
  tibia_vv.mode = tibia_vv_mode0_;
  tibia_vv.channel = -1;
  // a free tibial VV starts aligned with the femur, as build_model does
  tibia_vv.initial = tibia_vv.mode == engine::DofMode::kFree ? femur_vv.initial : 0.0;
  const int vv_channel = model.gait.channel("vv_torque_Nm");
  if (vv_channel >= 0 && (tibia_vv.mode == engine::DofMode::kFree ||
                          tibia_vv.mode == engine::DofMode::kForce)) {
    tibia_vv.mode = engine::DofMode::kForce;
    tibia_vv.channel = vv_channel;
    tibia_vv.scale = 1.0;
  }
  // seat the femur on the insert under the t = 0 load (as build_model does)
  engine::DofModel& femur_is = model.carriages[0].dofs[1];
  {
    femur_is.initial = 0.0;
    engine::State s = engine::make_initial_state(model);
    engine::Data d = engine::make_data(model);
    const double load0 =
        femur_is.channel >= 0 ? -femur_is.scale * model.gait.value(femur_is.channel, 0.0) : 0.0;
    engine::position_femur_statically(model, s, d, std::max(load0, 1.0));
    femur_is.initial = s.carriages[0].pivot_W.y() - model.carriages[0].pivot0_W.y();
  }
  // the gait run's step retry at the stability limit (analysis/run)
  engine::State state = engine::make_initial_state(model);
  engine::RunOptions ro;
  ro.cycles = config_.cycles;
  // each output sample is the mean over its own 1 % of the cycle (centred on it), not the
  // instant: sampled at an instant, the contact's fast oscillation on the faceted insert
  // aliased into the medial force as jitter between close parameter values (second
  // difference over 0.5 deg of alignment 10-14 N RMS at an instant, 2-3 N as the mean;
  // forces forward jitter). The mean is the anti-aliasing filter a decimation needs
  const int frames = ro.frames_per_cycle;
  // per frame of the last cycle: medial, lateral, axial [N], steps
  std::vector<std::array<double, 4>> sums;
  if (!instant_samples_) {
    ro.observer = [&sums, frames](const engine::Model& m, const engine::State& s,
                                  const engine::Data& d) {
      if (sums.empty()) sums.assign(static_cast<size_t>(frames), {0.0, 0.0, 0.0, 0.0});
      // the data describe the start of the step just taken; the last cycle starts at a
      // multiple of the period, and frame k at k / frames of it
      const double phase = std::fmod((s.time - m.dt) / m.period, 1.0);
      const int k = static_cast<int>(std::floor(phase * frames + 0.5)) % frames;
      auto& a = sums[static_cast<size_t>(std::max(k, 0))];
      a[0] += d.contact.normal_force[0];
      a[1] += d.contact.normal_force[1];
      a[2] += d.contact.force_W.y();
      a[3] += 1.0;
    };
  }
  const engine::RunResult r = engine::simulate_with_retry(model, state, ro, built_.dt_safety, 4,
                                                          [&sums] { sums.clear(); });

  auto trace = std::make_shared<ForcesTrace>();
  trace->ok = r.status == engine::StepStatus::kOk && !r.frames.empty();
  if (!trace->ok) trace->failure = engine::to_string(r.status);
  for (size_t i = 0; i < r.frames.size(); ++i) {
    const engine::Frame& f = r.frames[i];
    std::array<double, 4> a = {f.contact.normal_force[0], f.contact.normal_force[1],
                               f.contact.force_W.y(), 1.0};  // the instant if no mean
    if (i < sums.size() && sums[i][3] > 0.0) a = sums[i];
    const double med = a[0] / a[3], lat = a[1] / a[3];
    const double axial = a[2] / a[3];  // axial contact force (+ compressive)
    const double share = med + lat > 0.0 ? med / (med + lat) : 0.5;
    trace->gait_pct.push_back(f.gait_pct);
    trace->medial_N.push_back(share * std::max(axial, 0.0));
    trace->lateral_N.push_back((1.0 - share) * std::max(axial, 0.0));
  }
  return trace;
}

std::string ForcesSimulator::equivalent_sets(Effect effect, double value) const {
  switch (effect) {
    case Effect::load_line: return "--set gait.vv_torque_axial_arm_mm=" + fmt("%.4g", value);
    case Effect::vv_moment: return "--set gait.vv_torque_stance_arm_mm=" + fmt("%.4g", value);
    case Effect::vv_alignment: return "--set rig.femur_vv_deg=" + fmt("%.4g", value);
    case Effect::friction: return "--set contact.friction=" + fmt("%.4g", value);
    case Effect::none:
    case Effect::running_in:
    case Effect::pressure_dependent_wear:
    case Effect::cross_shear:
    case Effect::creep:
    case Effect::incubation:
    case Effect::restraint:
    case Effect::load_convention: break;
  }
  return "";
}

}  // namespace kneesim::diagnosis
