#include "wear/particles/detachment.h"

#include <algorithm>
#include <cmath>

#include "wear/particles/stress.h"

namespace kneesim::particles {
namespace {
constexpr double kPi = 3.14159265358979323846;

struct Voxel {
  int i, j, l;  // j unwrapped across a periodic seam
};

// flood fill from a seed; visits in a fixed order (deterministic)
template <class Visit>
void flood(const std::vector<unsigned char>& mask, std::vector<int>& label, const Grid& g,
           int nz, Voxel seed, int id, Visit visit) {
  const long n = g.size();
  auto index = [&](int i, int j, int l) {
    const int jw = ((j % g.ny) + g.ny) % g.ny;
    return static_cast<long>(l) * n + static_cast<long>(i) * g.ny + jw;
  };
  std::vector<Voxel> stack{seed};
  label[index(seed.i, seed.j, seed.l)] = id;
  while (!stack.empty()) {
    const Voxel v = stack.back();
    stack.pop_back();
    visit(v);
    const Voxel nb[6] = {{v.i - 1, v.j, v.l}, {v.i + 1, v.j, v.l}, {v.i, v.j - 1, v.l},
                         {v.i, v.j + 1, v.l}, {v.i, v.j, v.l - 1}, {v.i, v.j, v.l + 1}};
    for (const Voxel& w : nb) {
      if (w.i < 0 || w.i >= g.nx || w.l < 0 || w.l >= nz) continue;
      if (!g.periodic_y && (w.j < 0 || w.j >= g.ny)) continue;
      const long k = index(w.i, w.j, w.l);
      if (mask[k] && label[k] == 0) {
        label[k] = id;
        stack.push_back(w);
      }
    }
  }
}

}  // namespace

Detachment find_particles(const std::vector<double>& vm, const Grid& g, int nz, double dz,
                          double yield_stress) {
  const long n = g.size();
  std::vector<unsigned char> mask(vm.size());
  for (std::size_t k = 0; k < vm.size(); ++k) mask[k] = vm[k] > yield_stress ? 1 : 0;
  std::vector<int> label(mask.size(), 0);
  Detachment out;
  out.removed_depth.assign(n, 0.0);
  int id = 0;
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j) {
      const long k = static_cast<long>(i) * g.ny + j;
      if (!mask[k] || label[k] != 0) continue;
      long count = 0, surface = 0;
      int imin = i, imax = i, jmin = j, jmax = j, lmax = 0;
      double sx = 0.0, sy = 0.0;
      flood(mask, label, g, nz, Voxel{i, j, 0}, ++id, [&](const Voxel& v) {
        ++count;
        imin = std::min(imin, v.i), imax = std::max(imax, v.i);
        jmin = std::min(jmin, v.j), jmax = std::max(jmax, v.j);
        lmax = std::max(lmax, v.l);
        if (v.l == 0) ++surface, sx += g.x(v.i), sy += v.j;
        const int jw = ((v.j % g.ny) + g.ny) % g.ny;
        double& d = out.removed_depth[static_cast<long>(v.i) * g.ny + jw];
        d = std::max(d, (v.l + 1) * dz);
      });
      Particle p;
      p.volume = count * g.dx * g.dy * dz;
      p.eq_radius = std::cbrt(3.0 * p.volume / (4.0 * kPi));
      p.length = (imax - imin + 1) * g.dx;
      p.width = std::min(jmax - jmin + 1, g.ny) * g.dy;
      p.thickness = (lmax + 1) * dz;
      p.x = sx / surface;
      const double jc = sy / surface;
      p.y = (jc - 0.5 * (g.ny - 1)) * g.dy;
      out.particles.push_back(p);
    }
  return out;
}

Detachment find_particles_from_levels(const std::function<void(int, double*)>& level,
                                      const Grid& grid, int nz, double dz, int refine,
                                      double threshold, std::vector<double>& levels,
                                      int* computed) {
  const long n = grid.size();
  levels.resize(static_cast<long>(nz) * n);
  int count = 0;
  for (int k = 0; k < nz; ++k) {
    double* v = levels.data() + static_cast<long>(k) * n;
    level(k, v);
    count = k + 1;
    const bool above = std::any_of(v, v + n, [&](double x) { return x > threshold; });
    if (!above && k >= 1) break;
  }
  if (computed != nullptr) *computed = count;
  // refine_levels reads only the first `count` levels of the scratch
  return find_particles(refine_levels(levels, n, count, refine), grid, (count - 1) * refine,
                        dz / refine, threshold);
}

}  // namespace kneesim::particles
