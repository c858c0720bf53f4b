// Signed distance field (engine/sdf.h) of a closed icosphere of radius R = 10 mm (level 4,
// 5120 triangles) against
//  - the analytic distance |p| - R: within the mesh's chordal error (max over triangles of
//    R - distance from the centre to the triangle, computed here, ~13 um) plus the sampling
//    error of the field (below);
//  - the exact unsigned distance to the mesh itself, MeshBvh::closest_point (FCL BVH query),
//    signed by the analytic side: within the sampling error only. Sampling error of trilinear
//    interpolation on a grid of spacing s: (s^2/8) * (sum of the Hessian's |eigenvalues| =
//    2/r) for the smooth part, plus the creases of the polyhedral distance (a slope jump of at
//    most the dihedral angle theta between neighbouring facets, error <= theta s / 4) —
//    stated per test below with s = 0.25 mm;
//  - the band convention: |phi| clamps to the band beyond it (+band outside, -band inside),
//    and +band outside the grid; the sign is right wherever |p| - R exceeds the chordal error.
// Points are sampled at random (fixed seed) in a shell |p| - R in [-2, 2] mm and in the box.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "engine/fcl_adapter.h"
#include "engine/sdf.h"
#include "engine/sdf_pairs.h"
#include "engine_fixtures.h"

using namespace kneesim;

namespace {

constexpr double kR = 10e-3;        // sphere radius [m]
constexpr double kSpacing = 0.25e-3;  // grid spacing [m]
constexpr double kBand = 1.0e-3;    // exact band half-width [m]

struct Fixture {
  models::TriMesh mesh = test::make_icosphere(kR, 4);
  engine::SignedDistanceField sdf =
      engine::make_signed_distance_field(mesh.vertices, mesh.triangles, kSpacing, kBand);
  double chordal = 0.0;    // max gap between the mesh and the sphere [m]
  double dihedral = 0.0;   // max angle between normals of triangles sharing an edge [rad]
  Fixture() {
    const auto normals = models::face_normals(mesh);
    for (const auto& t : mesh.triangles) {
      const auto proj = engine::project_on_triangle(mesh.vertices[t[0]], mesh.vertices[t[1]],
                                                    mesh.vertices[t[2]], Eigen::Vector3d::Zero());
      chordal = std::max(chordal, kR - std::sqrt(proj.squared_distance));
    }
    // neighbouring facets: bounded by the largest angle between any two facets sharing a vertex
    std::vector<std::vector<int>> at_vertex(mesh.vertices.size());
    for (size_t f = 0; f < mesh.triangles.size(); ++f)
      for (int c = 0; c < 3; ++c) at_vertex[mesh.triangles[f][c]].push_back(static_cast<int>(f));
    for (const auto& fs : at_vertex)
      for (int a : fs)
        for (int b : fs)
          dihedral = std::max(dihedral, std::acos(std::clamp(normals[a].dot(normals[b]), -1.0, 1.0)));
  }
  // sampling error bound at distance r from the centre (r > 0)
  double sampling_error(double r) const {
    return kSpacing * kSpacing / 8.0 * 2.0 / r + dihedral * kSpacing / 4.0;
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

}  // namespace

TEST_CASE("icosphere fixture is a closed outward mesh") {
  const auto& f = fixture();
  const auto check = models::check_mesh(f.mesh);
  CHECK(check.watertight());
  CHECK(models::enclosed_volume(f.mesh) > 0.0);
  // volume of the inscribed polyhedron: below the sphere's, within 3 chordal errors * area
  const double v_sphere = 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
  CHECK(models::enclosed_volume(f.mesh) < v_sphere);
  CHECK(models::enclosed_volume(f.mesh) > v_sphere - 4.0 * std::numbers::pi * kR * kR * f.chordal);
  MESSAGE("icosphere level 4: chordal error " << f.chordal * 1e6 << " um, max facet angle "
                                               << f.dihedral << " rad");
}

TEST_CASE("signed distance field of a sphere vs |p| - R and vs the FCL BVH distance") {
  const auto& f = fixture();
  const engine::MeshBvh bvh(f.mesh.vertices, f.mesh.triangles);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_analytic = 0.0, worst_bvh = 0.0, worst_grad = 0.0;
  int in_band = 0, signs_checked = 0;
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3d dir(u(rng), u(rng), u(rng));
    if (dir.norm() < 1e-3) continue;
    dir.normalize();
    const double r = kR + 2e-3 * u(rng);  // shell |p| - R in [-2, 2] mm
    const Eigen::Vector3d p = r * dir;
    Eigen::Vector3d grad;
    const double phi = f.sdf.sample(p, &grad);
    const double analytic = r - kR;
    // sign wherever the side is unambiguous
    if (std::abs(analytic) > f.chordal + f.sampling_error(r)) {
      ++signs_checked;
      CHECK((phi > 0.0) == (analytic > 0.0));
    }
    // exact band, away from its edge by the interpolation stencil (sqrt(3) s)
    if (std::abs(analytic) < kBand - std::sqrt(3.0) * kSpacing - f.chordal) {
      ++in_band;
      const double tol_sampling = f.sampling_error(std::min(r, kR) - kBand);
      const double err_analytic = std::abs(phi - analytic);
      worst_analytic = std::max(worst_analytic, err_analytic);
      CHECK(err_analytic <= f.chordal + tol_sampling);
      // against the mesh's own exact distance (BVH), signed by the side of the mesh
      Eigen::Vector3d q;
      int tri = -1;
      const double dist = bvh.closest_point(p, q, tri);
      const double side = (p - q).dot(q) >= 0.0 ? 1.0 : -1.0;  // outward: along q
      const double err_bvh = std::abs(phi - side * dist);
      worst_bvh = std::max(worst_bvh, err_bvh);
      CHECK(err_bvh <= tol_sampling);
      // gradient: the unit radial direction, to the slope error of one cell
      if (std::abs(analytic) > 2.0 * kSpacing) worst_grad = std::max(worst_grad, (grad - dir).norm());
    }
    // beyond the band (by a cell) the field holds the clamp value
    if (analytic > kBand + std::sqrt(3.0) * kSpacing + f.chordal)
      CHECK(phi == doctest::Approx(kBand).scale(0));
    if (analytic < -(kBand + std::sqrt(3.0) * kSpacing + f.chordal)) {
      CHECK(phi == doctest::Approx(-kBand).scale(0));
    }
  }
  MESSAGE("sdf vs |p| - R: max error " << worst_analytic * 1e6 << " um over " << in_band
          << " points in the band (bound: chordal " << f.chordal * 1e6 << " um + sampling "
          << f.sampling_error(kR - kBand) * 1e6 << " um); vs FCL BVH distance: max error "
          << worst_bvh * 1e6 << " um; gradient max deviation " << worst_grad << "; "
          << signs_checked << " signs checked");
  CHECK(in_band > 4000);
  CHECK(worst_grad < 0.2);
}

TEST_CASE("signed distance field far from the surface and outside the grid") {
  const auto& f = fixture();
  // deep inside (the centre): -band; far outside within the grid: +band; outside the grid:
  // +band with zero gradient
  CHECK(f.sdf.sample(Eigen::Vector3d::Zero()) == doctest::Approx(-kBand).scale(0));
  const Eigen::Vector3d corner = f.sdf.origin + Eigen::Vector3d::Constant(1.5 * kSpacing);
  CHECK(f.sdf.sample(corner) == doctest::Approx(kBand).scale(0));
  Eigen::Vector3d g;
  CHECK(f.sdf.sample(Eigen::Vector3d(1.0, 0.0, 0.0), &g) == kBand);
  CHECK(g.norm() == 0.0);
  // the grid covers the mesh with the band and two cells of padding on every side
  for (int a = 0; a < 3; ++a) {
    CHECK(f.sdf.origin[a] <= -kR - kBand - 2.0 * kSpacing + 1e-12);
    CHECK(f.sdf.origin[a] + (f.sdf.dims[a] - 1) * kSpacing >= kR + kBand + 2.0 * kSpacing - 1e-12);
  }
}

TEST_CASE("bricked field: a sample is the trilinear interpolation of its cell's 8 node values") {
  // reference: the interpolation written out from node(i, j, k), which addresses a node through
  // whichever brick holds it; bricks share their boundary nodes, so cells on a brick face, edge
  // and corner (local index 6) are included by drawing cells across the whole grid
  const auto& f = fixture();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int stored = 0;
  for (int n = 0; n < 20000; ++n) {
    Eigen::Vector3d g;
    for (int a = 0; a < 3; ++a) g[a] = u(rng) * (f.sdf.dims[a] - 1);
    const int i = static_cast<int>(std::floor(g.x())), j = static_cast<int>(std::floor(g.y())),
              k = static_cast<int>(std::floor(g.z()));
    if (i >= f.sdf.dims.x() - 1 || j >= f.sdf.dims.y() - 1 || k >= f.sdf.dims.z() - 1) continue;
    const double tx = g.x() - i, ty = g.y() - j, tz = g.z() - k;
    double expected = 0.0;
    for (int c = 0; c < 8; ++c) {
      const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
      expected += (di ? tx : 1 - tx) * (dj ? ty : 1 - ty) * (dk ? tz : 1 - tz) *
                  f.sdf.node(i + di, j + dj, k + dk);
    }
    const double phi = f.sdf.sample(f.sdf.origin + f.sdf.spacing * g);
    if (std::abs(phi) < kBand) ++stored;
    // the two evaluation orders differ by rounding only (values ~1e-3 m, double arithmetic)
    CHECK(std::abs(phi - expected) <= 1e-15);
  }
  // the field is mostly clamp values: only bricks near the surface are stored
  const int all = f.sdf.bricks.prod();
  MESSAGE("bricks stored: " << f.sdf.stored_bricks() << " of " << all << "; samples in the band: "
                            << stored);
  CHECK(f.sdf.stored_bricks() < all);
  CHECK(stored > 100);
}

TEST_CASE("pairs of samples (engine/sdf_pairs.h) equal the scalar map and sample bit for bit") {
  // reference: the scalar path of the contact kernel, A p + b (Eigen) then sample_grid, for
  // each point of a pair. Points from a box larger than the grid (some pairs have one or both
  // points outside: the fallback) under a rotated, scaled map like the kernel's X_FT / spacing;
  // the points inside cover stored bricks, clamp bricks (+band and -band) and brick faces.
  const auto& f = fixture();
  const engine::FieldSampler s = f.sdf.sampler();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.4e-3, -0.7e-3, 0.2e-3);
  const Eigen::Matrix3d A = R / f.sdf.spacing;
  const Eigen::Vector3d b = (t - f.sdf.origin) / f.sdf.spacing;
  const engine::PairGridMap map(A, b);
  std::mt19937 rng(11);
  const double half = -f.sdf.origin.x() + 2.0 * kSpacing;  // beyond the grid by two cells
  std::uniform_real_distribution<double> u(-half, half);
  int inside = 0, clamp = 0, fallback = 0, mismatches = 0;
  for (int n = 0; n < 50000; ++n) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng)), q(u(rng), u(rng), u(rng));
    double out[2];
    engine::sample_pair(s, map, p, q, out);
    const double ref_p = s.sample_grid(A * p + b), ref_q = s.sample_grid(A * q + b);
    mismatches += out[0] != ref_p || out[1] != ref_q;
    for (const double v : {ref_p, ref_q}) {
      inside += std::abs(v) < kBand;
      clamp += std::abs(v) == static_cast<float>(kBand);
    }
    fallback += ref_p == kBand || ref_q == kBand;  // outside the grid (or on its clamp value)
  }
  MESSAGE("samples in the band " << inside << ", at a clamp value " << clamp
                                 << ", pairs with a point outside the grid " << fallback);
  CHECK(mismatches == 0);
  CHECK(inside > 1000);
  CHECK(clamp > 1000);
  CHECK(fallback > 1000);
}
