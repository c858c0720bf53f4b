// Runs whole gait cycles on a const Model and records one frame per 1 % of the last cycle.
// The driver around step(): progress, frame sampling, the per-step observer used by wear, and
// the clean stop on numerical trouble (the frames recorded so far are kept).
#pragma once

#include <functional>
#include <vector>

#include "engine/data.h"
#include "engine/joint_coordinates.h"
#include "engine/model.h"
#include "engine/state.h"
#include "engine/step.h"

namespace kneesim::engine {

struct Frame {
  double gait_pct = 0.0;                                // [%]
  double time = 0.0;                                    // [s]
  std::array<std::array<double, kNumDof>, 2> q{};       // carriage DOF values [m or rad]
  JointCoordinates joint;                               // tibia relative to femur (outputs)
  std::array<std::array<double, kNumDof>, 2> applied{}; // waveform loads [N or N m]
  Eigen::Vector3d restraint = Eigen::Vector3d::Zero();  // AP force [N], IE torque [N m]
  ContactSummary contact;
  // area inside the contact line per condyle [m^2] (engine/contact_line.h), beside
  // contact.area's elements (nodes) with a positive pressure
  std::array<double, 2> contact_line_area{};
};

struct RunOptions {
  int cycles = 2;            // whole gait cycles; frames come from the last one
  int frames_per_cycle = 100;
  std::vector<double> map_pcts;  // gait % at which to keep the per-element pressure map
  std::function<void(double)> progress;  // fraction done, called now and then
  // called after every step of the last cycle (wear accumulation)
  std::function<void(const Model&, const State&, const Data&)> observer;
};

struct RunResult {
  StepStatus status = StepStatus::kOk;
  double failed_at = 0.0;             // time of the failure [s]
  std::vector<Frame> frames;          // last cycle, one per 1 %
  std::vector<std::vector<double>> maps;  // pressure [Pa] per articular element (rigid) or
                                          // per top-surface node (deformable), per map_pcts
  long steps = 0;
  long evaluations = 0;               // contact element evaluations
  double max_stability_ratio = 0.0;   // max over steps of omega_max dt / limit (< 1 stable)
  double omega_max = 0.0;             // highest contact frequency met [rad/s]
  int step_retries = 0;               // runs repeated with a shorter step (simulate_with_retry)
};

// the frame of the step just taken (data describes its start), with the area inside the
// contact line (evaluated here: outputs only)
Frame make_frame(const Model& model, const State& state, const Data& data);

RunResult simulate(const Model& model, State& state, Data& data, const RunOptions& options);

// the largest step with fraction `safety` of the central-difference limit for a contact
// frequency omega [rad/s] under the model's contact damping [s]
double find_step_for_frequency(const Model& model, double omega, double safety);

// the longest step not above `dt` that fits a whole number of times in the gait period [s]
double find_whole_cycle_step(const Model& model, double dt);

// simulate() with a fresh Data; the stable step is estimated before the run from a few static
// poses, and a contact area or load the estimate did not sample can stiffen the contact beyond
// it: when the stability monitor trips, the run is repeated from the same start state with the
// step the measured frequency allows (model.dt, a whole number per cycle), at most
// `max_retries` times. `state` advances only on the returned run; `before_attempt` (may be
// empty) resets what the observer accumulates.
RunResult simulate_with_retry(Model& model, State& state, const RunOptions& options,
                              double dt_safety, int max_retries = 4,
                              const std::function<void()>& before_attempt = {});

}  // namespace kneesim::engine
