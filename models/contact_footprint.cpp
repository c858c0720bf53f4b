#include "models/contact_footprint.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/simulate.h"

namespace kneesim::models {
namespace {

// frames whose contact force is below this share of the cycle's peak (swing, heel strike)
// do not widen the zone: their pressures are a fraction of the loaded frames'
constexpr double kLoadedFraction = 0.25;

}  // namespace

std::vector<Interval> merge_intervals(std::vector<Interval> intervals, double margin) {
  std::sort(intervals.begin(), intervals.end(),
            [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
  std::vector<Interval> out;
  for (const Interval& i : intervals) {
    if (!out.empty() && i.lo - margin <= out.back().hi) {
      out.back().hi = std::max(out.back().hi, i.hi + margin);
    } else {
      out.push_back({i.lo - margin, i.hi + margin});
    }
  }
  return out;
}

std::pair<double, double> calc_patch_widths(const std::vector<double>& x,
                                            const std::vector<double>& z,
                                            const std::vector<double>& p) {
  double w = 0.0, mx = 0.0, mz = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    w += p[i];
    mx += p[i] * x[i];
    mz += p[i] * z[i];
  }
  if (!(w > 0.0)) return {0.0, 0.0};
  mx /= w;
  mz /= w;
  double vx = 0.0, vz = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    vx += p[i] * (x[i] - mx) * (x[i] - mx);
    vz += p[i] * (z[i] - mz) * (z[i] - mz);
  }
  const double k = 2.0 * std::sqrt(5.0);
  return {k * std::sqrt(vx / w), k * std::sqrt(vz / w)};
}

double find_percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t i = std::min(values.size() - 1,
                            static_cast<size_t>(std::floor(q * static_cast<double>(values.size()))));
  return values[i];
}

ContactFootprint find_contact_footprint(const engine::Model& rigid, double foundation_modulus,
                                        double dt_safety, double margin) {
  engine::Model m = rigid;
  m.contact.foundation_modulus = foundation_modulus;
  engine::RunOptions options;
  options.cycles = 1;
  for (int p = 0; p < 100; ++p) options.map_pcts.push_back(p);
  engine::State state = engine::make_initial_state(m);
  const engine::RunResult r = engine::simulate_with_retry(m, state, options, dt_safety);
  if (r.status != engine::StepStatus::kOk) {
    throw std::runtime_error("the rigid cycle that finds the contact footprint failed (" +
                             std::string(engine::to_string(r.status)) + ")");
  }
  // the loaded frames: contact force at least kLoadedFraction of the cycle's largest
  double peak_force = 0.0;
  auto force = [](const engine::Frame& f) {
    return f.contact.normal_force[0] + f.contact.normal_force[1];
  };
  for (const auto& f : r.frames) peak_force = std::max(peak_force, force(f));
  std::vector<unsigned char> touched(m.insert.size(), 0);
  ContactFootprint f;
  for (size_t i = 0; i < r.maps.size() && i < r.frames.size(); ++i) {
    if (force(r.frames[i]) < kLoadedFraction * peak_force) continue;
    // each condyle's patch: its elements' centroids weighted by pressure times area
    for (const unsigned char side : {0, 1}) {
      std::vector<double> x, z, w;
      for (int e = 0; e < m.insert.size(); ++e) {
        if (!(r.maps[i][e] > 0.0) || m.insert.medial[e] != side) continue;
        x.push_back(m.insert.centroid_T[e].x());
        z.push_back(m.insert.centroid_T[e].z());
        w.push_back(r.maps[i][e] * m.insert.area[e]);
      }
      const auto [wx, wz] = calc_patch_widths(x, z, w);
      if (wx > 0.0 && wz > 0.0) {
        f.width_x.push_back(wx);
        f.width_z.push_back(wz);
      }
    }
    for (int e = 0; e < m.insert.size(); ++e) touched[e] |= r.maps[i][e] > 0.0;
  }
  std::vector<Interval> xs, zs;
  std::vector<double> thickness;
  for (int e = 0; e < m.insert.size(); ++e) {
    if (!touched[e]) continue;
    ++f.elements_touched;
    thickness.push_back(m.insert.thickness[e]);
    // the element's own extent: touching neighbours overlap and merge
    Interval x{INFINITY, -INFINITY}, z{INFINITY, -INFINITY};
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = m.insert.vertices_T[m.insert.triangles[e][c]];
      x = {std::min(x.lo, v.x()), std::max(x.hi, v.x())};
      z = {std::min(z.lo, v.z()), std::max(z.hi, v.z())};
    }
    xs.push_back(x);
    zs.push_back(z);
  }
  if (f.elements_touched == 0) {
    throw std::runtime_error("the rigid cycle that finds the contact footprint touched nothing");
  }
  f.layer_thickness = find_percentile(thickness, 0.5);
  f.x = merge_intervals(xs, margin);
  f.z = merge_intervals(zs, margin);
  return f;
}

}  // namespace kneesim::models
