// Export of the deformable insert's contact problem at chosen gait instants, for an independent
// finite-element code (tools/scripts/ccx_crosscheck.py writes a CalculiX deck from it and
// compares; docs/deformable.md, "Cross-check against CalculiX").
//
// What is exported is what a second code needs to solve the same problem and what kneesim
// found, with nothing re-derived: the hex mesh of the insert exactly as kneesim integrates it
// (reference nodes, elements in engine/solid/hex8.h order, top faces and the element under
// each, base nodes), its material, the femoral component's triangle mesh (frame F, the mesh
// kneesim's distance field was built from), and per instant the pose of F in T (the insert
// frame, in which the solid is integrated) with kneesim's results at that pose: per top node
// the penalty pressure, tributary area and penalty stiffness, per element the von Mises stress
// (one-point, of the second Piola-Kirchhoff stress) and the plastic strain, and the deformed
// node positions.
//
// The instant: the first step of the last cycle at or after gait_pct (within half a step), the
// rule the pressure maps use. The pose, the pressures and the stresses are all those of the
// start of that step (time t): the observer sees the state after the step (t + dt), so the
// node positions are taken back by one step, x(t) = x(t + dt) - dt v(t + dt/2), which is the
// central-difference update undone.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"
#include "engine/waveform.h"
#include "models/build_model.h"

namespace kneesim::run {

// heel strike (0 %) and the two highest local maxima of the axial force channel of the gait,
// in time order (the shipped ISO 14243-1-shaped gait: 0, 13 and 45 %); gait % to 0.1 %.
// Throws InputError when the waveform has no axial_force_N channel or fewer than two maxima.
std::vector<double> find_heel_strike_and_load_peaks(const engine::Waveform& gait);

// the exported instants, captured by observe() over the last cycle of a run
class FeExportRecorder {
 public:
  // pcts: gait % of the instants, ascending, in [0, 100)
  FeExportRecorder(const engine::Model& model, std::vector<double> pcts);
  // called after every step of the last cycle (RunOptions::observer)
  void observe(const engine::Model& model, const engine::State& state, const engine::Data& data);
  bool complete() const { return instants_.size() == pcts_.size(); }
  const std::vector<nlohmann::json>& instants() const { return instants_; }
  // forgets what was recorded (a run repeated with a shorter step)
  void clear() {
    instants_.clear();
    started_ = false;
  }

 private:
  std::vector<double> pcts_;
  bool started_ = false;     // the first step of the last cycle was observed
  double last_start_ = 0.0;  // time the last cycle starts [s]
  std::vector<nlohmann::json> instants_;
};

// the export document: mesh, material, femur and the recorded instants (units: mm, N, MPa)
nlohmann::json make_fe_export(const models::BuiltModel& built, const models::Config& config,
                              const FeExportRecorder& recorder);

}  // namespace kneesim::run
