// The forward model of the knee-wear diagnosis: simulated gait cycles per condition, recorded so
// that the wear of every effect of the library is a cheap sum.
//
// Two forms (issue 14 item 6):
//  - pristine only (one state): wear linear in cycles on the pristine geometry,
//    V(N) = N V_1 with V_1 the volume of one observed cycle (after one settling cycle);
//  - following the geometry update (several states): the condition's own wear loop under the
//    config's [wear] law (wear/wear_loop.h, what `kneesim wear` runs, loop_law()) at a
//    reference k is run once, and one cycle is recorded on the insert after each of its
//    updates. The geometry is indexed by the worn
//    volume V_s the loop had reached (not by cycles), so any k and any law can walk the same
//    path: the per-cycle volume rate r_s(law) of each state is interpolated linearly in V, and
//    dV/dN_eff = r(V) is integrated in closed form (on a segment with r = r_a + m (V - V_a):
//    N = ln(r / r_a) / m); vertex depth rates are interpolated the same way. Why: under a
//    pressure law the worn insert conforms, the pressure falls and the wear rate rises with
//    cycles, which the pristine-linear form cannot follow (a hidden pressure law in loop-made
//    data was named `none`). The approximation left: the path's geometry is the config law's at
//    each worn volume, so a candidate effect (which extends Archard) walks the baseline law's
//    geometry (a law that redistributes wear reaches a somewhat different geometry at the same
//    volume); beyond the last state the last rates hold.
//
// What is recorded per articular element (only elements that were in contact are kept):
//  - sum of p ds over the cycle binned by ln p (kBins bins from 0.01 to 300 MPa), with the
//    work-weighted mean ln p of each bin, so the pressure-dependent law
//    W(alpha) = sum A p (p / p_ref)^-alpha ds is a sum over bins (bin-mean ln p makes the
//    error second order: under 0.3 % at alpha = 1);
//  - the cross-shear ratio CS_e of the cycle's frictional work, computed by
//    wear::WearAccumulator::cross_shear_ratio, the same code `kneesim wear --wear-law
//    cross_shear` uses, so k (1 + g CS_e) is the same extension;
//  - the depth per cycle of the config's own [wear] law per unit of the material's k
//    (wear::WearAccumulator with wear::make_wear_law, what `kneesim wear` accumulates), so the
//    baseline (effect none) is the config's law, not Archard, whatever law that is: at the
//    material's k the pristine volume per cycle is `kneesim wear`'s; for an archard config the
//    binned sum is used (the same figure);
//  - the area-weighted spreading to vertices (wear/geometry_update.h) as a sparse matrix,
//    for the maximum depth.
// Rejected: storing every (step, element) sample (10^6 per cycle), because every prediction
// would then loop over them; the binned table is 100 times smaller and exact for archard and
// cross-shear.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"
#include "engine/model.h"
#include "models/config.h"
#include "wear/wear_law.h"

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
  double incubation_cycles = 2e5;  // N_i, incubation time constant [cycles]
};

// the geometry path of a condition: its wear loop under the config's law (loop_law() at
// k = k_ref; running-in and incubation, which only weight the cycles, walk Archard's path)
// until the worn volume reaches target_volume, with `states` updates at cumulative cycle
// fractions (j / states)^1.5 (denser early, where the conformity changes fastest); one
// geometry state after each
struct KneeGeometryPath {
  int states = 0;                 // worn geometry states; 0 = pristine only [-]
  double target_volume = 0.0;     // worn volume the path reaches [m^3]
  double k_ref = 2.643e-16;       // k of the loop [m^2/N] (the law's coefficient scaled by
                                  // k_ref over the material's k; sets only the loop's cycle
                                  // counts: the states are indexed by volume)
};

// one cycle simulated on one insert geometry
struct KneeCycleRecord {
  double volume = 0.0;            // worn volume of the geometry (loop's depth integral) [m^3]
  double max_penetration = 0.0;   // largest elastic penetration of the cycle [m]
  Eigen::VectorXd area;           // kept element areas [m^2]
  Eigen::VectorXd cross_shear;    // kept element CS [-]
  Eigen::VectorXd law_rate;       // kept element depth per cycle of the config's law per unit
                                  // of the material's k (Sarkar included where the law has it)
                                  // [m per (m^2/N)]
  Eigen::MatrixXd pds;            // kept elements x bins: sum p ds [Pa m]
  Eigen::MatrixXd lnp;            // kept elements x bins: mean ln(p / 1 Pa) of the bin [-]
  Eigen::SparseMatrix<double> spread;  // vertices x kept elements
};

class KneeWearTable {
 public:
  static constexpr int kBins = 48;

  // simulates `config` (one settling and one observed cycle) and records the cycle; with a
  // path, also runs the condition's wear loop (the config's law) and records a cycle after
  // each of its updates;
  // throws std::runtime_error when a simulation stops on numerical trouble
  KneeWearTable(const std::string& name, const models::Config& config,
                const KneeGeometryPath& path = {});

  // per-cycle figures of a law at every geometry state: everything a prediction needs
  // (computed once per condition and parameter set)
  struct Rates {
    Eigen::VectorXd volume;      // volume per cycle, per state [m^3]
    Eigen::MatrixXd vertex;      // vertex depth per cycle, vertices x states [m]
    double max_depth = 0.0;      // largest vertex depth per cycle, pristine state [m]
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
  int geometry_states() const { return static_cast<int>(states_.size()); }
  double state_volume(int s) const { return states_[static_cast<size_t>(s)].volume; }  // [m^3]
  double friction() const { return friction_; }             // [-]
  // the config's [wear] law (wear::make_wear_law): the baseline the effects are judged against
  const wear::WearLawParams& law() const { return law_; }
  // the law `kneesim wear` runs for the parameters p on this condition, what volume(p, ..)
  // approximates: for the baseline (effect none) and creep the config's law with its
  // coefficient scaled by p.k over the material's k (contact_area: C p.k / k); for
  // pressure_dependent_wear, cross_shear, running_in and incubation Archard extended by the
  // effect under the law of that name (the effect library's definition, p_ref =
  // p.reference_pressure). Creep is off: it moves no surface, so the loop's volume and depth
  // are the wear part
  wear::WearLawParams loop_law(const KneeWearParams& p) const;
  double period() const { return period_; }                 // [s]
  double max_penetration() const { return states_.front().max_penetration; }  // elastic [m]
  double work() const { return work_; }                     // sum A p ds over the cycle [J]
  // work-weighted geometric mean contact pressure [Pa]
  double mean_pressure() const { return mean_pressure_; }
  // work-weighted mean cross-shear ratio [-]
  double mean_cross_shear() const { return mean_cross_shear_; }
  double seconds() const { return seconds_; }               // simulation wall time [s]

 private:
  // element depth per unit k (Sarkar included) for the laws that change its distribution [m
  // per (m^2/N)] over the kept elements of a state
  Eigen::VectorXd element_depth_rate(const KneeCycleRecord& r, const KneeWearParams& p) const;
  double effective_cycles(const KneeWearParams& p, double cycles) const;
  // records one cycle (after a settling one) on `model`
  KneeCycleRecord record(const engine::Model& model, double volume) const;
  // vertex depth per unit rate integrated along the path to `cycles` (effective) [m]
  Eigen::VectorXd path_depth(const Rates& r, double cycles) const;

  std::string name_;               // condition name
  double friction_ = 0.07;         // mu of the contact [-]
  double sarkar_ = 1.0;            // sqrt(1 + 3 mu^2) [-]
  wear::WearLawParams law_;        // the config's [wear] law with the material's coefficients
  double period_ = 1.0;            // gait cycle [s]
  double work_ = 0.0;              // sum A p ds [J]
  double mean_pressure_ = 0.0;     // work-weighted geometric mean pressure [Pa]
  double mean_cross_shear_ = 0.0;  // work-weighted mean CS [-]
  double seconds_ = 0.0;           // build and simulation wall time [s]
  std::vector<KneeCycleRecord> states_;  // pristine first, then after each loop update
};

}  // namespace kneesim::diagnosis
