// Accumulates the wear law's (wear/wear_law.h) depth per contact site over the time steps of a simulated cycle: an
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
#include "wear/wear_law.h"

namespace kneesim::wear {

class WearAccumulator {
 public:
  WearAccumulator(int n_elements, WearLawParams params);
  // engine::RunOptions::observer: adds this step's increments of the elements in contact
  void observe(const engine::Model& model, const engine::State& state, const engine::Data& data);
  // the same for the deformable insert's top nodes (sites in model.insert_contact order)
  void observe_nodes(const engine::Model& model, const engine::State& state,
                     const engine::Data& data);
  // depth per site accumulated over the observed cycle [m], n_sites
  std::vector<double> depth_per_cycle() const;
  // the wear potential per site over the cycle: depth_per_cycle() over the law's coefficient
  // (k [m^2/N] for the k laws: [N/m]; C [-] for contact_area: [m])
  std::vector<double> potential_per_cycle() const;
  // the law's coefficient: k [m^2/N], or C [-] for contact_area
  double coefficient() const;
  // the site's elastic penetration averaged over the observed time (creep's d_el) [m]; zeros
  // unless the law has creep
  std::vector<double> mean_penetration() const;
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
  // the law's per-step weight: (p / p_ref)^-alpha p ds for the k laws [Pa m], ds for
  // contact_area [m], per site
  std::vector<double> depth_;
  std::vector<double> penetration_time_;  // sum of penetration dt, per site (creep) [m s]
  double observed_time_ = 0.0;            // [s]
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
