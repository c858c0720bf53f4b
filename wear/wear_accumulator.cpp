#include "wear/wear_accumulator.h"

#include <algorithm>
#include <cmath>

#include "wear/archard.h"

namespace kneesim::wear {

WearAccumulator::WearAccumulator(int n, WearLawParams params)
    : params_(params), depth_(n, 0.0), penetration_time_(params.creep ? n : 0, 0.0),
      wxx_(n, 0.0), wxz_(n, 0.0), wzz_(n, 0.0), area_(n, 0.0), site_work_(n, 0.0) {}

void WearAccumulator::observe(const engine::Model& model, const engine::State&,
                              const engine::Data& data) {
  const double dt = model.dt;
  observed_time_ += dt;
  step_load_ = step_load_slip_ = 0.0;
  for (int e : data.in_contact) {
    add(e, data.pressure[e], data.slip_speed[e] * dt, data.slip_velocity_T[e],
        model.insert.area[e]);
  }
  if (step_load_ > 0.0) sliding_ += step_load_slip_ / step_load_;
  if (params_.creep) {
    for (int e : data.in_contact) penetration_time_[e] += data.penetration[e] * dt;
  }
}

void WearAccumulator::observe_nodes(const engine::Model& model, const engine::State&,
                                    const engine::Data& data) {
  const double dt = model.dt;
  observed_time_ += dt;
  const engine::solid::SurfaceContactData& c = data.insert_contact;
  step_load_ = step_load_slip_ = 0.0;
  for (int i = 0; i < model.insert_contact.size(); ++i) {
    if (!(c.pressure[i] > 0.0)) continue;  // add() takes nothing from a node out of contact
    // the friction on the node opposes its slip against the femur (engine/insert_solid.h):
    // its direction is the slip direction the cross-shear tensor needs
    const Eigen::Vector3d& f = c.friction_force[i];
    const double fn = f.norm();
    const Eigen::Vector3d v = fn > 0.0 ? Eigen::Vector3d(-c.slip_speed[i] / fn * f)
                                       : Eigen::Vector3d::Zero();
    add(i, c.pressure[i], c.slip_speed[i] * dt, v, model.insert_contact.area[i]);
  }
  if (step_load_ > 0.0) sliding_ += step_load_slip_ / step_load_;
}

void WearAccumulator::add(int e, double p, double ds, const Eigen::Vector3d& v, double area) {
  if (!(p > 0.0)) return;
  step_load_ += p * area;  // a site in contact carries load whether or not it slips
  if (!(ds > 0.0)) return;
  step_load_slip_ += p * area * ds;
  area_[e] = area;
  site_work_[e] += p * area * ds;
  switch (params_.law) {
    case WearLaw::kContactArea:  // wear per unit sliding distance in contact, whatever the load
      depth_[e] += ds;
      break;
    case WearLaw::kPressureDependent:
    case WearLaw::kCrossShear:  // each step weighted by (p / p_ref)^-alpha
      depth_[e] += (params_.alpha == 0.0 ? 1.0 : std::pow(p / params_.p_ref, -params_.alpha)) *
                   p * ds;
      break;
    case WearLaw::kArchard:
    case WearLaw::kRunningIn:
    case WearLaw::kIncubation:
      depth_[e] += p * ds;
      break;
  }
  const double vx = v.x(), vz = v.z(), v2 = vx * vx + vz * vz;
  if (v2 > 0.0) {
    const double w = p * ds / v2;
    wxx_[e] += w * vx * vx;
    wxz_[e] += w * vx * vz;
    wzz_[e] += w * vz * vz;
  }
  work_ += p * area * ds;
}

std::vector<double> WearAccumulator::cross_shear_ratio() const {
  // CS = smallest / total eigenvalue of the frictional-work tensor: the share of the work
  // done perpendicular to the principal sliding direction
  std::vector<double> cs(depth_.size(), 0.0);
  for (size_t e = 0; e < depth_.size(); ++e) {
    const double tr = wxx_[e] + wzz_[e];
    if (tr <= 0.0) continue;
    const double half = 0.5 * (wxx_[e] - wzz_[e]);
    const double lo = 0.5 * tr - std::sqrt(half * half + wxz_[e] * wxz_[e]);
    cs[e] = std::clamp(lo / tr, 0.0, 0.5);
  }
  return cs;
}

std::vector<double> WearAccumulator::law_gain() const {
  std::vector<double> gain(depth_.size(), 1.0);
  switch (params_.law) {
    case WearLaw::kArchard:
    case WearLaw::kRunningIn:
    case WearLaw::kIncubation:
    case WearLaw::kPressureDependent:
      break;
    case WearLaw::kCrossShear:
    case WearLaw::kContactArea: {  // f(CS) needs the whole cycle's sliding path
      const std::vector<double> cs = cross_shear_ratio();
      for (size_t e = 0; e < gain.size(); ++e) gain[e] = cross_shear_factor(cs[e], params_.beta);
      break;
    }
  }
  return gain;
}

double WearAccumulator::coefficient() const { return law_coefficient(params_); }

std::vector<double> WearAccumulator::potential_per_cycle() const {
  // the Sarkar factor belongs to the k laws (frictional shear in the yield of a loaded
  // asperity); the area law has no load
  const double sarkar =
      params_.law == WearLaw::kContactArea ? 1.0 : sarkar_factor(params_.friction);
  std::vector<double> out = law_gain();
  for (size_t e = 0; e < depth_.size(); ++e) out[e] *= sarkar * depth_[e];
  return out;
}

double WearAccumulator::wear_potential() const {
  // potential_per_cycle() per site times the site's area: depth_per_cycle() without the
  // coefficient
  const std::vector<double> pot = potential_per_cycle();
  double w = 0.0;
  for (size_t e = 0; e < depth_.size(); ++e) w += area_[e] * pot[e];
  return w;
}

double WearAccumulator::mean_cross_shear() const {
  const std::vector<double> cs = cross_shear_ratio();
  double num = 0.0, den = 0.0;
  for (size_t e = 0; e < cs.size(); ++e) {
    num += site_work_[e] * cs[e];
    den += site_work_[e];
  }
  return den > 0.0 ? num / den : 0.0;
}

std::vector<double> WearAccumulator::depth_per_cycle() const {
  std::vector<double> out = potential_per_cycle();
  const double c = coefficient();
  for (double& d : out) d *= c;
  return out;
}

std::vector<double> WearAccumulator::mean_penetration() const {
  std::vector<double> out(depth_.size(), 0.0);
  if (!params_.creep || !(observed_time_ > 0.0)) return out;
  for (size_t e = 0; e < out.size(); ++e) out[e] = penetration_time_[e] / observed_time_;
  return out;
}

}  // namespace kneesim::wear
