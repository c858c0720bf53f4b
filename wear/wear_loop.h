// The wear outer loop (design.md "wear is an outer loop"): simulate one gait cycle on a const
// Model while accumulating Archard depth, scale it by the cycles of this update, recede the
// insert, rebuild the insert part of the Model, and continue. After every update the state
// needed to continue is checkpointed atomically (wear/checkpoint.h), so a killed run resumes
// to a bit-identical result.
//
// Both inserts run through the same loop (wear/worn_insert.h): the rigid insert's articular
// vertices recede and its surface elements are rebuilt; the deformable insert's top nodes
// recede, its columns are re-graded and its solid is rebuilt, the State carried onto it.
//
// If an update would invert or collapse a face (rigid) or an element (deformable) of the
// insert, the update is refined: its cycle count is halved (the per-cycle depth rate is kept)
// until none does; the number of refinements is reported per update.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/simulate.h"
#include "models/build_model.h"
#include "wear/wear_accumulator.h"
#include "wear/worn_insert.h"

namespace kneesim::wear {

// one row of wear.csv (SI inside; converted at output): the insert after `cycles` cycles; its
// kinematic and contact figures are those of a settled gait cycle simulated on that geometry
// (row 0: the pristine insert, the same cycle `kneesim run` reports)
struct UpdateRecord {
  double cycles = 0;               // cycles completed after this update
  double volume = 0;               // enclosed-volume loss of the insert [m^3]
  double volume_depth = 0;         // integral of the depth field [m^3]
  double max_depth = 0;            // [m]
  double medial_volume = 0;        // depth integral over the medial side [m^3]
  double lateral_volume = 0;       // [m^3]
  double contact_area = 0;         // mean over the simulated cycle's frames in contact [m^2]
  double peak_pressure = 0;        // max over the cycle [Pa]
  double mean_peak_pressure = 0;   // mean of the frame peaks [Pa]
  double ap_rom = 0;               // [m]
  double ie_rom = 0;               // [rad]
  double refinements = 0;          // interval halvings needed to avoid inverted faces
  // deformable insert (0 for the rigid one): largest von Mises stress over the cycle and the
  // equivalent plastic strain at its end, surface layer and subsurface
  double von_mises_surface = 0;    // [Pa]
  double von_mises_subsurface = 0; // [Pa]
  double plastic_strain_surface = 0;     // [-]
  double plastic_strain_subsurface = 0;  // [-]
  // the solid's kinetic/internal energy ratio over the cycle (engine/solid/energy_ratio.h):
  // largest over the loaded steps, and of the cycle sums (quasi-static validity, below 5 %)
  double kinetic_to_internal_max = 0;    // [-]
  double kinetic_to_internal_cycle = 0;  // [-]
  // what does not depend on the wear factor (wear/wear_accumulator.h), of the same cycle:
  // the volume per cycle per unit factor (volume = k x potential), the load-weighted slip,
  // the sliding-work-weighted cross-shear ratio, and the mean contact pressure over stance
  double wear_potential = 0;       // [J] = [m^3 / (m^2/N)]
  double sliding_distance = 0;     // [m]
  double cross_shear = 0;          // [-]
  double stance_mean_pressure = 0; // mean over the frames of 0-60 % in contact of force/area [Pa]
  // creep (wear.creep): the largest creep penetration and the largest penetration of wear
  // and creep together, as a CMM or radiograph measures it (0 without creep: wear alone) [m]
  double max_creep_depth = 0;
  double max_penetration = 0;
  static constexpr int kFields = 24;
};

// the enclosed-volume loss and the depth integral of a closed insert differ by this fraction
// at most in a sound run; beyond it the geometry update has gone wrong and the run is not
// complete. They agree within 1 % for the default run (docs/validation.md); deep scars on curved
// surfaces differ by a few per cent (a curved surface receding along its normals changes its
// area; tests/wear/deep_wear_test.cpp reaches 2.5 %), so the bound is 10 %.
inline constexpr double kVolumeBookkeepingTolerance = 0.10;

// why an update record cannot be part of a finished result ("" when it can): a non-finite
// figure, or (closed insert, some wear) volume bookkeeping beyond kVolumeBookkeepingTolerance
std::string check_update_record(const UpdateRecord& r, bool closed_insert);

struct WearOptions {
  long total_cycles = 5'000'000;
  std::vector<long> schedule;      // cycles per update, repeated last; empty -> update_every
  long update_every = 250'000;
  WearLawParams law;
  uint64_t identity = 0;           // hash of everything that defines the run (checkpoints)
  std::filesystem::path checkpoint;  // "" for none
  bool resume = false;
  std::function<void(double)> progress;
  // whenever a record is complete, i.e. once the cycle on its geometry has been simulated (row
  // 0 after the first wear cycle, row k at the start of update k + 1, the last row after one
  // more cycle on the final geometry): all records so far and the cumulative depth per
  // articular vertex
  std::function<void(const std::vector<UpdateRecord>&, const std::vector<double>&)> on_update;
  // after every update: the receded insert (for forward models that follow the geometry,
  // analysis/diagnosis/knee_wear_table.h)
  std::function<void(const models::TriMesh&)> on_insert;
};

struct WearResult {
  engine::StepStatus status = engine::StepStatus::kOk;
  std::string message;                  // why it stopped early
  std::vector<UpdateRecord> records;    // cycle 0 first
  std::vector<double> vertex_depth;     // cumulative, per wear site [m]: articular vertex
                                        // (rigid) or top node (deformable, insert_contact order)
  std::vector<double> vertex_creep;     // creep penetration per wear site at the end [m]
  models::TriMesh worn;                 // the rigid insert after the last update (empty for
                                        // the deformable insert: worn_insert has its nodes)
  WornInsert worn_insert;               // the worn geometry (wear/worn_insert.h)
  engine::Model final_model;            // the model on the final geometry
  engine::State final_state;            // the state the last cycle ended in
  std::vector<double> von_mises_max;    // deformable: per element over the last cycle [Pa]
  std::vector<engine::Frame> frames;    // the last simulated cycle (on the final geometry)
  int resumed_from_update = -1;         // update index the run resumed after, -1 if fresh
};

// the wear potential of the whole run with its geometry updates: each geometry's potential per
// cycle times the (law-weighted, effective_cycles) cycles run on it [J]; times k it is the
// depth-integral volume (exactly so while the geometry is the pristine one)
double calc_run_wear_potential(const std::vector<UpdateRecord>& records, const WearLawParams& law);

// the time step of the next wear cycle [s]: the current one (model.dt), shortened to dt_safety
// of the stability limit at the contact frequency omega_max [rad/s] (the loop passes the
// highest one the last completed cycle met times an allowance for the stiffening the next
// update brings), in whole steps per gait cycle; never lengthened. Continuous in omega_max, so
// that a run's result does not jump when a wear factor (or anything else) moves the worn
// geometry's stiffness by a hair: a threshold here changes the step of every later cycle by a
// finite amount, and a cycle's wear potential moves with the step (pristine CFR-PEEK insert,
// stanmore rig: 59076 N mm at solver.dt_safety 0.8, 59538 at 0.4, 59948 at 0.2).
double next_cycle_step(const engine::Model& model, double omega_max, double dt_safety);

// the interval of update number u (0-based)
long update_interval(const WearOptions& options, int u);

WearResult run_wear(const models::BuiltModel& pristine, const WearOptions& options);

}  // namespace kneesim::wear
