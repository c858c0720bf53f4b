// The forward model of the forces diagnosis (issue 16): the force-controlled rig simulation of
// a config driven by measured loads, one simulation per measured gait cycle, with the
// compartment-force effects of the library applied to the built Model:
//   load_line     tibial VV torque = d x axial force: the axial load line moved medially by d
//                 (`kneesim run --set gait.vv_torque_axial_arm_mm=d`)
//   vv_moment     tibial VV torque = A x the stance shape of models/gait_assembly.h x axial
//                 force (`--set gait.vv_torque_stance_arm_mm=A`)
//   vv_alignment  the femoral component's VV angle (locked femoral VV) (`--set rig.femur_vv_deg=a`)
//   friction      contact friction coefficient (`--set contact.friction=mu`)
// Each is what build_model makes of the equivalent config keys (the same functions), so the
// Model (and the femoral distance field, seconds for a mesh implant) is built once; the femur
// is re-seated on the insert under the t = 0 load after every change (an aligned femur must
// not start inside the insert).
//
// Output per cycle: the medial and lateral compartment forces, one sample per 1 %, each the
// mean over its own 1 % of the cycle (the contact's chatter, sampled at an instant, aliased
// into the force as jitter between close parameter values): the simulated axial contact
// force split in the ratio of the condyles' normal forces (the load cells measure axial
// force; the engine sums normal forces per condyle, which lean by the coronal contact angle,
// a few degrees on this insert).
//
// Every evaluation is a full simulation; results are cached by (effect, parameter, cycle), and
// run_grid() evaluates a parameter grid (the diagnosis interpolates between grid points,
// forces_case.h).
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/diagnosis/effect.h"
#include "loads/iso14243/waveform.h"
#include "models/build_model.h"

namespace kneesim::diagnosis {

// one simulated cycle, one sample per 1 % (0..99 %)
struct ForcesTrace {
  std::vector<double> gait_pct;    // [%]
  std::vector<double> medial_N;    // medial compartment axial force [N]
  std::vector<double> lateral_N;   // lateral compartment axial force [N]
  bool ok = true;                  // false when the simulation stopped on numerical trouble
  std::string failure;             // why, when !ok
  // medial or lateral force at gait % (linear, periodic) [N]
  double at(bool medial, double pct) const;
  // medial share of the axial contact force at gait % (0.5 where the condyles carry nothing)
  double share(double pct) const;
};

// one measured cycle as the rig is driven: the config's gait with the cycle's measured channels
struct ForcesCycle {
  std::string name;         // e.g. "cycle 1"
  loads::Waveform gait;     // merged gait waveform (models::make_gait with this cycle)
  double period_s = 1.0;    // [s]
};

class ForcesSimulator {
 public:
  ForcesSimulator(const models::Config& config, std::vector<ForcesCycle> cycles);

  struct Key {
    Effect effect = Effect::none;
    double value = 0.0;  // [I/O units]
    int cycle = 0;
  };

  // the trace of `effect` with parameter `value` [I/O units] for cycle `cycle`
  std::shared_ptr<const ForcesTrace> run(Effect effect, double value, int cycle);
  // runs every key not cached yet, `threads` simulations at a time, each on its own copy of the
  // Model (results do not depend on the thread count)
  void run_many(const std::vector<Key>& keys);
  void set_threads(int threads) { threads_ = threads; }
  // samples at an instant instead of the means over their 1 % (diagnostics of the aliasing
  // the means remove; forces_sim_test.cpp); clears the cache
  void set_instant_samples(bool instant) {
    instant_samples_ = instant;
    cache_.clear();
  }

  // `kneesim run` overrides that reproduce run(effect, value, .)
  std::string equivalent_sets(Effect effect, double value) const;

  const models::Config& config() const { return config_; }
  int cycles() const { return static_cast<int>(cycles_.size()); }
  const ForcesCycle& cycle(int i) const { return cycles_[static_cast<size_t>(i)]; }
  int simulations() const { return simulations_; }
  double seconds() const { return seconds_; }
  double build_seconds() const { return build_seconds_; }

 private:
  models::Config config_;
  models::BuiltModel built_;
  std::vector<ForcesCycle> cycles_;
  engine::DofMode tibia_vv_mode0_ = engine::DofMode::kFree;
  double femur_vv0_ = 0.0;     // as built [rad]
  double friction0_ = 0.07;    // as built [-]
  std::shared_ptr<const ForcesTrace> simulate(Effect effect, double value, int cycle) const;
  std::map<std::tuple<int, double, int>, std::shared_ptr<const ForcesTrace>> cache_;
  int threads_ = 1;
  bool instant_samples_ = false;
  int simulations_ = 0;
  double seconds_ = 0.0;
  double build_seconds_ = 0.0;
};

}  // namespace kneesim::diagnosis
