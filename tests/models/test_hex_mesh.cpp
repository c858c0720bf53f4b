// Structured hex meshes (models/hex_mesh.h). References: the box's element volumes sum to the
// box volume; the generic insert's mesh follows the exact height field insert_surface_height
// at its top nodes in the dishes (to the chordal error of the triangulated surface, 0.05 mm
// at 1 mm edges),
// its volume equals the insert's enclosed volume within the bilinear-top error (1 %), the
// layer grading is as requested, and no element is inverted (make_solid_model accepts it);
// the Grand Challenge DM and JW inserts mesh without inverted elements; bad options and a top at or
// below the base are one-sentence errors.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "engine/io/source_tree.h"
#include "engine/errors.h"
#include "engine/solid/solid_build.h"
#include "models/deformable_insert.h"
#include "models/generic_tkr.h"
#include "models/hex_mesh.h"
#include "models/mesh_io.h"

using namespace kneesim;
namespace fs = std::filesystem;

namespace {

engine::solid::SolidMaterial uhmwpe() {
  engine::solid::SolidMaterial m;
  m.youngs_modulus = 685e6;
  m.poisson = 0.47;
  m.density = 935.0;
  return m;
}

double mesh_volume(const engine::solid::SolidModel& s) {
  double v = 0.0;
  for (const auto& r : s.reference) v += r.volume;
  return v;
}

}  // namespace

TEST_CASE("box hex mesh: counts, volume, top faces and base nodes") {
  const Eigen::Vector3d size(0.018, 0.012, 0.012);
  const models::HexMesh m = models::make_box_hex_mesh(6, 4, 3, size, Eigen::Vector3d(-0.009, 0, -0.006));
  CHECK(m.elements.size() == 72u);
  CHECK(m.nodes.size() == 7u * 5u * 4u);
  CHECK(m.top_faces.size() == 18u);
  CHECK(m.base_nodes.size() == 28u);
  const auto s = engine::solid::make_solid_model(m.nodes, m.elements, uhmwpe(), {});
  CHECK(mesh_volume(s) == doctest::Approx(size.prod()).epsilon(1e-12).scale(0));
  for (size_t f = 0; f < m.top_faces.size(); ++f) {
    // the top quad lies on y = 12 mm, faces up, and is a face of its element
    const auto& q = m.top_faces[f];
    const Eigen::Vector3d n = (m.nodes[q[1]] - m.nodes[q[0]]).cross(m.nodes[q[3]] - m.nodes[q[0]]);
    CHECK(n.y() > 0.0);
    for (int a = 0; a < 4; ++a) {
      CHECK(m.nodes[q[a]].y() == doctest::Approx(0.012).scale(0));
      const auto& e = m.elements[m.top_face_element[f]];
      CHECK(std::find(e.begin(), e.end(), q[a]) != e.end());
    }
  }
  for (int n : m.base_nodes) CHECK(m.nodes[n].y() == 0.0);
}

TEST_CASE("generic insert hex mesh follows the height field, keeps the volume, grades the layers") {
  const models::GenericTkrParams p;
  const models::TriMesh insert = models::make_generic_insert(p, 1e-3);
  models::InsertMeshOptions o;
  o.element_size = 1.5e-3;
  o.layers = 4;
  o.grading = 0.5;
  const models::HexMesh m = models::make_insert_hex_mesh(insert, 0.0, o);
  const auto s = engine::solid::make_solid_model(m.nodes, m.elements, uhmwpe(), {});
  MESSAGE("generic insert: " << m.elements.size() << " elements, " << m.nodes.size() << " nodes, "
          << "dt_critical " << s.dt_critical << " s");
  // the rectangular footprint is covered completely: 4 layers under every top face
  CHECK(m.elements.size() == 4 * m.top_faces.size());
  CHECK(mesh_volume(s) == doctest::Approx(models::enclosed_volume(insert)).epsilon(0.01).scale(0));
  // in the dishes (0.5 mm and more below the eminence plane, away from the kink where the
  // dish meets the plane, which the triangulation rounds off over one edge)
  double worst = 0.0;
  int checked = 0;
  for (const auto& q : m.top_faces)
    for (int n : q) {
      const Eigen::Vector3d& x = m.nodes[n];
      const double exact = models::insert_surface_height(p, x.x(), x.z());
      if (exact > p.insert_eminence_height_m - 5e-4) continue;
      worst = std::max(worst, std::abs(x.y() - exact));
      ++checked;
    }
  CHECK(checked > 500);
  CHECK(worst < 5e-5);
  // grading: in the column under a dwell point, top layer / bottom layer = 0.5
  const Eigen::Vector3d dwell = models::dwell_point(p, 0);
  int base = -1;
  for (int n : m.base_nodes)
    if (base < 0 || (m.nodes[n] - Eigen::Vector3d(dwell.x(), 0, dwell.z())).norm() <
                        (m.nodes[base] - Eigen::Vector3d(dwell.x(), 0, dwell.z())).norm())
      base = n;
  const double bottom = m.nodes[base + 1].y() - m.nodes[base].y();
  const double topl = m.nodes[base + 4].y() - m.nodes[base + 3].y();
  CHECK(topl / bottom == doctest::Approx(0.5).epsilon(1e-9).scale(0));
  CHECK(m.nodes[base + 4].y() == doctest::Approx(p.insert_thickness_m).epsilon(0.01).scale(0));
}

TEST_CASE("Grand Challenge DM and JW inserts mesh without inverted elements") {
  const char* data = std::getenv("KNEESIM_DATA");
  const fs::path dir = data ? fs::path(data) : kneesim::io::source_dir() / "../shared/data";
  for (const std::string name : {"gc6_dm", "gc4_jw"}) {
    CAPTURE(name);
    const fs::path file = dir / name / "tibial_insert.stl";
    if (!fs::exists(file)) {
      MESSAGE("skipped: " << file << " absent (set KNEESIM_DATA to the shared data folder)");
      continue;
    }
    // as models/examples/dm_stanmore.toml (both data sets share the axes): metres, turned
    // 180 deg about y; the base plane at the insert's lowest point
    models::MeshImportOptions io;
    io.units = "m";
    io.rotation = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const models::TriMesh insert = models::load_mesh(file, io);
    models::InsertMeshOptions o;
    o.element_size = 1.5e-3;
    const double base_y = models::bounding_box(insert).min().y();
    const models::HexMesh m = models::make_insert_hex_mesh(insert, base_y, o);
    const auto s = engine::solid::make_solid_model(m.nodes, m.elements, uhmwpe(), {});
    const double volume = models::enclosed_volume(insert);
    MESSAGE(name << " insert: " << m.elements.size() << " elements, volume " << mesh_volume(s) * 1e9
            << " mm^3 vs enclosed " << volume * 1e9 << " mm^3");
    CHECK(m.elements.size() > 1000u);
    // the stair-stepped outline loses a strip up to one element wide around the rim, and the
    // columns fill whatever lies under the top down to the base plane: within 5 %
    CHECK(mesh_volume(s) == doctest::Approx(volume).epsilon(0.05).scale(0));
  }
}

TEST_CASE("insert hex mesh bad input is one sentence naming the value and the range") {
  const models::TriMesh insert = models::make_generic_insert(models::GenericTkrParams{}, 2e-3);
  models::InsertMeshOptions o;
  o.layers = 0;
  CHECK_THROWS_WITH_AS(models::make_insert_hex_mesh(insert, 0.0, o),
                       "insert hex mesh: layers 0 is out of range (must be >= 1)", InputError);
  o.layers = 3;
  o.element_size = 0.0;
  CHECK_THROWS_WITH_AS(models::make_insert_hex_mesh(insert, 0.0, o),
                       "insert hex mesh: element size 0 mm is out of range (must be > 0)",
                       InputError);
  o.element_size = 2e-3;
  // a base plane above the insert's lowest top point: zero or negative layer thickness
  CHECK_THROWS_WITH_AS(models::make_insert_hex_mesh(insert, 0.010, o),
                       doctest::Contains("mm above the base plane (layer thickness must be > 0)"),
                       InputError);
}

TEST_CASE("refined grid lines: fine in the zone, growing away from it, ending exactly") {
  // zone [-5, 5] mm and [12, 14] mm of [-20, 20] mm; 0.25 mm in it, growing by 1.3 to 2 mm
  const std::vector<models::Interval> zone = {{-5e-3, 5e-3}, {12e-3, 14e-3}};
  const std::vector<double> v = models::make_refined_lines(-20e-3, 20e-3, zone, 0.25e-3, 2e-3, 1.3);
  REQUIRE(v.size() > 2u);
  CHECK(v.front() == -20e-3);
  CHECK(v.back() == 20e-3);
  double in_zone_max = 0.0, largest = 0.0, worst_ratio = 1.0;
  for (size_t i = 1; i < v.size(); ++i) {
    const double h = v[i] - v[i - 1];
    CHECK(h > 0.0);
    largest = std::max(largest, h);
    const double mid = 0.5 * (v[i] + v[i - 1]);
    if ((mid > -5e-3 && mid < 5e-3) || (mid > 12e-3 && mid < 14e-3)) in_zone_max = std::max(in_zone_max, h);
    if (i > 1) {
      const double prev = v[i - 1] - v[i - 2];
      worst_ratio = std::max(worst_ratio, std::max(h / prev, prev / h));
    }
  }
  // the spacing follows s(v) = min(coarse, fine + 0.3 d) to within the rounding of whole cells
  CHECK(in_zone_max < 0.25e-3 * 1.05);
  CHECK(largest < 2e-3 * 1.05);
  CHECK(largest > 2e-3 * 0.9);  // the far ends reach the coarse spacing
  CHECK(worst_ratio < 1.3 * 1.05);  // neighbours differ by the growth at most
  // no zone, or coarse = fine: the uniform grid
  const std::vector<double> u = models::make_refined_lines(0.0, 10e-3, {}, 1e-3, 2e-3, 1.3);
  CHECK(u.size() == 6u);
  CHECK(u[1] == doctest::Approx(2e-3).scale(0));
}

TEST_CASE("graded layers: the top layer as asked, the fewest layers growing by 'growth' that reach the height") {
  for (const auto& [height, top] : {std::pair{8e-3, 0.5e-3}, std::pair{6e-3, 0.15e-3},
                                    std::pair{10e-3, 1e-3}}) {
    CAPTURE(height);
    CAPTURE(top);
    const auto [layers, grading] = models::find_graded_layers(height, top, 1.5);
    // the fewest layers of growth 1.5 that reach the height
    const double q = 1.5;
    CHECK(top * (std::pow(q, layers) - 1) / (q - 1) >= height * (1 - 1e-12));
    CHECK(top * (std::pow(q, layers - 1) - 1) / (q - 1) < height);
    // the mesh's layer fractions give exactly that top layer
    const double r = std::pow(grading, 1.0 / (layers - 1));
    double sum = 0.0, t = 1.0;
    for (int l = 0; l < layers; ++l, t *= r) sum += t;
    CHECK(height * std::pow(r, layers - 1) / sum == doctest::Approx(top).epsilon(1e-9));
    // the layer count rounded up, so the growth that fits the height is at most the one asked
    CHECK(1.0 / r <= q * (1 + 1e-9));
    CHECK(1.0 / r > 1.0);
  }
  CHECK(models::find_graded_layers(1e-3, 2e-3, 1.5) == std::pair<int, double>{1, 1.0});
}

TEST_CASE("generic insert mesh refined in a zone: whole columns, fine spacing there, no inverted element") {
  const models::GenericTkrParams p;
  const models::TriMesh insert = models::make_generic_insert(p, 1e-3);
  models::InsertMeshOptions o;
  o.element_size = 0.6e-3;
  o.element_size_z = 0.8e-3;
  o.outer_element_size = 3e-3;
  o.layers = 5;
  o.grading = 0.2;
  o.refine_x = {{-8e-3, 6e-3}};
  o.refine_z = {{-28e-3, -14e-3}, {14e-3, 28e-3}};
  const models::HexMesh m = models::make_insert_hex_mesh(insert, 0.0, o);
  const auto s = engine::solid::make_solid_model(m.nodes, m.elements, uhmwpe(), {});
  MESSAGE("refined generic insert: " << m.elements.size() << " elements");
  CHECK(m.elements.size() == 5 * m.top_faces.size());
  CHECK(m.nodes.size() == 6 * m.base_nodes.size());  // whole columns (the wear update needs them)
  CHECK(mesh_volume(s) == doctest::Approx(models::enclosed_volume(insert)).epsilon(0.01).scale(0));
  // the top faces inside the zone are at most the refined spacing wide
  int inside = 0;
  for (const auto& q : m.top_faces) {
    const Eigen::Vector3d c = 0.25 * (m.nodes[q[0]] + m.nodes[q[1]] + m.nodes[q[2]] + m.nodes[q[3]]);
    if (!(c.x() > -8e-3 && c.x() < 6e-3 && std::abs(c.z()) > 14e-3 && std::abs(c.z()) < 28e-3)) continue;
    ++inside;
    double dx = 0.0, dz = 0.0;
    for (int a = 0; a < 4; ++a) {
      dx = std::max(dx, std::abs(m.nodes[q[a]].x() - m.nodes[q[(a + 1) % 4]].x()));
      dz = std::max(dz, std::abs(m.nodes[q[a]].z() - m.nodes[q[(a + 1) % 4]].z()));
    }
    CHECK(dx < 0.6e-3 * 1.05);
    CHECK(dz < 0.8e-3 * 1.05);
  }
  // the zone holds (14 / 0.6) x (2 x 14 / 0.8) = 817 refined cells; those cut by its edges
  // (a spacing that does not divide it) and by the insert's outline are not counted
  CHECK(inside > 0.9 * 817);
  // the same zone with no refinement keeps the uniform mesher's grid
  o.outer_element_size = 0.0;
  o.element_size_z = 0.0;
  o.element_size = 2e-3;
  const models::HexMesh u = models::make_insert_hex_mesh(insert, 0.0, o);
  o.refine_x.clear();
  o.refine_z.clear();
  const models::HexMesh u2 = models::make_insert_hex_mesh(insert, 0.0, o);
  CHECK(u.nodes == u2.nodes);
}
