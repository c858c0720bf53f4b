// Accumulates Archard wear depth per contact site over the time steps of a simulated cycle: an
// observer of engine::simulate (it reads Data, never writes the Model). The sites are the
// rigid insert's articular elements (observe: depth per element, later spread to vertices
// with area weights by wear/geometry_update.h, which keeps the volume sum_e depth_e A_e) or
// the deformable insert's top-surface nodes (observe_nodes: depth per node, with the node's
// penalty pressure, slip and tributary area; no spreading needed).
#pragma once

#include <vector>

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::wear {

enum class WearLaw {
  kArchard,          // constant k (the baseline)
  kPressureDependent,  // k = k_ref (p / p_ref)^-alpha (Mazzucco & Spector 2003)
  kCrossShear,       // k = k_ref * (1 + beta * CS) with the element's cross-shear ratio CS
  kRunningIn,        // dV/dN = k F S (1 + a exp(-N / N_r)): extra early wear (Hussin 2024)
  kIncubation,       // dV/dN = k F S (1 - exp(-N / N_i)): the rate rises to steady state
};

struct WearLawParams {
  WearLaw law = WearLaw::kArchard;
  double wear_factor = 0.0;   // k or k_ref [m^2/N]
  double friction = 0.07;     // mu in the Sarkar factor [-]
  double p_ref = 10e6;        // reference pressure of the pressure-dependent law [Pa]
  double alpha = 0.0;         // exponent of the pressure-dependent law [-]
  double beta = 0.0;          // cross-shear gain [-]
  double running_in_excess = 0.0;    // a, initial extra wear-rate ratio [-]
  double running_in_cycles = 2e5;    // N_r, running-in decay constant [cycles]
  double incubation_cycles = 2e5;    // N_i, incubation time constant [cycles]
};

// the cycles [n0, n0 + n] weighted by the law's wear-rate factor: n, for running-in
// n + a N_r (exp(-n0 / N_r) - exp(-(n0 + n) / N_r)), for incubation
// n - N_i (exp(-n0 / N_i) - exp(-(n0 + n) / N_i)) [cycles]; the wear loop scales the depth of
// one simulated cycle by it
double effective_cycles(const WearLawParams& law, double n0, double n);

class WearAccumulator {
 public:
  WearAccumulator(int n_elements, WearLawParams params);
  // engine::RunOptions::observer: adds this step's increments of the elements in contact
  void observe(const engine::Model& model, const engine::State& state, const engine::Data& data);
  // the same for the deformable insert's top nodes (sites in model.insert_contact order)
  void observe_nodes(const engine::Model& model, const engine::State& state,
                     const engine::Data& data);
  // depth per element accumulated over the observed cycle [m], n_elements
  std::vector<double> depth_per_cycle() const;
  // cross-shear ratio per element over the cycle [-] (0 for unidirectional sliding)
  std::vector<double> cross_shear_ratio() const;
  double sliding_work() const { return work_; }  // sum of p A ds over the cycle [J]
  // the cycle's wear volume per unit wear factor: what the law multiplies by k (Archard:
  // sarkar(mu) sum_e A_e sum_steps p ds; the pressure-dependent and cross-shear laws weight
  // each term as depth_per_cycle() does), so that volume = k x potential on the observed
  // geometry [m^3 / (m^2/N) = J]
  double wear_potential() const;
  // the load-weighted slip of the contact over the cycle: sum over steps of
  // sum_e p A ds / sum_e p A [m] (the distance S of V = k F S for a uniform load)
  double sliding_distance() const { return sliding_; }
  // the sliding-work-weighted mean of the sites' cross-shear ratios over the cycle [-]
  double mean_cross_shear() const;

 private:
  // one site's step: pressure p [Pa], slip ds [m] along the slip velocity v (T frame) [m/s],
  // over the site's area [m^2]
  void add(int site, double p, double ds, const Eigen::Vector3d& v, double area);
  // the law's factor on k per site from the whole cycle (cross-shear), 1 otherwise [-]
  std::vector<double> law_gain() const;

  WearLawParams params_;
  std::vector<double> depth_;      // Archard-weighted p ds, per site [Pa m]
  // frictional-work tensor per site (x-z plane of T): sum of w v v^T / |v|^2 with
  // w = p ds, from which the principal direction and cross-shear follow (Kang 2008)
  std::vector<double> wxx_, wxz_, wzz_;
  double work_ = 0.0;
  std::vector<double> area_;       // the site's area on the observed geometry [m^2]
  std::vector<double> site_work_;  // sum of p A ds per site [J]
  double sliding_ = 0.0;           // load-weighted slip [m]
  double step_load_ = 0.0, step_load_slip_ = 0.0;  // this step's sum p A [N], p A ds [N m]
};

}  // namespace kneesim::wear
