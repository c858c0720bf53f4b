// The forward model of the kinematics diagnosis: the force-controlled rig simulation of a
// config, with the two kinematic effects of the library applied to the built Model:
//   friction   contact.friction = mu                       (`kneesim run --set contact.friction=mu`)
//   restraint  every restraint stiffness scaled by s, the AP spring gap set to g
//              (`kneesim run --set rig.restraint.k_anterior_N_per_mm=... gap_mm=g ...`)
//   load_convention  the AP force and IE torque scaled (sign included) and delayed
//              (`kneesim run --set gait.ap_sign=-1 --set gait.ap_force_scale=|s|
//               --set gait.ap_force_shift_pct=d ...`)
// Both are exactly what build_model makes of the equivalent config keys (the restraint is
// linear in its stiffnesses), so the Model is built once (the femoral distance field of a mesh
// implant takes seconds) and only these fields change between evaluations; equivalent_sets()
// prints the --set list that reproduces an evaluation with `kneesim run`.
//
// Every evaluation is a full simulation (config.cycles gait cycles), so results are cached by
// (effect, parameters): the diagnosis asks for the same parameters for several row subsets
// (folds, offsets). The simulator is thread-safe: fits running side by side share its cache,
// and at most `threads` simulations run at a time, each on its own copy of the Model; a
// simulation depends only on its effect and parameters, so every result is bit-identical for
// any thread count. Every evaluation starts from the initial state: the rig's last cycle
// depends on where it started (run one cycle from the configured rig's settled state instead,
// the DM rig's last cycle differs by up to 3.6 mm AP or deg IE from the fresh run's, whose own
// last cycle is periodic to 0.002; tests/diagnosis_knee/kinematics_sim_long.cpp), so a settled
// start is not a cheaper equivalent. The time step is kept: the restraint is 3-4
// orders softer than the contact, and friction is bounded (0-0.3) so the regularized Coulomb
// slope stays stable.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <condition_variable>
#include <map>
#include <mutex>
#include <set>
#include <memory>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"
#include "loads/iso14243/waveform.h"
#include "models/build_model.h"

namespace kneesim::diagnosis {

// one simulated cycle, one sample per 1 % (101 samples, 0..100 %)
struct KinematicsTrace {
  std::vector<double> gait_pct;  // [%]
  std::vector<double> ap_mm;     // tibial AP, + anterior [mm]
  std::vector<double> ie_deg;    // tibial IE, + internal [deg]
  bool ok = true;                // false when the simulation stopped on numerical trouble
  // value of "ap_mm" or "ie_deg" at gait % (linear, periodic) [mm or deg]
  double at(const std::string& quantity, double pct) const;
};

class KinematicsSimulator {
 public:
  explicit KinematicsSimulator(const models::Config& config);

  // the trace of `effect` with its parameters [I/O units] (none: the config as it is)
  std::shared_ptr<const KinematicsTrace> run(Effect effect, const Eigen::VectorXd& params);
  // runs every (effect, parameters) not cached yet, at most `threads` simulations at a time
  // (over all callers), and returns the traces in the order of `params`
  std::vector<std::shared_ptr<const KinematicsTrace>> run_many(
      Effect effect, const std::vector<Eigen::VectorXd>& params);
  // simulations run at a time (set before the first run) [-]
  void set_threads(int threads) { threads_ = std::max(1, threads); }
  int threads() const { return threads_; }

  // `kneesim run` overrides that reproduce run(effect, params)
  std::string equivalent_sets(Effect effect, const Eigen::VectorXd& params) const;

  const models::Config& config() const { return config_; }
  // the model's friction coefficient and AP laxity gap as built (the null values of the
  // friction and restraint effects) [-] and [mm]
  double nominal_friction() const { return friction0_; }
  double nominal_gap_mm() const;
  int simulations() const { return simulations_; }   // evaluations not served by the cache
  double seconds() const { return seconds_; }  // wall time of those evaluations, summed [s]
  double build_seconds() const { return build_seconds_; }  // model build [s]

 private:
  models::Config config_;
  models::BuiltModel built_;
  std::vector<engine::RestraintSpring> restraint0_;  // as built
  double friction0_ = 0.07;                          // as built [-]
  loads::Waveform gait0_;                            // as built
  struct ForceDof {
    int carriage = 0, dof = 0;  // indices into Model::carriages and its dofs
    double scale = 1.0;         // as built [SI per channel unit]
  };
  std::vector<ForceDof> ap_force_dofs_, ie_torque_dofs_;  // DOFs driven by those channels
  std::shared_ptr<const KinematicsTrace> simulate(engine::Model& model, Effect effect,
                                                  const Eigen::VectorXd& params) const;
  std::vector<double> key_of(Effect effect, const Eigen::VectorXd& params) const;
  std::mutex mutex_;                  // guards everything below
  std::condition_variable done_;      // a simulation finished
  std::map<std::vector<double>, std::shared_ptr<const KinematicsTrace>> cache_;
  std::set<std::vector<double>> running_;
  std::vector<std::unique_ptr<engine::Model>> idle_models_;  // copies of the built Model
  int models_made_ = 0;
  int threads_ = 1;
  int simulations_ = 0;
  double seconds_ = 0.0;
  double build_seconds_ = 0.0;
};

}  // namespace kneesim::diagnosis
