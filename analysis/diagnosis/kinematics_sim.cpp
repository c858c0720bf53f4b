#include "analysis/diagnosis/kinematics_sim.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <thread>

#include "analysis/diagnosis/text_format.h"
#include "engine/simulate.h"
#include "loads/iso14243/conventions.h"

namespace kneesim::diagnosis {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

}  // namespace

double KinematicsTrace::at(const std::string& quantity, double pct) const {
  const std::vector<double>& y = (quantity == "ie_deg") ? ie_deg : ap_mm;
  const size_t n = gait_pct.size();
  if (n == 0) return NAN;
  if (pct <= gait_pct.front()) return y.front();
  if (pct >= gait_pct.back()) return y.back();
  size_t i = 1;
  while (i < n - 1 && gait_pct[i] < pct) ++i;
  const double t = (pct - gait_pct[i - 1]) / (gait_pct[i] - gait_pct[i - 1]);
  return y[i - 1] + t * (y[i] - y[i - 1]);
}

KinematicsSimulator::KinematicsSimulator(const models::Config& config)
    : config_(config), built_(models::build_model(config)) {
  restraint0_ = built_.model.restraint;
  friction0_ = built_.model.contact.friction;
  gait0_ = built_.model.gait;
  for (int c = 0; c < 2; ++c) {
    for (int d = 0; d < engine::kNumDof; ++d) {
      const engine::DofModel& dof = built_.model.carriages[static_cast<size_t>(c)].dofs[static_cast<size_t>(d)];
      if (dof.mode != engine::DofMode::kForce || dof.channel < 0) continue;
      const std::string& name = gait0_.channel_name(dof.channel);
      if (name == "ap_force_N") ap_force_dofs_.push_back({c, d, dof.scale});
      if (name == "ie_torque_Nm") ie_torque_dofs_.push_back({c, d, dof.scale});
    }
  }
  build_seconds_ = built_.build_seconds;
}

double KinematicsSimulator::nominal_gap_mm() const {
  for (const engine::RestraintSpring& s : restraint0_) {
    if (s.kind == engine::RestraintKind::kTranslational) return s.gap * 1e3;
  }
  return 0.0;
}

std::vector<double> KinematicsSimulator::key_of(Effect effect, const Eigen::VectorXd& params) const {
  std::vector<double> key = {static_cast<double>(effect)};
  if (effect == Effect::friction || effect == Effect::restraint ||
      effect == Effect::load_convention) {
    key.insert(key.end(), params.data(), params.data() + params.size());
  }
  return key;
}

std::shared_ptr<const KinematicsTrace> KinematicsSimulator::run(Effect effect,
                                                                const Eigen::VectorXd& params) {
  return run_many(effect, {params}).front();
}

std::vector<std::shared_ptr<const KinematicsTrace>> KinematicsSimulator::run_many(
    Effect effect, const std::vector<Eigen::VectorXd>& params) {
  std::vector<std::vector<double>> keys;
  for (const auto& p : params) keys.push_back(key_of(effect, p));
  std::vector<size_t> mine;  // indices of the keys this call simulates
  {
    std::lock_guard lock(mutex_);
    for (size_t i = 0; i < keys.size(); ++i) {
      if (cache_.count(keys[i]) || running_.count(keys[i])) continue;
      running_.insert(keys[i]);
      mine.push_back(i);
    }
  }
  // this call's simulations, at most `threads` at a time over all callers: a worker takes an
  // idle Model copy (or makes one while fewer than `threads` exist) and waits when there is none
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t k = next++; k < mine.size(); k = next++) {
      std::unique_ptr<engine::Model> model;
      {
        std::unique_lock lock(mutex_);
        done_.wait(lock, [&] { return !idle_models_.empty() || models_made_ < threads_; });
        if (idle_models_.empty()) {
          ++models_made_;
          lock.unlock();
          model = std::make_unique<engine::Model>(built_.model);
          // simulations run side by side: one thread each (the contact loop's result does
          // not depend on its thread count)
          if (threads_ > 1) model->threads = 1;
        } else {
          model = std::move(idle_models_.back());
          idle_models_.pop_back();
        }
      }
      const auto t0 = std::chrono::steady_clock::now();
      auto trace = simulate(*model, effect, params[mine[k]]);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      {
        std::lock_guard lock(mutex_);
        idle_models_.push_back(std::move(model));
        cache_[keys[mine[k]]] = std::move(trace);
        running_.erase(keys[mine[k]]);
        ++simulations_;
        seconds_ += seconds;
      }
      done_.notify_all();
    }
  };
  std::vector<std::thread> pool;
  const int helpers = std::min<int>(threads_, static_cast<int>(mine.size())) - 1;
  for (int t = 0; t < helpers; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  // the keys other callers were simulating
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] {
    return std::all_of(keys.begin(), keys.end(), [&](const auto& k) { return cache_.count(k) > 0; });
  });
  std::vector<std::shared_ptr<const KinematicsTrace>> out;
  for (const auto& k : keys) out.push_back(cache_.at(k));
  return out;
}

std::shared_ptr<const KinematicsTrace> KinematicsSimulator::simulate(
    engine::Model& model, Effect effect, const Eigen::VectorXd& params) const {
  model.contact.friction = friction0_;
  model.restraint = restraint0_;
  model.gait = gait0_;
  auto set_scale = [&model](const std::vector<ForceDof>& dofs, double factor) {
    for (const ForceDof& f : dofs) {
      model.carriages[static_cast<size_t>(f.carriage)].dofs[static_cast<size_t>(f.dof)].scale =
          f.scale * factor;
    }
  };
  set_scale(ap_force_dofs_, 1.0);
  set_scale(ie_torque_dofs_, 1.0);
  if (effect == Effect::load_convention) {
    // what build_model makes of gait.ap_sign/ap_force_scale/ap_force_shift_pct and the IE
    // equivalents: the channel scaled on its DOF, the waveform delayed
    set_scale(ap_force_dofs_, params[0]);
    set_scale(ie_torque_dofs_, params[2]);
    model.gait = loads::delay_channels(gait0_, {{"ap_force_N", params[1]},
                                                {"ie_torque_Nm", params[3]}});
  }
  if (effect == Effect::friction) model.contact.friction = params[0];
  if (effect == Effect::restraint) {
    for (engine::RestraintSpring& s : model.restraint) {
      s.k_inside *= params[0];
      s.k_positive *= params[0];
      s.k_negative *= params[0];
      if (s.kind == engine::RestraintKind::kTranslational) s.gap = params[1] * 1e-3;
    }
  }
  // the gait run's step retry at the stability limit (analysis/run); the shortened step is
  // this evaluation's only, the next starts from the estimated one
  engine::State state = engine::make_initial_state(model);
  engine::RunOptions ro;
  ro.cycles = config_.cycles;
  const double dt_estimated = model.dt;
  const engine::RunResult r = engine::simulate_with_retry(model, state, ro, built_.dt_safety);
  model.dt = dt_estimated;

  auto trace = std::make_shared<KinematicsTrace>();
  trace->ok = r.status == engine::StepStatus::kOk && !r.frames.empty();
  for (const engine::Frame& f : r.frames) {
    trace->gait_pct.push_back(f.gait_pct);
    trace->ap_mm.push_back(f.joint.ap * 1e3);
    trace->ie_deg.push_back(f.joint.ie * kRadToDeg);
  }
  return trace;
}

std::string KinematicsSimulator::equivalent_sets(Effect effect, const Eigen::VectorXd& p) const {
  switch (effect) {
    case Effect::friction: return "--set contact.friction=" + fmt("%.4g", p[0]);
    case Effect::restraint: {
      const models::Config& c = config_;
      std::string s = "--set rig.restraint.gap_mm=" + fmt("%.4g", p[1]);
      auto scaled = [&](const char* key, double v) {
        if (v > 0.0) s += std::string(" --set rig.restraint.") + key + "=" + fmt("%.4g", v * p[0]);
      };
      scaled("k_anterior_N_per_mm", c.k_anterior_N_per_mm);
      scaled("k_posterior_N_per_mm", c.k_posterior_N_per_mm);
      scaled("k_inside_N_per_mm", c.k_inside_N_per_mm);
      scaled("k_ie_inside_Nm_per_deg", c.k_ie_inside_Nm_per_deg);
      scaled("k_ie_Nm_per_deg", c.k_ie_Nm_per_deg);
      return s;
    }
    case Effect::load_convention: {
      // gait.ap_sign flips the file's AP channels; the scale keys take magnitudes
      std::string s;
      if (p[0] < 0.0) s += "--set gait.ap_sign=-1 ";
      s += "--set gait.ap_force_scale=" + fmt("%.4g", std::abs(p[0])) +
           " --set gait.ap_force_shift_pct=" + fmt("%.4g", p[1]);
      if (p[2] < 0.0) s += " --set gait.ie_sign=-1";
      s += " --set gait.ie_torque_scale=" + fmt("%.4g", std::abs(p[2])) +
           " --set gait.ie_torque_shift_pct=" + fmt("%.4g", p[3]);
      return s;
    }
    case Effect::none:
    case Effect::running_in:
    case Effect::pressure_dependent_wear:
    case Effect::cross_shear:
    case Effect::creep:
    case Effect::incubation: break;
    case Effect::load_line:
    case Effect::vv_moment:
    case Effect::vv_alignment: break;
  }
  return "";
}

}  // namespace kneesim::diagnosis
