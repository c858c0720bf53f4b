// The area inside the contact line (engine/contact_line.h) against closed forms:
//  - triangle: linear corner values; the part below zero is the corner triangle cut at the
//    edges' zero crossings (fractions t_ab t_ac), or its complement;
//  - quad: a bilinear field linear in u, phi = u - u0, is negative on the strip u < u0; with
//    the midpoints of an n x n grid the sampled fraction is exact when u0 n is a whole number,
//    within 1/n otherwise;
//  - a rigid sphere of radius R pressed by delta into a flat surface (the elastic-foundation
//    bed of triangles, and the top quads of a hex8 box at rest) touches it inside the circle
//    of radius a, a^2 = 2 R delta - delta^2. The line area is pi a^2 up to the field's
//    geometric error (the field too large by under 0.6 um, contact_pipeline_test.cpp: a
//    shorter by R/a x 0.6 um, 0.3 % of the area), the linear (bilinear) interpolation of phi
//    over 0.2 mm elements (phi's curvature along the surface about 1/R: (h^2/8)/R = 0.5 um,
//    0.25 %) and for quads the 1/16 sampling of the cut ones (signed, averaging out round the
//    circle); tolerance 1 %. (At rest, the touching nodes' tributary areas and the elements
//    with a positive pressure also give pi a^2 on average, by the lattice count: their error
//    is a scatter of a few per cent with the circle's position on the grid, printed only. The
//    line measure matters under load, where the insert conforms to the femur and the nodes just
//    outside the patch nearly touch.)
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "engine/contact_line.h"
#include "engine/data.h"
#include "engine/sdf.h"
#include "engine/solid/surface_contact.h"
#include "engine/step.h"
#include "engine_fixtures.h"
#include "solid_fixtures.h"

using namespace kneesim;

TEST_CASE("triangle fraction below zero: the cut corner in closed form") {
  using engine::calc_triangle_negative_fraction;
  CHECK(calc_triangle_negative_fraction(1.0, 2.0, 3.0) == 0.0);
  CHECK(calc_triangle_negative_fraction(-1.0, -2.0, -3.0) == 1.0);
  // one corner below: zero crossings at 1/2 and 1/4 of its edges -> 1/8
  CHECK(calc_triangle_negative_fraction(-1.0, 1.0, 3.0) == doctest::Approx(0.125));
  CHECK(calc_triangle_negative_fraction(3.0, -1.0, 1.0) == doctest::Approx(0.125));
  CHECK(calc_triangle_negative_fraction(1.0, 3.0, -1.0) == doctest::Approx(0.125));
  // two corners below: the complement of the corner above, cut at 1/2 on both edges -> 3/4
  CHECK(calc_triangle_negative_fraction(-1.0, -1.0, 1.0) == doctest::Approx(0.75));
  CHECK(calc_triangle_negative_fraction(1.0, -1.0, -1.0) == doctest::Approx(0.75));
  CHECK(calc_triangle_negative_fraction(-1.0, 1.0, -1.0) == doctest::Approx(0.75));
  // a corner exactly on the line adds nothing below zero
  CHECK(calc_triangle_negative_fraction(0.0, 1.0, 1.0) == 0.0);
  CHECK(calc_triangle_negative_fraction(0.0, -1.0, -1.0) == 1.0);
}

TEST_CASE("quad fraction below zero: a strip of a field linear in u") {
  using engine::calc_quad_negative_fraction;
  // corners in cyclic order (u, v) = (0,0), (1,0), (1,1), (0,1)
  const auto strip = [](double u0) { return std::array<double, 4>{-u0, 1.0 - u0, 1.0 - u0, -u0}; };
  CHECK(calc_quad_negative_fraction(strip(0.25), 16) == 0.25);
  CHECK(calc_quad_negative_fraction(strip(0.5), 16) == 0.5);
  CHECK(std::abs(calc_quad_negative_fraction(strip(0.3), 16) - 0.3) <= 1.0 / 16);
  CHECK(std::abs(calc_quad_negative_fraction(strip(0.3), 256) - 0.3) <= 1.0 / 256);
  CHECK(calc_quad_negative_fraction({1.0, 2.0, 3.0, 4.0}, 16) == 0.0);
  CHECK(calc_quad_negative_fraction({-1.0, -2.0, -3.0, -4.0}, 16) == 1.0);
  // one corner below of a field bilinear in both: the region u v' ... is the corner's, small
  const double f = calc_quad_negative_fraction({-1.0, 1.0, 1.0, 1.0}, 64);
  CHECK(f > 0.0);
  CHECK(f < 0.25);
}

namespace {
constexpr double kR = 10e-3, kDelta = 0.2e-3;
const double kContactRadius2 = 2.0 * kR * kDelta - kDelta * kDelta;  // a^2 [m^2]
}  // namespace

TEST_CASE("rigid insert: the line area of a sphere on a flat bed is pi a^2") {
  // the contact pipeline's sphere (contact_pipeline_test.cpp): cap to 20 deg, field 0.1 mm,
  // bed 6 x 6 mm of 0.2 mm squares (two triangles each), top at y = 1 mm
  const double layer = 1e-3;
  engine::Model m = test::make_locked_model(1e-5);
  m.insert = test::make_flat_bed(3e-3, 30, layer);
  const models::TriMesh cap = test::make_spherical_cap(kR, std::numbers::pi / 9.0, 40, 128);
  m.femur_sdf = engine::make_signed_distance_field(cap.vertices, cap.triangles, 0.1e-3, 0.45e-3);
  m.carriages[0].pivot0_W = Eigen::Vector3d(0.0, layer + kR - kDelta, 0.0);
  m.contact.foundation_modulus = 4e9;
  m.contact.damping_beta = 0.0;
  const engine::State s = engine::make_initial_state(m);
  engine::Data d = engine::make_data(m);
  engine::calc_forces(m, s, d);
  const std::array<double, 2> line = engine::calc_contact_line_area(m, d);
  const double expected = std::numbers::pi * kContactRadius2;
  const double elements = d.contact.area[0] + d.contact.area[1];
  MESSAGE("sphere on bed: line area " << (line[0] + line[1]) * 1e6 << " mm^2, elements with p > 0 "
          << elements * 1e6 << " mm^2, pi a^2 = " << expected * 1e6 << " mm^2");
  CHECK((line[0] + line[1]) / expected == doctest::Approx(1.0).epsilon(0.01));
  // centred: the two sides (z < 0 and z > 0) carry half each, up to the bed's diagonals
  CHECK(line[0] / (line[0] + line[1]) == doctest::Approx(0.5).epsilon(0.01));
}

TEST_CASE("deformable insert: the line area of a sphere on the top quads is pi a^2") {
  // a hex8 box 8 x 2 x 8 mm of 0.2 mm top quads at rest (top at y = 2 mm), the sphere's pole
  // delta below the top; the quads' nodes sampled where they are
  const test::BoxMesh mesh = test::make_box(40, 2, 40, {8e-3, 2e-3, 8e-3}, {-4e-3, 0.0, -4e-3});
  engine::Model m;
  m.insert_solid = engine::solid::make_solid_model(mesh.nodes, mesh.elements,
                                                   test::make_elastic(1e9, 0.4, 945.0), {});
  m.insert_contact =
      engine::solid::make_surface_contact(m.insert_solid, mesh.top_faces, mesh.top_face_element, 0.0, 1e-3);
  m.insert_top_faces = mesh.top_faces;
  models::TriMesh cap = test::make_spherical_cap(kR, std::numbers::pi / 9.0, 40, 128);
  for (auto& v : cap.vertices) v.y() += 2e-3 + kR - kDelta;  // pole delta below the top
  m.femur_sdf = engine::make_signed_distance_field(cap.vertices, cap.triangles, 0.1e-3, 0.45e-3);
  engine::Data d;  // the frame's pose (both identity) and the nodes' contact state
  d.insert_contact = engine::solid::make_surface_contact_data(m.insert_contact);
  double tributary = 0.0;
  for (int i = 0; i < m.insert_contact.size(); ++i) {
    const Eigen::Vector3d& x = m.insert_solid.reference_positions[m.insert_contact.nodes[i]];
    d.insert_contact.position[i] = x;
    const double phi = m.femur_sdf.sample(x);
    d.insert_contact.pressure[i] = phi < 0.0 ? 1.0 : 0.0;
    if (phi < 0.0) {
      ++d.insert_contact.nodes_in_contact;
      tributary += m.insert_contact.area[i];
    }
  }
  const std::array<double, 2> line = engine::calc_contact_line_area(m, d);
  const double expected = std::numbers::pi * kContactRadius2;
  MESSAGE("sphere on hex8 top: line area " << (line[0] + line[1]) * 1e6
          << " mm^2, touching nodes' tributary area " << tributary * 1e6 << " mm^2, pi a^2 = "
          << expected * 1e6 << " mm^2");
  CHECK((line[0] + line[1]) / expected == doctest::Approx(1.0).epsilon(0.01));
  CHECK(line[0] / (line[0] + line[1]) == doctest::Approx(0.5).epsilon(0.01));
}
