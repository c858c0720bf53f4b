// Small hand-built models and meshes shared by the engine tests: a rig with every DOF locked
// and no insert (to which a test frees the DOFs it needs), closed sphere and box meshes,
// flat insert beds, and a coarse default model built through models::build_model.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "engine/model.h"
#include "loads/iso14243/waveform.h"
#include "models/build_model.h"
#include "models/config.h"
#include "models/tri_mesh.h"

namespace kneesim::test {

// every DOF of both carriages locked at zero, unit masses, no damping, no insert elements, no
// femoral field, a single all-zero waveform channel; dt as given
inline engine::Model make_locked_model(double dt) {
  engine::Model m;
  m.gait = loads::Waveform::from_keypoints({{"zero", {0.0, 100.0}, {0.0, 0.0}}});
  m.period = 1.0;
  m.dt = dt;
  m.dt_critical = dt;
  for (auto& c : m.carriages) {
    for (auto& d : c.dofs) {
      d.mode = engine::DofMode::kLocked;
      d.mass = 1.0;
      d.damping = 0.0;
    }
  }
  return m;
}

// UV sphere of radius r centred at the origin, poles on the y axis, n_theta latitude bands and
// n_phi longitude sectors; closed and outward oriented (counter-clockwise seen from outside)
inline models::TriMesh make_uv_sphere(double r, int n_theta, int n_phi) {
  models::TriMesh m;
  m.vertices.push_back({0.0, -r, 0.0});  // south pole (lowest point)
  for (int i = 1; i < n_theta; ++i) {
    const double th = std::numbers::pi * i / n_theta;  // polar angle from the south pole
    for (int j = 0; j < n_phi; ++j) {
      const double ph = 2.0 * std::numbers::pi * j / n_phi;
      m.vertices.push_back({r * std::sin(th) * std::cos(ph), -r * std::cos(th),
                            r * std::sin(th) * std::sin(ph)});
    }
  }
  m.vertices.push_back({0.0, r, 0.0});  // north pole
  const int north = static_cast<int>(m.vertices.size()) - 1;
  auto ring = [n_phi](int i, int j) { return 1 + (i - 1) * n_phi + (j % n_phi); };
  for (int j = 0; j < n_phi; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i < n_theta - 1; ++i) {
    for (int j = 0; j < n_phi; ++j) {
      const int a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j), d = ring(i + 1, j + 1);
      m.triangles.push_back({a, c, d});
      m.triangles.push_back({a, d, b});
    }
  }
  for (int j = 0; j < n_phi; ++j) {
    m.triangles.push_back({north, ring(n_theta - 1, j + 1), ring(n_theta - 1, j)});
  }
  return m;
}

// lower spherical cap of the sphere of radius r centred at the origin: polar angles 0..theta_max
// from the south pole (0, -r, 0), n_theta bands and n_phi sectors; an open surface (boundary
// at the top ring), outward oriented like make_uv_sphere
inline models::TriMesh make_spherical_cap(double r, double theta_max, int n_theta, int n_phi) {
  models::TriMesh m;
  m.vertices.push_back({0.0, -r, 0.0});
  for (int i = 1; i <= n_theta; ++i) {
    const double th = theta_max * i / n_theta;
    for (int j = 0; j < n_phi; ++j) {
      const double ph = 2.0 * std::numbers::pi * j / n_phi;
      m.vertices.push_back({r * std::sin(th) * std::cos(ph), -r * std::cos(th),
                            r * std::sin(th) * std::sin(ph)});
    }
  }
  auto ring = [n_phi](int i, int j) { return 1 + (i - 1) * n_phi + (j % n_phi); };
  for (int j = 0; j < n_phi; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i < n_theta; ++i) {
    for (int j = 0; j < n_phi; ++j) {
      const int a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j), d = ring(i + 1, j + 1);
      m.triangles.push_back({a, c, d});
      m.triangles.push_back({a, d, b});
    }
  }
  return m;
}

// icosphere of radius r (icosahedron subdivided `levels` times, vertices on the sphere)
inline models::TriMesh make_icosphere(double r, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  models::TriMesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& v : m.vertices) v.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      const int idx = static_cast<int>(m.vertices.size()) - 1;
      mid[key] = idx;
      return idx;
    };
    std::vector<Eigen::Vector3i> next;
    for (const auto& tri : m.triangles) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                c = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = next;
  }
  for (auto& v : m.vertices) v *= r;
  return m;
}

// axis-aligned box [lo, hi], closed, outward oriented, 12 triangles
inline models::TriMesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  models::TriMesh m;
  for (int k = 0; k < 8; ++k) {
    m.vertices.push_back({(k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                          (k & 4) ? hi.z() : lo.z()});
  }
  // faces as quads (a, b, c, d) counter-clockwise seen from outside
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

// flat bed of elastic-foundation elements in T: the square [-half, half]^2 in x and z at
// height y = thickness, split into n x n squares of two right triangles each, normals +y,
// layer thickness `thickness`, medial = (z < 0)
inline engine::InsertSurface make_flat_bed(double half, int n, double thickness) {
  engine::InsertSurface s;
  const double h = 2.0 * half / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s.vertices_T.push_back({-half + i * h, thickness, -half + j * h});
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
      // counter-clockwise seen from +y: (x, z) -> normal (b - a) x (c - a) must be +y
      for (const Eigen::Vector3i& t : {Eigen::Vector3i(a, c, b), Eigen::Vector3i(b, c, d)}) {
        const Eigen::Vector3d& p0 = s.vertices_T[t[0]];
        const Eigen::Vector3d& p1 = s.vertices_T[t[1]];
        const Eigen::Vector3d& p2 = s.vertices_T[t[2]];
        const Eigen::Vector3d n3 = (p1 - p0).cross(p2 - p0);
        s.triangles.push_back(t);
        s.centroid_T.push_back((p0 + p1 + p2) / 3.0);
        s.normal_T.push_back(n3.normalized());
        s.area.push_back(0.5 * n3.norm());
        s.thickness.push_back(thickness);
        s.medial.push_back(s.centroid_T.back().z() < 0.0 ? 1 : 0);
      }
    }
  }
  return s;
}

// the built-in default config with the given overrides ("key=value")
inline models::Config default_config(const std::vector<std::string>& sets) {
  std::vector<models::Override> o;
  for (const auto& s : sets) o.push_back(models::parse_override(s));
  return models::load_config("", o);
}

}  // namespace kneesim::test
