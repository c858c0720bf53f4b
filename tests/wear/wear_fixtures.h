// Shared helpers of the wear tests: a closed flat-topped box insert (optionally with its top
// grid jittered in x-z so the elements differ in size), synthetic engine Data with a uniform
// contact state, and the coarse default model every real-run test starts from.
#pragma once

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

#include "engine/data.h"
#include "engine/model.h"
#include "models/build_model.h"
#include "models/config.h"
#include "models/tri_mesh.h"

namespace kneesim::test {

// A closed, outward-oriented box [-lx/2, lx/2] x [0, h] x [-lz/2, lz/2] [m] whose top face is
// an n x n grid of quads (two triangles each) and whose bottom and walls are one quad each
// side's grid row. jitter > 0 moves every interior top vertex by up to jitter * cell size in
// x and z (seeded): the top stays planar, its triangles get different areas.
inline models::TriMesh make_flat_box(double lx, double lz, double h, int n, double jitter = 0.0,
                                     unsigned seed = 1) {
  models::TriMesh m;
  const double dx = lx / n, dz = lz / n;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  auto top = [n](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      double x = -0.5 * lx + i * dx, z = -0.5 * lz + j * dz;
      if (jitter > 0.0 && i > 0 && i < n && j > 0 && j < n) {
        x += u(rng) * dx;
        z += u(rng) * dz;
      }
      m.vertices.emplace_back(x, h, z);
    }
  }
  const int bottom = static_cast<int>(m.vertices.size());
  auto bot = [n, bottom](int i, int j) { return bottom + i * (n + 1) + j; };
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) m.vertices.emplace_back(-0.5 * lx + i * dx, 0.0, -0.5 * lz + j * dz);
  }
  // top: (x_i, z_j) -> (x_i, z_j+1) -> (x_i+1, z_j+1) has the normal dz x dx = +y (outward)
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      m.triangles.push_back({top(i, j), top(i, j + 1), top(i + 1, j + 1)});
      m.triangles.push_back({top(i, j), top(i + 1, j + 1), top(i + 1, j)});
      m.triangles.push_back({bot(i, j), bot(i + 1, j + 1), bot(i, j + 1)});
      m.triangles.push_back({bot(i, j), bot(i + 1, j), bot(i + 1, j + 1)});
    }
  }
  // walls: quads between the top and bottom boundary vertices, oriented outward
  auto wall = [&m](int a_top, int b_top, int a_bot, int b_bot) {
    m.triangles.push_back({a_bot, b_bot, b_top});
    m.triangles.push_back({a_bot, b_top, a_top});
  };
  for (int k = 0; k < n; ++k) {
    wall(top(0, k), top(0, k + 1), bot(0, k), bot(0, k + 1));          // x = -lx/2
    wall(top(n, k + 1), top(n, k), bot(n, k + 1), bot(n, k));          // x = +lx/2
    wall(top(k + 1, 0), top(k, 0), bot(k + 1, 0), bot(k, 0));          // z = -lz/2
    wall(top(k, n), top(k + 1, n), bot(k, n), bot(k + 1, n));          // z = +lz/2
  }
  return m;
}

// Data for the given surface with every element in contact at pressure p [Pa] and slip
// velocity (v, 0, 0) [m/s] in the insert frame
inline engine::Data make_uniform_contact(const engine::InsertSurface& s, double p, double v) {
  engine::Data d;
  const int n = s.size();
  d.pressure.assign(n, p);
  d.penetration.assign(n, 0.0);
  d.slip_speed.assign(n, std::abs(v));
  d.slip_velocity_T.assign(n, Eigen::Vector3d(v, 0.0, 0.0));
  d.element_force_W.assign(n, Eigen::Vector3d::Zero());
  for (int e = 0; e < n; ++e) d.in_contact.push_back(e);
  return d;
}

// the default config on a coarse 2 mm implant plus the given overrides: what the real-run
// tests use to stay within seconds. The law calibrated for the implant where one is found, else
// the law as specified (contact.calibration = "auto"): the tests that change the implant's
// geometry are about wear, and a calibration on first use would cost each a deformable cycle.
inline models::Config coarse_config(std::vector<models::Override> overrides = {}) {
  overrides.insert(overrides.begin(), {"implant.edge_length_mm", "2"});
  overrides.insert(overrides.begin(), {"contact.calibration", "\"auto\""});
  return models::load_config("", overrides);
}

}  // namespace kneesim::test
