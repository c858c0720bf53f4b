// The knee-wear diagnosis case (issue 4, `kneesim diagnose knee-wear`). Measured data: CSV with
// columns condition, cycles, volume_mm3 and optional max_depth_mm and specimen; every condition
// named in it is a [conditions.<name>] of the config (a list of "key=value" overrides, e.g.
// different IE torque scales or loads).
//
// Forward model: knee_wear_table.h, one simulated cycle per condition on the pristine insert,
// wear linear in cycles (the approximation is stated in the report and checked against the
// full wear loop by the command).
// Calibration rule (practitioners): k from the least-squares slope of volume against cycles
// over the steady-state points (cycles >= steady_state_from) of one calibration condition.
// Held-out split: leave-one-specimen-out when every condition has two or more specimens,
// otherwise leave-one-condition-out.
// Candidates: running_in always; pressure_dependent_wear when two conditions differ in mean
// contact pressure by more than 5 %; cross_shear when two conditions differ in mean
// cross-shear ratio by more than 10 % (two kinematic conditions); creep when depth was measured.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnosis_case.h"
#include "analysis/diagnosis/knee_wear_table.h"

namespace kneesim::diagnosis {

struct KneeWearCaseOptions {
  std::string calibration_condition;   // condition of the calibration; "" = first in the data
  double steady_state_from = 5e5;      // first cycle count of the steady state [cycles]
};

using KneeWearTables = std::map<std::string, std::shared_ptr<const KneeWearTable>>;

// reads and validates the measured CSV (InputError names file, row and column)
MeasuredData read_knee_wear_measured(const std::string& path);

// the config of each condition named in `data`: the config file with `sets` and then the
// condition's own overrides applied; throws InputError naming the measured file, row and
// column for a condition the config does not define
std::map<std::string, models::Config> knee_condition_configs(const MeasuredData& data,
                                                             const std::string& config_path,
                                                             const std::vector<std::string>& sets);

// simulates every condition once (the forward tables, pristine only), or, with
// geometry_states > 0, also along its wear loop (the config's law) to kPathVolumeMargin times
// the largest volume `data` holds for it (knee_wear_table.h; k_ref from the library default)
KneeWearTables make_knee_wear_tables(const std::map<std::string, models::Config>& configs,
                                     const MeasuredData& data = {}, int geometry_states = 0);

// how far the geometry path reaches beyond the largest measured volume of a condition [-]
constexpr double kPathVolumeMargin = 1.5;

// the case over precomputed tables (one per condition of the data)
DiagnosisCase make_knee_wear_case(MeasuredData data, const KneeWearTables& tables,
                                  const KneeWearCaseOptions& options);

// the knee wear parameters [SI] of an effect from the fit's parameters [I/O units]
KneeWearParams knee_wear_params(Effect effect, const Eigen::VectorXd& baseline,
                                const Eigen::VectorXd& effect_params, double reference_pressure);

// p_ref of the pressure law: the work-weighted geometric mean pressure of the calibration
// condition [Pa]
double knee_reference_pressure(const KneeWearTables& tables, const MeasuredData& data,
                               const KneeWearCaseOptions& options);

// the effect parameter specs of the knee-wear case (knee-scale running-in and creep times)
std::vector<ParamSpec> knee_wear_effect_params(Effect effect);

}  // namespace kneesim::diagnosis
