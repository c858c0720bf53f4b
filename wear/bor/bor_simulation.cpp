#include "wear/bor/bor_simulation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/sundials_adapter.h"

namespace kneesim::bor {
namespace {

BorRow make_row(const BorRig& rig, BorWearLaw law, const BorWearParams& params, double cycles,
                const BorContact& c, double delta_el) {
  BorRow r;
  r.cycles = cycles;
  r.volume = c.volume;
  r.depth = c.scar_depth +
            creep_depth(law, params, delta_el, cycles * seconds_per_cycle(rig));
  r.contact_width = c.contact_width;
  r.mean_pressure = c.mean_pressure;
  r.theta = c.theta;
  r.theta_scar = c.theta_scar;
  r.scar_radius = (c.scar_curvature > 0.0) ? rig.ring_radius / c.scar_curvature : 0.0;
  return r;
}

// volumes of the pressure law at the requested cycle counts, with CVODE on y = V / (k F S)
std::vector<double> integrate_pressure_law(const BorRig& rig, double load,
                                           const BorWearParams& params,
                                           const std::vector<double>& cycles) {
  const double per_cycle = params.k * load * sliding_distance_per_cycle(rig);  // [m^3]
  BorContact warm = solve_bor_contact(rig, load, 0.0);
  auto rhs = [&](double n, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
    const double v = std::max(y[0], 0.0) * per_cycle;
    const BorContact c =
        (v > 0.0) ? solve_bor_contact(rig, load, v, warm.volume > 0.0 ? &warm : nullptr) : warm;
    if (v > 0.0) warm = c;
    ydot[0] = wear_rate_factor(BorWearLaw::pressure_dependent_wear, params, n, c.mean_pressure);
  };
  engine::OdeOptions opt;
  opt.method = engine::OdeMethod::adams;
  opt.rtol = 1e-9;
  opt.atol = 1e-6;  // [Archard-equivalent cycles]
  engine::OdeIntegrator ode(1, rhs, opt);
  ode.reset(0.0, Eigen::VectorXd::Zero(1));
  std::vector<double> volumes;
  Eigen::VectorXd y(1);
  for (double n : cycles) {
    ode.advance_to(n, y);
    volumes.push_back(y[0] * per_cycle);
  }
  return volumes;
}

void check_cycles(const std::vector<double>& cycles, bool ascending) {
  for (size_t i = 0; i < cycles.size(); ++i) {
    if (!(cycles[i] >= 0.0) || (ascending && i > 0 && cycles[i] < cycles[i - 1])) {
      throw std::invalid_argument("simulate_bor needs cycle counts >= 0 in ascending order");
    }
  }
}

}  // namespace

std::vector<BorRow> simulate_bor(const BorRig& rig, double load, BorWearLaw law,
                                 const BorWearParams& params, const std::vector<double>& cycles) {
  check_cycles(cycles, true);
  const double sliding = sliding_distance_per_cycle(rig);
  std::vector<double> volumes;
  if (law == BorWearLaw::pressure_dependent_wear) {
    volumes = integrate_pressure_law(rig, load, params, cycles);
  } else {
    for (double n : cycles) volumes.push_back(closed_form_volume(law, params, load, sliding, n));
  }
  const BorContact unworn = solve_bor_contact(rig, load, 0.0);
  std::vector<BorRow> rows;
  BorContact prev;
  for (size_t i = 0; i < cycles.size(); ++i) {
    const BorContact c = solve_bor_contact(rig, load, volumes[i],
                                           prev.scar_curvature > 0.0 ? &prev : nullptr);
    rows.push_back(make_row(rig, law, params, cycles[i], c, unworn.penetration));
    prev = c;
  }
  return rows;
}

std::vector<BorRow> simulate_bor_table(BorContactTable& table, const BorRig& rig,
                                       BorWearLaw law, const BorWearParams& params,
                                       const std::vector<double>& cycles) {
  check_cycles(cycles, false);
  const double load = table.load();
  const double per_cycle = params.k * load * sliding_distance_per_cycle(rig);
  const double delta_el = table.at(0.0).penetration;
  std::vector<double> volumes(cycles.size());
  if (law == BorWearLaw::pressure_dependent_wear) {
    // N(V) on the table grid by the trapezoid rule, extended until it covers the largest N
    const double n_max = *std::max_element(cycles.begin(), cycles.end());
    std::vector<double> n_of_v;
    for (int attempt = 0;; ++attempt) {
      const auto& vs = table.volumes();
      const auto& st = table.states();
      n_of_v.assign(vs.size(), 0.0);
      double g_prev = 0.0;
      for (size_t i = 0; i < vs.size(); ++i) {
        const double g =
            1.0 / wear_rate_factor(law, params, 0.0, st[i].mean_pressure) / per_cycle;
        if (i > 0) n_of_v[i] = n_of_v[i - 1] + 0.5 * (g + g_prev) * (vs[i] - vs[i - 1]);
        g_prev = g;
      }
      if (n_of_v.back() >= n_max) break;
      if (attempt > 40) throw std::runtime_error("pressure-law wear volume does not converge");
      table.extend_to(2.0 * table.max_volume());  // doubles the grid's range
    }
    const auto& vs = table.volumes();
    for (size_t j = 0; j < cycles.size(); ++j) {
      const auto it = std::lower_bound(n_of_v.begin(), n_of_v.end(), cycles[j]);
      const size_t i = std::clamp<size_t>(it - n_of_v.begin(), 1, vs.size() - 1);
      const double f = (cycles[j] - n_of_v[i - 1]) / (n_of_v[i] - n_of_v[i - 1]);
      volumes[j] = vs[i - 1] + f * (vs[i] - vs[i - 1]);
    }
  } else {
    const double sliding = sliding_distance_per_cycle(rig);
    for (size_t j = 0; j < cycles.size(); ++j) {
      volumes[j] = closed_form_volume(law, params, load, sliding, cycles[j]);
    }
  }
  std::vector<BorRow> rows;
  rows.reserve(cycles.size());
  for (size_t j = 0; j < cycles.size(); ++j) {
    rows.push_back(make_row(rig, law, params, cycles[j], table.at(volumes[j]), delta_el));
  }
  return rows;
}

}  // namespace kneesim::bor
