// TriMesh helpers on shapes with closed-form answers: a unit cube (volume 1, area 6, centroid
// at its centre, vertex normals along the diagonals), and the topology defects that check_mesh
// must count exactly.
#include <doctest/doctest.h>

#include <cmath>

#include "models/tri_mesh.h"

using kneesim::models::TriMesh;

namespace {

// unit cube [0,1]^3, 12 outward triangles
TriMesh cube() {
  TriMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (auto& t : f) m.triangles.emplace_back(t[0], t[1], t[2]);
  return m;
}

}  // namespace

TEST_CASE("cube: volume, area, centroid, normals") {
  const TriMesh m = cube();
  CHECK(kneesim::models::enclosed_volume(m) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(kneesim::models::surface_area(m) == doctest::Approx(6.0).epsilon(1e-14));
  CHECK((kneesim::models::enclosed_centroid(m) - Eigen::Vector3d(0.5, 0.5, 0.5)).norm() < 1e-14);
  const auto c = kneesim::models::check_mesh(m);
  CHECK(c.watertight());
  CHECK(c.boundary_edges == 0);
  // every face normal points away from the centre
  const auto fn = kneesim::models::face_normals(m);
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const Eigen::Vector3d mid = (m.vertices[m.triangles[i][0]] + m.vertices[m.triangles[i][1]] +
                                 m.vertices[m.triangles[i][2]]) /
                                3.0;
    CHECK(fn[i].dot(mid - Eigen::Vector3d(0.5, 0.5, 0.5)) > 0.0);
  }
  // angle weighting makes corner normals the exact diagonals despite unequal triangle counts
  const auto vn = kneesim::models::vertex_normals(m);
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Eigen::Vector3d diag = (m.vertices[i] - Eigen::Vector3d(0.5, 0.5, 0.5)).normalized();
    CHECK((vn[i] - diag).norm() < 1e-12);
  }
  const auto stats = kneesim::models::edge_length_stats(m);
  CHECK(stats.count == 18);
  CHECK(stats.min_m == doctest::Approx(1.0));
  CHECK(stats.max_m == doctest::Approx(std::sqrt(2.0)));
  const auto box = kneesim::models::bounding_box(m);
  CHECK(box.min().isZero());
  CHECK(box.max().isOnes());
}

TEST_CASE("check_mesh counts open, non-manifold, inconsistent and degenerate edges") {
  TriMesh open = cube();
  open.triangles.pop_back();
  auto c = kneesim::models::check_mesh(open);
  CHECK(c.boundary_edges == 3);
  CHECK(!c.closed());

  TriMesh flippedface = cube();
  std::swap(flippedface.triangles[0][1], flippedface.triangles[0][2]);
  c = kneesim::models::check_mesh(flippedface);
  CHECK(c.closed());
  CHECK(c.inconsistent_edges == 3);
  CHECK(!c.watertight());

  TriMesh fin = cube();  // a fourth triangle on edge 0-1
  fin.vertices.emplace_back(0.5, -1.0, 0.5);
  fin.triangles.emplace_back(0, 1, 8);
  c = kneesim::models::check_mesh(fin);
  CHECK(c.nonmanifold_edges == 1);
  CHECK(c.boundary_edges == 2);

  TriMesh degenerate = cube();
  degenerate.vertices.emplace_back(2.0, 2.0, 2.0);  // unused
  degenerate.triangles.emplace_back(0, 0, 1);
  degenerate.triangles.emplace_back(0, 1, 99);
  c = kneesim::models::check_mesh(degenerate);
  CHECK(c.degenerate_faces == 1);
  CHECK(c.unused_vertices == 1);
  CHECK(c.bad_indices == 1);

  // an inward cube has the negative volume
  CHECK(kneesim::models::enclosed_volume(kneesim::models::flipped(cube())) ==
        doctest::Approx(-1.0));
}

TEST_CASE("transforms keep volume and orientation; the mirror keeps the outward winding") {
  const TriMesh m = cube();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(0.1, -0.2, 0.3);
  const TriMesh t = kneesim::models::transformed(m, X);
  CHECK(kneesim::models::enclosed_volume(t) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK((t.vertices[7] - X * Eigen::Vector3d(1, 1, 1)).norm() < 1e-15);
  const TriMesh r = kneesim::models::mirrored_z(m);
  CHECK(kneesim::models::enclosed_volume(r) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(r.vertices[4].z() == -1.0);
}

TEST_CASE("submesh keeps index maps") {
  const TriMesh m = cube();
  // the two triangles of the z = 1 face
  auto s = kneesim::models::submesh(m, [&](int t) {
    for (int k = 0; k < 3; ++k) {
      if (m.vertices[m.triangles[t][k]].z() != 1.0) return false;
    }
    return true;
  });
  CHECK(s.mesh.triangles.size() == 2);
  CHECK(s.mesh.vertices.size() == 4);
  CHECK(s.triangle_to_parent == std::vector<int>{2, 3});
  for (std::size_t i = 0; i < s.mesh.vertices.size(); ++i) {
    CHECK(s.mesh.vertices[i] == m.vertices[s.vertex_to_parent[i]]);
    CHECK(s.parent_to_vertex[s.vertex_to_parent[i]] == static_cast<int>(i));
  }
  CHECK(s.parent_to_vertex[0] == -1);
  CHECK(kneesim::models::check_mesh(s.mesh).boundary_edges == 4);
  TriMesh two = m;
  kneesim::models::append(
      two, kneesim::models::transformed(m, Eigen::Isometry3d(Eigen::Translation3d(3.0, 0.0, 0.0))));
  CHECK(kneesim::models::enclosed_volume(two) == doctest::Approx(2.0));
  CHECK(kneesim::models::check_mesh(two).watertight());
}
