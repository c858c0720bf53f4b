#include "engine/contact_line.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/data.h"
#include "engine/model.h"

namespace kneesim::engine {
namespace {

// the fraction of a triangle cut off at the corner with value `inside` (< 0) by the zero line
// through its two edges towards `b` and `c` (both >= 0)
double corner_fraction(double inside, double b, double c) {
  return inside / (inside - b) * (inside / (inside - c));
}

// area of the quad with corners x (cyclic order) [m^2]: half the cross product of its diagonals
double quad_area(const std::array<Eigen::Vector3d, 4>& x) {
  return 0.5 * (x[2] - x[0]).cross(x[3] - x[1]).norm();
}

std::array<double, 2> calc_rigid_line_area(const Model& model, const Data& data) {
  const InsertSurface& s = model.insert;
  const Eigen::Isometry3d X_FT = data.X_WF.inverse() * data.X_WT;
  std::array<double, 2> area{};
  if (data.in_contact.empty()) return area;
  // the signed distance of every articular vertex (an output frame, not a step: a few thousand
  // samples of the field)
  std::vector<double> phi(s.vertices_T.size());
  for (size_t v = 0; v < phi.size(); ++v) phi[v] = model.femur_sdf.sample(X_FT * s.vertices_T[v]);
  for (int e = 0; e < s.size(); ++e) {
    const Eigen::Vector3i& t = s.triangles[e];
    const double f = calc_triangle_negative_fraction(phi[t[0]], phi[t[1]], phi[t[2]]);
    if (f > 0.0) area[s.medial[e] ? 0 : 1] += f * s.area[e];
  }
  return area;
}

std::array<double, 2> calc_solid_line_area(const Model& model, const Data& data) {
  const solid::SurfaceContact& contact = model.insert_contact;
  const solid::SurfaceContactData& out = data.insert_contact;
  const Eigen::Isometry3d X_FT = data.X_WF.inverse() * data.X_WT;
  std::array<double, 2> area{};
  if (out.nodes_in_contact == 0) return area;
  constexpr int kSamples = 16;  // per quad edge: a 1/16 resolution of the line in a cut quad
  for (const std::array<int, 4>& face : model.insert_top_faces) {
    std::array<int, 4> idx{};
    bool touches = false, known = true;
    for (int k = 0; k < 4; ++k) {
      idx[k] = contact.index_of_node[face[k]];
      known = known && idx[k] >= 0;
      touches = touches || (idx[k] >= 0 && out.pressure[idx[k]] > 0.0);
    }
    // a quad none of whose nodes touches has no negative corner, hence no negative point
    if (!touches || !known) continue;
    std::array<double, 4> phi{};
    std::array<Eigen::Vector3d, 4> x;
    for (int k = 0; k < 4; ++k) {
      x[k] = out.position[idx[k]];  // where the node's contact was evaluated this step
      phi[k] = model.femur_sdf.sample(X_FT * x[k]);
    }
    const double f = calc_quad_negative_fraction(phi, kSamples);
    if (f <= 0.0) continue;
    double z = 0.0;
    for (int k = 0; k < 4; ++k) z += model.insert_solid.reference_positions[face[k]].z();
    area[z < 0.0 ? 0 : 1] += f * quad_area(x);  // medial: z < 0, as the nodes' sides
  }
  return area;
}

}  // namespace

double calc_triangle_negative_fraction(double a, double b, double c) {
  const int below = (a < 0.0) + (b < 0.0) + (c < 0.0);
  if (below == 0) return 0.0;
  if (below == 3) return 1.0;
  // rotate so that `a` is the corner alone on its side of the line
  if (below == 1) {
    if (b < 0.0) return corner_fraction(b, c, a);
    if (c < 0.0) return corner_fraction(c, a, b);
    return corner_fraction(a, b, c);
  }
  if (b >= 0.0) return 1.0 - corner_fraction(-b, -c, -a);
  if (c >= 0.0) return 1.0 - corner_fraction(-c, -a, -b);
  return 1.0 - corner_fraction(-a, -b, -c);
}

double calc_quad_negative_fraction(const std::array<double, 4>& phi, int samples) {
  const int below = (phi[0] < 0.0) + (phi[1] < 0.0) + (phi[2] < 0.0) + (phi[3] < 0.0);
  if (below == 0) return 0.0;
  if (below == 4) return 1.0;
  int count = 0;
  for (int i = 0; i < samples; ++i) {
    const double u = (i + 0.5) / samples;
    for (int j = 0; j < samples; ++j) {
      const double v = (j + 0.5) / samples;
      const double value = (1.0 - u) * (1.0 - v) * phi[0] + u * (1.0 - v) * phi[1] +
                           u * v * phi[2] + (1.0 - u) * v * phi[3];
      count += value < 0.0;
    }
  }
  return static_cast<double>(count) / (samples * samples);
}

std::array<double, 2> calc_contact_line_area(const Model& model, const Data& data) {
  return model.insert_solid.empty() ? calc_rigid_line_area(model, data)
                                    : calc_solid_line_area(model, data);
}

}  // namespace kneesim::engine
