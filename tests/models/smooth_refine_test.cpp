// Smooth refinement of a coarse surface (models/smooth_refine.h). References:
//  - a sphere: the chords' midpoints of one flat level are R (1 - cos(th/2)) inside (th the
//    edge's arc angle); the smooth level's points (Phong at a = 1/2, the mesh's averaged
//    normals) must be at least ten times closer on edges of 17 deg, below R th^4 / 8, and
//    their error must fall at least eightfold when the edges halve (third order or better:
//    the flat one falls fourfold);
//  - a cube: every edge is a feature (90 deg), every face flat: all points stay on the cube's
//    faces and edges exactly, and the original vertices never move;
//  - topology: a watertight mesh stays watertight, each level quarters the triangles;
//  - the levels that bring a mesh's median edge under a target.
#include <doctest/doctest.h>

#include <cmath>

#include "models/smooth_refine.h"

using namespace kneesim::models;
using Eigen::Vector3d;

namespace {

// an octahedron subdivided flat `levels` times, its vertices pushed onto the sphere of radius r
TriMesh make_sphere(double r, int levels) {
  TriMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  SmoothRefineOptions flat;
  flat.levels = levels;
  flat.phong_shape = 0.0;
  m = refine_smooth(m, flat);
  for (auto& v : m.vertices) v = r * v.normalized();
  return m;
}

double max_radial_error(const TriMesh& m, double r) {
  double e = 0.0;
  for (const auto& v : m.vertices) e = std::max(e, std::abs(v.norm() - r));
  return e;
}

}  // namespace

TEST_CASE("smooth refinement: a sphere's new points lie on it to fourth order") {
  const double r = 0.02;
  SmoothRefineOptions smooth;
  smooth.feature_angle_deg = 60.0;  // the sphere's faces meet at under 20 deg: all smooth
  SmoothRefineOptions flat = smooth;
  flat.phong_shape = 0.0;
  double previous_smooth = 0.0;
  for (int base : {3, 4}) {
    const TriMesh coarse = make_sphere(r, base);  // 512 faces of 17 deg edges, 2048 of 9 deg
    REQUIRE(max_radial_error(coarse, r) < 1e-15);
    double th = 0.0;
    for (const auto& t : coarse.triangles) {
      th = std::max(th, std::acos(coarse.vertices[t[0]].normalized().dot(
                            coarse.vertices[t[1]].normalized())));
    }
    const double e_smooth = max_radial_error(refine_smooth(coarse, smooth), r);
    const double e_flat = max_radial_error(refine_smooth(coarse, flat), r);
    MESSAGE("edge arc up to " << th * 180 / M_PI << " deg: radial error flat " << e_flat * 1e6
            << " um, smooth " << e_smooth * 1e6 << " um");
    CHECK(e_flat == doctest::Approx(r * (1.0 - std::cos(th / 2))).epsilon(0.05));
    CHECK(e_smooth < 0.1 * e_flat);
    CHECK(e_smooth < r * std::pow(th, 4) / 8.0);
    if (previous_smooth > 0.0) CHECK(e_smooth < previous_smooth / 8.0);
    previous_smooth = e_smooth;
  }
  const TriMesh coarse = make_sphere(r, 2);
  // the original vertices never move; topology stays watertight
  const TriMesh two = refine_smooth(coarse, SmoothRefineOptions{2, 60.0, 0.5});
  for (size_t i = 0; i < coarse.vertices.size(); ++i) CHECK(two.vertices[i] == coarse.vertices[i]);
  CHECK(two.triangles.size() == 16 * coarse.triangles.size());
  CHECK(check_mesh(two).watertight());
}

TEST_CASE("smooth refinement: a cube's faces stay flat and its edges sharp") {
  TriMesh cube;
  for (int i = 0; i < 8; ++i) cube.vertices.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  REQUIRE(check_mesh(cube).watertight());
  const TriMesh fine = refine_smooth(cube, SmoothRefineOptions{3, 30.0, 0.5});
  CHECK(check_mesh(fine).watertight());
  for (const auto& v : fine.vertices) {
    // on the surface: the largest coordinate is exactly 1, none beyond
    CHECK(v.cwiseAbs().maxCoeff() == doctest::Approx(1.0).epsilon(1e-14));
  }
  for (int i = 0; i < 8; ++i) CHECK(fine.vertices[i] == cube.vertices[i]);
}

TEST_CASE("smooth refinement: the levels for a target edge") {
  const TriMesh sphere = make_sphere(0.02, 2);
  std::vector<double> e;
  for (const auto& t : sphere.triangles)
    for (int k = 0; k < 3; ++k) e.push_back((sphere.vertices[t[k]] - sphere.vertices[t[(k + 1) % 3]]).norm());
  std::sort(e.begin(), e.end());
  const double median = e[e.size() / 2];
  CHECK(find_refine_levels(sphere, 2.0 * median) == 0);
  CHECK(find_refine_levels(sphere, 0.99 * median) == 1);
  CHECK(find_refine_levels(sphere, 0.3 * median) == 2);
  CHECK(find_refine_levels(sphere, 0.0) == 0);
}
