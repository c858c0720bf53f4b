// The forward model of the knee-wear diagnosis: one simulated gait cycle per condition on the
// pristine insert, recorded so that the wear of every effect of the library is a cheap sum.
//
// Approximation (stated in every report): wear is linear in cycles on the pristine geometry,
// V(N) = N V_1 with V_1 the volume of one observed cycle (after one settling cycle). The full
// knee wear loop (wear/wear_loop.h, `kneesim wear`) recedes the insert every update, which
// makes it more conforming and lowers the pressure; `kneesim diagnose knee-wear` checks the
// approximation against that loop for the calibration condition and prints the difference.
//
// What is recorded per articular element (only elements that were in contact are kept):
//  - sum of p ds over the cycle binned by ln p (kBins bins from 0.01 to 300 MPa), with the
//    work-weighted mean ln p of each bin, so the pressure-dependent law
//    W(alpha) = sum A p (p / p_ref)^-alpha ds is a sum over bins (bin-mean ln p makes the
//    error second order: under 0.3 % at alpha = 1);
//  - the cross-shear ratio CS_e of the cycle's frictional work, computed by
//    wear::WearAccumulator::cross_shear_ratio, the same code `kneesim wear --wear-law
//    cross_shear` uses, so k (1 + g CS_e) is the same extension;
//  - the area-weighted spreading to vertices (wear/geometry_update.h) as a sparse matrix,
//    for the maximum linear depth.
// Rejected: storing every (step, element) sample (10^6 per cycle), because every prediction
// would then loop over them; the binned table is 100 times smaller and exact for archard and
// cross-shear.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"
#include "models/config.h"

namespace kneesim::diagnosis {

// the knee wear laws the diagnosis fits, in SI (I/O conversion in knee_wear_case.cpp)
struct KneeWearParams {
  Effect effect = Effect::none;
  double k = 2.643e-16;            // wear factor (k_ref for the pressure law) [m^2/N]
  double running_in_excess = 0.0;  // a, initial extra wear-rate ratio [-]
  double running_in_cycles = 2e5;  // N_r, running-in decay constant [cycles]
  double pressure_exponent = 0.0;  // alpha in k (p / p_ref)^-alpha [-]
  double reference_pressure = 10e6;  // p_ref [Pa]
  double cross_shear_gain = 0.0;   // g in k (1 + g CS) [-]
  double creep_ratio = 0.0;        // phi, saturated creep over elastic penetration [-]
  double creep_time = 1e5;         // tau, creep time constant [s]
};

class KneeWearTable {
 public:
  static constexpr int kBins = 48;

  // simulates `config` (one settling and one observed cycle) and records the cycle; throws
  // std::runtime_error when the simulation stops on numerical trouble
  KneeWearTable(const std::string& name, const models::Config& config);

  // per-cycle figures of a law: everything a prediction needs (computed once per condition)
  struct Rates {
    double volume = 0.0;     // volume per cycle [m^3]
    double max_depth = 0.0;  // largest vertex depth per cycle [m]
  };
  Rates rates(const KneeWearParams& p) const;
  // volume after `cycles` [m^3] and maximum linear depth [m] (creep included for creep)
  double volume(const KneeWearParams& p, const Rates& r, double cycles) const;
  double max_depth(const KneeWearParams& p, const Rates& r, double cycles) const;
  double volume(const KneeWearParams& p, double cycles) const { return volume(p, rates(p), cycles); }
  double max_depth(const KneeWearParams& p, double cycles) const {
    return max_depth(p, rates(p), cycles);
  }

  const std::string& name() const { return name_; }
  double friction() const { return friction_; }             // [-]
  double period() const { return period_; }                 // [s]
  double max_penetration() const { return max_penetration_; }  // elastic, over the cycle [m]
  double work() const { return work_; }                     // sum A p ds over the cycle [J]
  // work-weighted geometric mean contact pressure [Pa]
  double mean_pressure() const { return mean_pressure_; }
  // work-weighted mean cross-shear ratio [-]
  double mean_cross_shear() const { return mean_cross_shear_; }
  double seconds() const { return seconds_; }               // simulation wall time [s]

 private:
  // element depth per unit k (Sarkar included) for the laws that change its distribution [m
  // per (m^2/N)] over the kept elements
  Eigen::VectorXd element_depth_rate(const KneeWearParams& p) const;
  double effective_cycles(const KneeWearParams& p, double cycles) const;

  std::string name_;               // condition name
  double friction_ = 0.07;         // mu of the contact [-]
  double sarkar_ = 1.0;            // sqrt(1 + 3 mu^2) [-]
  double period_ = 1.0;            // gait cycle [s]
  double max_penetration_ = 0.0;   // largest elastic penetration of the cycle [m]
  double work_ = 0.0;              // sum A p ds [J]
  double mean_pressure_ = 0.0;     // work-weighted geometric mean pressure [Pa]
  double mean_cross_shear_ = 0.0;  // work-weighted mean CS [-]
  double seconds_ = 0.0;           // build and simulation wall time [s]
  Eigen::VectorXd area_;          // kept element areas [m^2]
  Eigen::VectorXd cross_shear_;   // kept element CS [-]
  Eigen::MatrixXd pds_;           // kept elements x bins: sum p ds [Pa m]
  Eigen::MatrixXd lnp_;           // kept elements x bins: mean ln(p / 1 Pa) of the bin [-]
  Eigen::SparseMatrix<double> spread_;  // vertices x kept elements
};

}  // namespace kneesim::diagnosis
