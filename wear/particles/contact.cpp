#include "wear/particles/contact.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/errors.h"

namespace kneesim::particles {
namespace {

// fixed-order sum of f(k) over the grid: each row sequentially, then the rows in order.
// Serial on purpose: these memory-bound passes cost microseconds, while an OpenMP barrier on a
// machine shared with other jobs can cost milliseconds; the FFT passes carry the threads.
template <class F>
double row_sum(int nx, int ny, F f) {
  std::vector<double> rows(nx);
  for (int i = 0; i < nx; ++i) {
    double s = 0.0;
    for (int j = 0; j < ny; ++j) s += f(static_cast<long>(i) * ny + j);
    rows[i] = s;
  }
  double s = 0.0;
  for (double r : rows) s += r;
  return s;
}

}  // namespace

double ordered_sum(const std::vector<double>& v, int nx, int ny) {
  return row_sum(nx, ny, [&](long k) { return v[k]; });
}

void check_load(double load, double hardness, const Grid& grid, const std::string& source) {
  char buf[256];
  if (!(load > 0.0) || !std::isfinite(load)) {
    std::snprintf(buf, sizeof buf, "%s: load %g N is not allowed; the load must be > 0",
                  source.c_str(), load);
    throw InputError(buf);
  }
  const double cap = hardness * grid.cell_area() * double(grid.nx) * grid.ny;
  if (hardness > 0.0 && load > cap) {
    std::snprintf(buf, sizeof buf,
                  "%s: load %g N on the %g x %g um grid exceeds hardness x area = %g N; lower "
                  "the load or enlarge the grid",
                  source.c_str(), load, grid.nx * grid.dx * 1e6, grid.ny * grid.dy * 1e6, cap);
    throw InputError(buf);
  }
}

ContactResult solve_contact(const DeflectionOperator& op, const std::vector<double>& h,
                            const ContactOptions& opt, const std::vector<double>* p_start) {
  const Grid& g = op.grid();
  const int nx = g.nx, ny = g.ny;
  const long n = g.size();
  const double area = g.cell_area();
  const double cap = opt.hardness > 0.0 ? opt.hardness : std::numeric_limits<double>::infinity();
  const double target = opt.load;

  ContactResult res;
  std::vector<double>& p = res.pressure;
  std::vector<double>& u = res.deflection;
  std::vector<double>& gap = res.gap;
  std::vector<double> t(n, 0.0), r(n, 0.0), p_old(n);
  u.assign(n, 0.0);
  gap.assign(n, 0.0);

  // start: the given pressure rescaled to the load, or a uniform pressure
  if (p_start != nullptr && static_cast<long>(p_start->size()) == n) {
    p = *p_start;
  } else {
    p.assign(n, 1.0);
  }
  {
    const double w = area * ordered_sum(p, nx, ny);
    const double s = w > 0.0 ? target / w : 0.0;
    for (long k = 0; k < n; ++k) p[k] = std::min(p[k] * s, cap);
    if (!(w > 0.0)) std::fill(p.begin(), p.end(), std::min(target / (area * n), cap));
  }

  auto in_set = [&](long k) { return p[k] > 0.0 && p[k] < cap; };
  // complementarity check: gap tolerance 1e-5 of the gap's range
  const auto [h_lo, h_hi] = std::minmax_element(h.begin(), h.end());
  const double gap_tol = 1e-5 * (*h_hi - *h_lo) + 1e-15;
  // violations allowed at convergence: none needed for elastic contact, where the pressure
  // change alone is the criterion (Polonsky & Keer); with capped cells a small share (1e-4 of
  // the grid plus 2 % of the loaded cells) where plastic zones meet elastic cells
  auto allowed_violations = [&]() {
    const double capped = row_sum(nx, ny, [&](long k) { return p[k] >= cap ? 1.0 : 0.0; });
    if (capped == 0.0) return std::numeric_limits<double>::infinity();
    const double loaded = row_sum(nx, ny, [&](long k) { return p[k] > 0.0 ? 1.0 : 0.0; });
    return std::floor(1e-4 * n) + 0.02 * loaded;
  };
  std::vector<long> order(n);
  auto select_capped = [&](const std::vector<double>& defl) {
    for (long k = 0; k < n; ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](long a, long b) { return h[a] + defl[a] < h[b] + defl[b]; });
    double left = target / area;  // sum of p still to place [Pa]
    std::fill(p.begin(), p.end(), 0.0);
    for (long k = 0; k < n && left > 0.0; ++k) {
      p[order[k]] = std::min(cap, left);
      left -= p[order[k]];
    }
  };
  // converged when the pressure no longer changes and complementarity holds
  auto settled = [&](double violations) {
    const double dp = row_sum(nx, ny, [&](long k) { return std::abs(p[k] - p_old[k]); });
    return area * dp <= opt.tolerance * target && violations <= allowed_violations();
  };
  double g_old = 1.0;
  bool conjugate = false;
  for (int it = 1; it <= opt.max_iterations; ++it) {
    res.iterations = it;
    // gap on the current contact set, shifted to zero mean there
    op.apply(p.data(), u.data());
    const double n_set = row_sum(nx, ny, [&](long k) { return in_set(k) ? 1.0 : 0.0; });
    const double mean_g =
        n_set > 0.0
            ? row_sum(nx, ny, [&](long k) { return in_set(k) ? u[k] + h[k] : 0.0; }) / n_set
            : 0.0;
    for (long k = 0; k < n; ++k) gap[k] = u[k] + h[k] - mean_g;
    // complementarity violations: open cells that overlap, capped cells that separate
    const double violations = row_sum(nx, ny, [&](long k) {
      return ((p[k] == 0.0 && gap[k] < -gap_tol) || (p[k] >= cap && gap[k] > gap_tol)) ? 1.0 : 0.0;
    });
    if (n_set == 0.0) {
      // every loaded cell is at the cap (fully plastic contact) and the CG set is empty: cap the cells of largest interference h + u that the load can
      // hold and give the remainder to the next one, which reopens the CG set
      p_old = p;
      select_capped(u);
      conjugate = false;
      if (settled(violations)) {
        res.converged = true;
        break;
      }
      continue;
    }
    const double g_norm = row_sum(nx, ny, [&](long k) { return in_set(k) ? gap[k] * gap[k] : 0.0; });
    // conjugate search direction
    // (g_old = 0 when the set was a single cell, whose gap the mean shift makes exactly zero:
    // 0 / 0 would turn the direction, the step and then the pressure into NaN)
    const double beta = conjugate && g_old > 0.0 ? g_norm / g_old : 0.0;
    for (long k = 0; k < n; ++k) t[k] = in_set(k) ? gap[k] + beta * t[k] : 0.0;
    g_old = g_norm;
    // step length from the deflection of the direction
    op.apply(t.data(), r.data());
    const double n_r = row_sum(nx, ny, [&](long k) { return in_set(k) ? r[k] : 0.0; }) / n_set;
    const double rt = row_sum(nx, ny, [&](long k) { return in_set(k) ? (r[k] - n_r) * t[k] : 0.0; });
    const double gt = row_sum(nx, ny, [&](long k) { return in_set(k) ? gap[k] * t[k] : 0.0; });
    const double tau = rt != 0.0 && std::isfinite(gt / rt) ? gt / rt : 0.0;
    p_old = p;
    for (long k = 0; k < n; ++k) {
      if (in_set(k)) p[k] = std::clamp(p[k] - tau * t[k], 0.0, cap);
    }
    // cells outside the set that overlap re-enter; then the CG restarts
    const double n_enter = row_sum(nx, ny, [&](long k) {
      return (p_old[k] == 0.0 && gap[k] < 0.0) ? 1.0 : 0.0;
    });
    conjugate = n_enter == 0.0;
    for (long k = 0; k < n; ++k) {
      if (p_old[k] == 0.0 && gap[k] < 0.0) p[k] = std::min(-tau * gap[k], cap);
      // capped cells whose gap opens are released below the cap
      if (p_old[k] == cap && gap[k] > 0.0) p[k] = std::nextafter(cap, 0.0);
    }
    // impose the load on the cells below the cap
    const double w_cap = area * row_sum(nx, ny, [&](long k) { return p[k] >= cap ? cap : 0.0; });
    const double w_free = area * row_sum(nx, ny, [&](long k) { return p[k] < cap ? p[k] : 0.0; });
    // (a denormal w_free would overflow the scale to inf and 0 * inf put NaN into the open
    // cells; such a step is left short of load and placed plastically below)
    if (w_free > 0.0 && target > w_cap && std::isfinite((target - w_cap) / w_free)) {
      const double s = (target - w_cap) / w_free;
      for (long k = 0; k < n; ++k) {
        if (p[k] < cap) p[k] = std::min(p[k] * s, cap);
      }
    } else if (w_cap + w_free > 0.0) {
      // the capped cells alone carry more than the load: scale all, releasing the cap
      const double s = target / (w_cap + w_free);
      for (long k = 0; k < n; ++k) p[k] = std::min(p[k], cap) * s;
    }
    // cells scaled past the cap were clipped and their share of the load lost; with nearly
    // every loaded cell at the cap no free cell is left to take it, and the CG would end
    // short of the load (seen in the wear loop: 40 % of the load after 100 iterations). Then
    // place the load plastically on the cells of largest interference under the current
    // deflection, as in the fully plastic branch, and restart the CG from there.
    if (area * ordered_sum(p, nx, ny) < (1.0 - 1e-9) * target) {
      select_capped(u);
      conjugate = false;
    }
    if (settled(violations)) {
      res.converged = true;
      break;
    }
  }

  // final deflection, approach and gap
  op.apply(p.data(), u.data());
  const double n_set = row_sum(nx, ny, [&](long k) { return in_set(k) ? 1.0 : 0.0; });
  if (n_set > 0.0) {
    res.approach = row_sum(nx, ny, [&](long k) { return in_set(k) ? u[k] + h[k] : 0.0; }) / n_set;
  } else {
    // fully plastic: no elastic cell fixes the approach; any value between the capped cells'
    // h + u and the open cells' is consistent, and the capped cell of least interference
    // (largest h + u) touching exactly gives the smallest plastic interference
    res.approach = -std::numeric_limits<double>::infinity();
    for (long k = 0; k < n; ++k) {
      if (p[k] > 0.0) res.approach = std::max(res.approach, h[k] + u[k]);
    }
    if (!std::isfinite(res.approach)) res.approach = 0.0;
  }
  for (long k = 0; k < n; ++k) gap[k] = h[k] + u[k] - res.approach;
  res.load = area * ordered_sum(p, nx, ny);
  res.contact_fraction = row_sum(nx, ny, [&](long k) { return p[k] > 0.0 ? 1.0 : 0.0; }) / n;
  res.capped_fraction = row_sum(nx, ny, [&](long k) { return p[k] >= cap ? 1.0 : 0.0; }) / n;
  return res;
}

}  // namespace kneesim::particles
