#include "wear/bor/bor_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "engine/sundials_adapter.h"

namespace kneesim::bor {

double segment_factor(double t) {
  // series (2/3) t^3 - (2/15) t^5 + (4/315) t^7 - (2/2835) t^9 below 0.05 rad: error < 1e-17 t^3
  if (std::abs(t) < 0.05) {
    const double t2 = t * t;
    return t * t2 * (2.0 / 3.0 + t2 * (-2.0 / 15.0 + t2 * (4.0 / 315.0 - t2 * 2.0 / 2835.0)));
  }
  return t - std::sin(t) * std::cos(t);
}

namespace {

double one_minus_cos(double t) {
  const double s = std::sin(0.5 * t);
  return 2.0 * s * s;
}

// theta with R_c^2 w seg(theta) = area_volume, from the small-angle form plus Newton polish
double theta_for_volume(double rc2w, double area_volume) {
  double t = std::cbrt(1.5 * area_volume / rc2w);
  for (int i = 0; i < 4; ++i) {
    const double s = std::sin(t);
    t -= (rc2w * segment_factor(t) - area_volume) / (rc2w * 2.0 * s * s);
  }
  return t;
}

void fill_outputs(const BorRig& rig, double load, BorContact& c) {
  const double rc = rig.ring_radius;
  c.contact_width = 2.0 * rc * std::sin(c.theta);
  c.contact_area = c.contact_width * rig.ring_width;
  c.mean_pressure = load / c.contact_area;
  c.penetration = rc * one_minus_cos(c.theta);
  c.scar_depth = (c.scar_curvature > 0.0) ? rc / c.scar_curvature * one_minus_cos(c.theta_scar)
                                          : 0.0;
}

BorContact solve_unworn(const BorRig& rig, double load) {
  const double rc2w = rig.ring_radius * rig.ring_radius * rig.ring_width;
  const double c_f = foundation_constant(rig);
  auto residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r[0] = c_f * rc2w * segment_factor(x[0]) - load;
  };
  engine::NonlinearOptions opt;
  opt.residual_tol = 1e-11;
  const double t0 = theta_for_volume(rc2w, load / c_f);
  opt.x_scale = Eigen::VectorXd::Constant(1, t0);
  opt.f_scale = Eigen::VectorXd::Constant(1, 1.0 / load);
  opt.constraints = Eigen::VectorXi::Constant(1, static_cast<int>(engine::Positivity::positive));
  const auto res = engine::solve_nonlinear(residual, Eigen::VectorXd::Constant(1, t0), opt);
  if (!res.converged) {
    throw std::runtime_error("block-on-ring unworn contact did not converge at load " +
                             std::to_string(load) + " N: " + res.message);
  }
  BorContact c;
  c.theta = res.x[0];
  c.iterations = res.iterations;
  fill_outputs(rig, load, c);
  return c;
}

// flat-scar guess: the scar is shallow compared with its chord, so V ~ (2/3) a^2 theta' w
BorContact worn_guess(const BorRig& rig, double load, double volume) {
  const double rc2w = rig.ring_radius * rig.ring_radius * rig.ring_width;
  BorContact g;
  g.theta = theta_for_volume(rc2w, volume + load / foundation_constant(rig));
  const double a = rig.ring_radius * std::sin(g.theta);
  g.theta_scar = std::min(1.5 * volume / (a * a * rig.ring_width), 0.95 * g.theta);
  g.scar_curvature = std::sin(g.theta_scar) / std::sin(g.theta);
  return g;
}

}  // namespace

BorContact solve_bor_contact(const BorRig& rig, double load, double volume,
                             const BorContact* guess) {
  if (!(load > 0.0) || !(volume >= 0.0)) {
    throw std::invalid_argument("solve_bor_contact needs load > 0 and volume >= 0");
  }
  if (volume == 0.0) return solve_unworn(rig, load);

  const double rc = rig.ring_radius, w = rig.ring_width;
  const double c_f = foundation_constant(rig);
  // x = (theta, theta', kappa); residuals in relative units
  auto residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    const double th = x[0], ts = x[1], kappa = x[2];
    r[0] = (kappa * std::sin(th) - std::sin(ts)) / std::sin(th);
    r[1] = (rc * rc * w * segment_factor(ts) / (kappa * kappa) - volume) / volume;
    r[2] = (c_f * (rc * rc * w * segment_factor(th) - volume) - load) / load;
  };
  const BorContact g = (guess && guess->scar_curvature > 0.0) ? *guess
                                                               : worn_guess(rig, load, volume);
  engine::NonlinearOptions opt;
  opt.residual_tol = 1e-11;
  opt.x_scale = Eigen::Vector3d(g.theta, g.theta_scar, g.scar_curvature);
  opt.constraints = Eigen::VectorXi::Constant(3, static_cast<int>(engine::Positivity::positive));
  auto res = engine::solve_nonlinear(
      residual, Eigen::Vector3d(g.theta, g.theta_scar, g.scar_curvature), opt);
  if (!res.converged && guess) {
    // a poor warm start: retry from the analytic guess
    const BorContact g2 = worn_guess(rig, load, volume);
    opt.x_scale = Eigen::Vector3d(g2.theta, g2.theta_scar, g2.scar_curvature);
    res = engine::solve_nonlinear(
        residual, Eigen::Vector3d(g2.theta, g2.theta_scar, g2.scar_curvature), opt);
  }
  if (!res.converged) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "block-on-ring contact did not converge at load %g N and worn "
                  "volume %g mm^3: ", load, volume * 1e9);
    throw std::runtime_error(buf + res.message);
  }
  BorContact c;
  c.volume = volume;
  c.theta = res.x[0];
  c.theta_scar = res.x[1];
  c.scar_curvature = res.x[2];
  c.iterations = res.iterations;
  fill_outputs(rig, load, c);
  return c;
}

BorContactTable::BorContactTable(const BorRig& rig, double load, double base_volume, int points)
    : rig_(rig), load_(load), base_volume_(base_volume), points_(std::max(points, 3)) {
  while (static_cast<int>(volumes_.size()) < points_) append_node();
}

void BorContactTable::append_node() {
  const size_t i = volumes_.size();
  if (static_cast<int>(i) >= kMaxNodes) {
    throw std::runtime_error("block-on-ring contact table exceeds its node limit (worn volume "
                             "far beyond the test range)");
  }
  const double s = static_cast<double>(i) / (points_ - 1);
  const double v = base_volume_ * s * s;
  const BorContact c = solve_bor_contact(rig_, load_, v, (i > 1) ? &states_[i - 1] : nullptr);
  volumes_.push_back(v);
  states_.push_back(c);
}

void BorContactTable::extend_to(double volume) {
  while (volumes_.back() < volume) append_node();
}

BorContact BorContactTable::at(double volume) {
  if (volume <= 0.0) return states_.front();
  extend_to(volume);
  // quadratic grid: index from sqrt(V / V_base)
  const double u = std::sqrt(volume / base_volume_) * (points_ - 1);
  const int last = static_cast<int>(volumes_.size()) - 2;
  const int i = std::min(static_cast<int>(u), last);
  const double f = (volume - volumes_[i]) / (volumes_[i + 1] - volumes_[i]);
  const BorContact& a = states_[i];
  const BorContact& b = states_[i + 1];
  auto lerp = [f](double x, double y) { return x + f * (y - x); };
  BorContact c;
  c.volume = volume;
  c.theta = lerp(a.theta, b.theta);
  c.theta_scar = lerp(a.theta_scar, b.theta_scar);
  c.scar_curvature = lerp(a.scar_curvature, b.scar_curvature);
  c.scar_depth = lerp(a.scar_depth, b.scar_depth);
  c.penetration = lerp(a.penetration, b.penetration);
  c.contact_width = lerp(a.contact_width, b.contact_width);
  c.contact_area = lerp(a.contact_area, b.contact_area);
  c.mean_pressure = load_ / c.contact_area;
  return c;
}

}  // namespace kneesim::bor
