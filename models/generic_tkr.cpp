#include "models/generic_tkr.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "engine/errors.h"

namespace kneesim::models {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = std::numbers::pi / 180.0;

// outward direction of the sagittal profile point whose lowest-point flexion is theta
Eigen::Vector2d profile_normal(double theta) { return {-std::sin(theta), -std::cos(theta)}; }

// d normal / d theta: the direction in which the profile runs (anterior -> posterior)
Eigen::Vector2d profile_tangent(double theta) { return {-std::cos(theta), std::sin(theta)}; }

// centre of the posterior arc, tangent to the distal arc at the transition [m]
Eigen::Vector2d posterior_centre(const GenericTkrParams& p) {
  return (p.femur_distal_radius_m - p.femur_posterior_radius_m) *
         profile_normal(p.femur_transition_rad);
}

// drop of the convex coronal arc at lateral offset u from the condyle centre line [m]
double coronal_drop(double radius, double u) { return radius - std::sqrt(radius * radius - u * u); }

int segments(double length, double edge) {
  return std::max(1, static_cast<int>(std::ceil(length / edge - 1e-9)));
}

// triangle (a, b, c) appended with its winding turned so its normal points along `outward`
void add_triangle(TriMesh& m, int a, int b, int c, const Eigen::Vector3d& outward) {
  const Eigen::Vector3d n = (m.vertices[b] - m.vertices[a]).cross(m.vertices[c] - m.vertices[a]);
  if (n.dot(outward) < 0.0) std::swap(b, c);
  m.triangles.emplace_back(a, b, c);
}

// quad a-b-c-d (in order round its edge) as two triangles facing `outward`
void add_quad(TriMesh& m, int a, int b, int c, int d, const Eigen::Vector3d& outward) {
  add_triangle(m, a, b, c, outward);
  add_triangle(m, a, c, d, outward);
}

std::string mm(double v_m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v_m * 1000.0);
  return buf;
}

[[noreturn]] void bad(const std::string& key, const std::string& value, const std::string& rule) {
  throw InputError("generic implant: " + key + " = " + value + " is not allowed; " + rule + ".");
}

// one condyle solid centred at z = zc
TriMesh make_condyle(const GenericTkrParams& p, double zc, double e) {
  const double w = p.condyle_width_m, t = p.femur_thickness_m, rc = p.femur_coronal_radius_m;
  const double th_a = -p.femur_anterior_extent_rad, th_t = p.femur_transition_rad,
               th_p = p.femur_posterior_extent_rad;
  const Eigen::Vector2d cp = posterior_centre(p);

  // profile stations: distal arc, then posterior arc, each evenly spaced
  std::vector<double> theta;
  const int nd = segments(p.femur_distal_radius_m * (th_t - th_a), e);
  const int np = segments(p.femur_posterior_radius_m * (th_p - th_t), e);
  for (int i = 0; i < nd; ++i) theta.push_back(th_a + (th_t - th_a) * i / nd);
  for (int i = 0; i <= np; ++i) theta.push_back(th_t + (th_p - th_t) * i / np);

  // cross-section ring (radial offset from the arc, lateral offset u): outer coronal arc, outer
  // wall, inner face, inner wall; nu is even so the centre line u = 0 is a vertex line
  int nu = segments(w, e);
  nu += nu % 2;
  const double edge_drop = coronal_drop(rc, 0.5 * w);
  const int nw = segments(t - edge_drop, e);
  std::vector<Eigen::Vector2d> ring;  // (radial offset, u)
  for (int j = 0; j <= nu; ++j) {
    const double u = -0.5 * w + w * j / nu;
    ring.emplace_back(-coronal_drop(rc, u), u);
  }
  for (int k = 1; k <= nw; ++k) ring.emplace_back(-edge_drop - (t - edge_drop) * k / nw, 0.5 * w);
  for (int j = 1; j <= nu; ++j) ring.emplace_back(-t, 0.5 * w - w * j / nu);
  for (int k = 1; k < nw; ++k) ring.emplace_back(-t + (t - edge_drop) * k / nw, -0.5 * w);
  const int nr = static_cast<int>(ring.size());

  TriMesh m;
  std::vector<Eigen::Vector3d> ring_centre;
  for (double th : theta) {
    const bool distal = th <= th_t;
    const Eigen::Vector2d c = distal ? Eigen::Vector2d::Zero() : cp;
    const double r = distal ? p.femur_distal_radius_m : p.femur_posterior_radius_m;
    const Eigen::Vector2d n = profile_normal(th);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector2d& q : ring) {
      const Eigen::Vector2d xy = c + (r + q.x()) * n;
      m.vertices.emplace_back(xy.x(), xy.y(), zc + q.y());
      sum += m.vertices.back();
    }
    ring_centre.push_back(sum / nr);
  }
  // tube between consecutive stations, facing away from the section centre
  const int ns = static_cast<int>(theta.size());
  for (int i = 0; i + 1 < ns; ++i) {
    const Eigen::Vector3d axis = 0.5 * (ring_centre[i] + ring_centre[i + 1]);
    for (int k = 0; k < nr; ++k) {
      const int a = i * nr + k, b = i * nr + (k + 1) % nr;
      const int c = b + nr, d = a + nr;
      const Eigen::Vector3d mid =
          0.25 * (m.vertices[a] + m.vertices[b] + m.vertices[c] + m.vertices[d]);
      add_quad(m, a, b, c, d, mid - axis);
    }
  }
  // planar end caps fanned from their centres (the section is convex)
  for (int end = 0; end < 2; ++end) {
    const int i = end == 0 ? 0 : ns - 1;
    const Eigen::Vector2d tan = profile_tangent(theta[i]) * (end == 0 ? -1.0 : 1.0);
    const Eigen::Vector3d outward(tan.x(), tan.y(), 0.0);
    const int centre = static_cast<int>(m.vertices.size());
    m.vertices.push_back(ring_centre[i]);
    for (int k = 0; k < nr; ++k)
      add_triangle(m, centre, i * nr + k, i * nr + (k + 1) % nr, outward);
  }
  return m;
}

// height of one toroidal dish centred at z = zc, or +inf outside its torus [m]
double dish_height(const GenericTkrParams& p, double x, double z, double zc) {
  const double rs = p.insert_sagittal_radius_m, rc = p.insert_coronal_radius_m;
  const double dz = z - zc;
  if (std::abs(dz) >= rc) return kInf;
  const double rho = rs - rc + std::sqrt(rc * rc - dz * dz);  // distance from the sagittal axis
  if (std::abs(x) >= rho) return kInf;
  return p.insert_thickness_m + rs - std::sqrt(rho * rho - x * x);
}

// grid coordinates from lo to hi through the breakpoints, each piece evenly spaced
std::vector<double> breakpoint_grid(const std::vector<double>& breaks, double e) {
  std::vector<double> g{breaks.front()};
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const int n = segments(breaks[k + 1] - breaks[k], e);
    for (int i = 1; i <= n; ++i) g.push_back(breaks[k] + (breaks[k + 1] - breaks[k]) * i / n);
  }
  return g;
}

}  // namespace

void check_generic_tkr(const GenericTkrParams& p) {
  const double rd = p.femur_distal_radius_m, rp = p.femur_posterior_radius_m;
  const double w = p.condyle_width_m, s = p.condyle_spacing_m;
  if (!(rd > 0.01 && rd < 0.1)) bad("femur_distal_radius_mm", mm(rd), "allowed 10..100 mm");
  if (!(rp > 0.005 && rp <= rd)) {
    bad("femur_posterior_radius_mm", mm(rp), "allowed 5 mm..femur_distal_radius_mm");
  }
  if (!(w > 0.002 && w < s)) bad("condyle_width_mm", mm(w), "allowed 2 mm..condyle_spacing_mm");
  if (!(p.femur_coronal_radius_m > 0.5 * w)) {
    bad("femur_coronal_radius_mm", mm(p.femur_coronal_radius_m),
        "it must exceed half the condyle width (" + mm(0.5 * w) + " mm)");
  }
  const double edge_drop = coronal_drop(p.femur_coronal_radius_m, 0.5 * w);
  if (!(p.femur_thickness_m > edge_drop + 1e-4 && p.femur_thickness_m < rp)) {
    bad("femur_thickness_mm", mm(p.femur_thickness_m),
        "allowed " + mm(edge_drop + 1e-4) + "..femur_posterior_radius_mm");
  }
  if (!(p.femur_transition_rad > 0.0 && p.femur_transition_rad < p.femur_posterior_extent_rad)) {
    bad("femur_transition_deg", std::to_string(p.femur_transition_rad / kDeg),
        "allowed 0..femur_posterior_extent_deg");
  }
  if (!(p.femur_anterior_extent_rad >= 0.0 && p.femur_anterior_extent_rad < 80 * kDeg)) {
    bad("femur_anterior_extent_deg", std::to_string(p.femur_anterior_extent_rad / kDeg),
        "allowed 0..80 deg");
  }
  if (!(p.femur_posterior_extent_rad <= 170 * kDeg)) {
    bad("femur_posterior_extent_deg", std::to_string(p.femur_posterior_extent_rad / kDeg),
        "allowed up to 170 deg");
  }
  const double rs = p.insert_sagittal_radius_m, rc = p.insert_coronal_radius_m;
  if (!(rc > 0.005 && rc <= rs)) {
    bad("insert_coronal_radius_mm", mm(rc), "allowed 5 mm..insert_sagittal_radius_mm");
  }
  if (!(rs < 1.0)) bad("insert_sagittal_radius_mm", mm(rs), "allowed up to 1000 mm");
  if (!(p.insert_thickness_m > 0.001)) {
    bad("insert_thickness_mm", mm(p.insert_thickness_m), "allowed above 1 mm");
  }
  if (!(p.insert_eminence_height_m > p.insert_thickness_m)) {
    bad("insert_eminence_height_mm", mm(p.insert_eminence_height_m),
        "it must exceed insert_thickness_mm (" + mm(p.insert_thickness_m) + " mm)");
  }
  if (!(p.insert_ml_width_m > s && p.insert_ap_depth_m > 0.01 &&
        0.5 * p.insert_ap_depth_m < rs - rc)) {
    bad("insert_ml_width_mm / insert_ap_depth_mm",
        mm(p.insert_ml_width_m) + " / " + mm(p.insert_ap_depth_m),
        "the width must exceed condyle_spacing_mm and half the depth must be below "
        "insert_sagittal_radius_mm - insert_coronal_radius_mm");
  }
}

TriMesh make_generic_femur(const GenericTkrParams& p, double edge_length_m) {
  check_generic_tkr(p);
  if (!(edge_length_m > 1e-5)) bad("edge_length_mm", mm(edge_length_m), "allowed above 0.01 mm");
  TriMesh femur = make_condyle(p, -0.5 * p.condyle_spacing_m, edge_length_m);
  append(femur, make_condyle(p, 0.5 * p.condyle_spacing_m, edge_length_m));
  return femur;
}

double insert_surface_height(const GenericTkrParams& p, double x_m, double z_m) {
  const double half = 0.5 * p.condyle_spacing_m;
  return std::min({p.insert_eminence_height_m, dish_height(p, x_m, z_m, -half),
                   dish_height(p, x_m, z_m, half)});
}

TriMesh make_generic_insert(const GenericTkrParams& p, double edge_length_m) {
  check_generic_tkr(p);
  const double e = edge_length_m;
  if (!(e > 1e-5)) bad("edge_length_mm", mm(e), "allowed above 0.01 mm");
  const double hx = 0.5 * p.insert_ap_depth_m, hz = 0.5 * p.insert_ml_width_m;
  const double s2 = 0.5 * p.condyle_spacing_m;
  // grid lines through x = 0 and z = -+s/2 so the dwell points are vertices
  const std::vector<double> xs = breakpoint_grid({-hx, 0.0, hx}, e);
  const std::vector<double> zs = breakpoint_grid({-hz, -s2, s2, hz}, e);
  const int nx = static_cast<int>(xs.size()), nz = static_cast<int>(zs.size());
  auto id = [nz](int layer_offset, int i, int j) { return layer_offset + i * nz + j; };

  TriMesh m;
  // top (articular) and bottom (base) grids
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < nz; ++j) {
      m.vertices.emplace_back(xs[i], insert_surface_height(p, xs[i], zs[j]), zs[j]);
    }
  }
  const int bottom = static_cast<int>(m.vertices.size());
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < nz; ++j) m.vertices.emplace_back(xs[i], 0.0, zs[j]);
  }
  for (int i = 0; i + 1 < nx; ++i) {
    for (int j = 0; j + 1 < nz; ++j) {
      add_quad(m, id(0, i, j), id(0, i + 1, j), id(0, i + 1, j + 1), id(0, i, j + 1),
               Eigen::Vector3d::UnitY());
      add_quad(m, id(bottom, i, j), id(bottom, i + 1, j), id(bottom, i + 1, j + 1),
               id(bottom, i, j + 1), -Eigen::Vector3d::UnitY());
    }
  }

  // side walls: walk the boundary loop once, with intermediate rows between base and top
  std::vector<std::pair<int, int>> loop;  // (i, j) of the boundary, counter-clockwise
  for (int j = 0; j + 1 < nz; ++j) loop.emplace_back(0, j);
  for (int i = 0; i + 1 < nx; ++i) loop.emplace_back(i, nz - 1);
  for (int j = nz - 1; j > 0; --j) loop.emplace_back(nx - 1, j);
  for (int i = nx - 1; i > 0; --i) loop.emplace_back(i, 0);
  const int rows = segments(p.insert_eminence_height_m, e);
  const int nl = static_cast<int>(loop.size());
  std::vector<std::vector<int>> column(nl);  // vertex ids bottom -> top at each loop point
  for (int k = 0; k < nl; ++k) {
    const auto [i, j] = loop[k];
    column[k].push_back(id(bottom, i, j));
    const double h = m.vertices[id(0, i, j)].y();
    for (int r = 1; r < rows; ++r) {
      column[k].push_back(static_cast<int>(m.vertices.size()));
      m.vertices.emplace_back(xs[i], h * r / rows, zs[j]);
    }
    column[k].push_back(id(0, i, j));
  }
  for (int k = 0; k < nl; ++k) {
    const int k1 = (k + 1) % nl;
    // outward: the wall's horizontal normal, from the insert centre line to the edge midpoint
    const Eigen::Vector3d a = m.vertices[column[k][0]], b = m.vertices[column[k1][0]];
    Eigen::Vector3d out = 0.5 * (a + b);
    out.y() = 0.0;
    if (std::abs(std::abs(out.x()) - hx) < 1e-12)
      out.z() = 0.0;
    else
      out.x() = 0.0;
    for (int r = 0; r < rows; ++r) {
      add_quad(m, column[k][r], column[k1][r], column[k1][r + 1], column[k][r + 1], out);
    }
  }
  return m;
}

Eigen::Vector3d dwell_point(const GenericTkrParams& p, int side) {
  const double z = (side >= 1 ? 0.5 : -0.5) * p.condyle_spacing_m;
  return {0.0, p.insert_thickness_m, z};
}

double femur_lowest_point_y(const GenericTkrParams& p, double flexion_rad) {
  if (flexion_rad <= p.femur_transition_rad) return -p.femur_distal_radius_m;
  const Eigen::Vector2d c = posterior_centre(p);
  // the posterior arc centre turned by the flexion, less the posterior radius
  return c.x() * std::sin(flexion_rad) + c.y() * std::cos(flexion_rad) - p.femur_posterior_radius_m;
}

}  // namespace kneesim::models
