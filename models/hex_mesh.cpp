#include "models/hex_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "engine/errors.h"

namespace kneesim::models {
namespace {

std::string mm(double v_m) {
  std::ostringstream s;
  s << v_m * 1e3;
  return s.str();
}

// the x-z projections of the insert's triangles bucketed on a regular grid, for vertical rays
class TopSurfaceRays {
 public:
  TopSurfaceRays(const TriMesh& mesh, Eigen::Vector2d lo, Eigen::Vector2d hi, double cell)
      : mesh_(mesh), lo_(lo), cell_(cell) {
    nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)));
    nz_ = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)));
    buckets_.resize(static_cast<size_t>(nx_) * nz_);
    for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
      Eigen::Vector2d a(INFINITY, INFINITY), b(-INFINITY, -INFINITY);
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d& v = mesh.vertices[mesh.triangles[t][c]];
        a = a.cwiseMin(Eigen::Vector2d(v.x(), v.z()));
        b = b.cwiseMax(Eigen::Vector2d(v.x(), v.z()));
      }
      for (int k = bucket(a.y(), lo_.y(), nz_); k <= bucket(b.y(), lo_.y(), nz_); ++k)
        for (int i = bucket(a.x(), lo_.x(), nx_); i <= bucket(b.x(), lo_.x(), nx_); ++i)
          buckets_[static_cast<size_t>(k) * nx_ + i].push_back(t);
    }
  }

  // the highest y where the vertical line through (x, z) meets the mesh; -inf when it misses
  double top(double x, double z) const {
    double best = -INFINITY;
    const int i = bucket(x, lo_.x(), nx_), k = bucket(z, lo_.y(), nz_);
    for (int t : buckets_[static_cast<size_t>(k) * nx_ + i]) {
      const Eigen::Vector3d& p0 = mesh_.vertices[mesh_.triangles[t][0]];
      const Eigen::Vector3d& p1 = mesh_.vertices[mesh_.triangles[t][1]];
      const Eigen::Vector3d& p2 = mesh_.vertices[mesh_.triangles[t][2]];
      // barycentric coordinates in the x-z projection
      const double d = (p1.x() - p0.x()) * (p2.z() - p0.z()) - (p2.x() - p0.x()) * (p1.z() - p0.z());
      if (std::abs(d) < 1e-18) continue;  // a vertical triangle: the ray grazes it
      const double u = ((x - p0.x()) * (p2.z() - p0.z()) - (p2.x() - p0.x()) * (z - p0.z())) / d;
      const double v = ((p1.x() - p0.x()) * (z - p0.z()) - (x - p0.x()) * (p1.z() - p0.z())) / d;
      if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
      best = std::max(best, p0.y() + u * (p1.y() - p0.y()) + v * (p2.y() - p0.y()));
    }
    return best;
  }

 private:
  int bucket(double v, double lo, int n) const {
    return std::clamp(static_cast<int>(std::floor((v - lo) / cell_)), 0, n - 1);
  }
  const TriMesh& mesh_;
  Eigen::Vector2d lo_;
  double cell_;
  int nx_ = 1, nz_ = 1;
  std::vector<std::vector<int>> buckets_;
};

// fractions of the column height at each layer boundary, 0 at the base to 1 at the top, the
// layer thicknesses geometric with top / bottom = grading
std::vector<double> layer_fractions(int layers, double grading) {
  const double r = layers > 1 ? std::pow(grading, 1.0 / (layers - 1)) : 1.0;
  std::vector<double> s(layers + 1, 0.0);
  double t = 1.0;
  for (int l = 0; l < layers; ++l, t *= r) s[l + 1] = s[l] + t;
  for (double& v : s) v /= s[layers];
  s[layers] = 1.0;
  return s;
}

}  // namespace

HexMesh make_graded_box_hex_mesh(const std::vector<double>& xs, const std::vector<double>& ys,
                                 const std::vector<double>& zs) {
  HexMesh m;
  m.nx = static_cast<int>(xs.size()) - 1;
  m.ny = static_cast<int>(ys.size()) - 1;
  m.nz = static_cast<int>(zs.size()) - 1;
  const int nx = m.nx, ny = m.ny, nz = m.nz;
  m.nodes.reserve(static_cast<size_t>(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.nodes.emplace_back(xs[i], ys[j], zs[k]);
  m.elements.reserve(static_cast<size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.elements.push_back({m.node(i, j, k), m.node(i + 1, j, k), m.node(i + 1, j + 1, k),
                              m.node(i, j + 1, k), m.node(i, j, k + 1), m.node(i + 1, j, k + 1),
                              m.node(i + 1, j + 1, k + 1), m.node(i, j + 1, k + 1)});
  // top quads counter-clockwise seen from +y: (i,k) -> (i,k+1) -> (i+1,k+1) -> (i+1,k)
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      m.top_faces.push_back({m.node(i, ny, k), m.node(i, ny, k + 1), m.node(i + 1, ny, k + 1),
                             m.node(i + 1, ny, k)});
      m.top_face_element.push_back(i + nx * ((ny - 1) + ny * k));
    }
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) m.base_nodes.push_back(m.node(i, 0, k));
  return m;
}

HexMesh make_box_hex_mesh(int nx, int ny, int nz, const Eigen::Vector3d& size,
                          const Eigen::Vector3d& origin) {
  auto lines = [](int n, double lo, double extent) {
    std::vector<double> v(n + 1);
    for (int i = 0; i <= n; ++i) v[i] = lo + extent * i / n;
    return v;
  };
  return make_graded_box_hex_mesh(lines(nx, origin.x(), size.x()), lines(ny, origin.y(), size.y()),
                                  lines(nz, origin.z(), size.z()));
}

std::vector<double> make_graded_lines(double a, double b, double centre, double half_width,
                                      double fine, double ratio) {
  // one side: from the fine zone's edge outwards to `end`, growing spacing
  auto side = [&](double start, double end) {
    std::vector<double> v;
    const double dir = end > start ? 1.0 : -1.0;
    double x = start, h = fine;
    while (dir * (end - x) > 1e-12) {
      h *= ratio;
      // stop when the next step would leave less than half a step to the end
      if (dir * (end - (x + dir * h)) < 0.5 * h) {
        v.push_back(end);
        break;
      }
      x += dir * h;
      v.push_back(x);
    }
    return v;
  };
  const double lo = std::max(a, centre - half_width), hi = std::min(b, centre + half_width);
  const int n = std::max(1, static_cast<int>(std::lround((hi - lo) / fine)));
  std::vector<double> left = side(lo, a);
  std::vector<double> lines(left.rbegin(), left.rend());
  for (int i = 0; i <= n; ++i) lines.push_back(lo + (hi - lo) * i / n);
  for (double v : side(hi, b)) lines.push_back(v);
  return lines;
}

std::vector<double> make_refined_lines(double a, double b, const std::vector<Interval>& zone,
                                       double fine, double coarse, double growth) {
  if (!(b > a) || !(fine > 0.0) || !(coarse >= fine) || !(growth >= 1.0)) {
    throw std::invalid_argument("make_refined_lines: needs a < b, 0 < fine <= coarse, growth >= 1");
  }
  if (zone.empty() || coarse == fine) {
    // the uniform grid (i * dx from a, as the insert mesher always placed it)
    const int n = std::max(1, static_cast<int>(std::lround((b - a) / coarse)));
    const double d = (b - a) / n;
    std::vector<double> lines(n + 1);
    for (int i = 0; i <= n; ++i) lines[i] = a + i * d;
    return lines;
  }
  // the wanted spacing at v: fine inside the zone, growing with the distance from it
  auto spacing = [&](double v) {
    double d = INFINITY;
    for (const Interval& z : zone) d = std::min(d, std::max({0.0, z.lo - v, v - z.hi}));
    return std::isfinite(d) ? std::min(coarse, fine + (growth - 1.0) * d) : coarse;
  };
  // cumulative cell count N(v) = int_a^v dv / s(v) on a sampling grid of a tenth of `fine`
  // (trapezoids; s is piecewise linear, so this is accurate to a fraction of a cell)
  const int samples = std::max(2, static_cast<int>(std::ceil((b - a) / (0.1 * fine))) + 1);
  std::vector<double> v(samples), count(samples, 0.0);
  for (int i = 0; i < samples; ++i) v[i] = a + (b - a) * i / (samples - 1);
  for (int i = 1; i < samples; ++i) {
    count[i] = count[i - 1] + 0.5 * (v[i] - v[i - 1]) * (1.0 / spacing(v[i - 1]) + 1.0 / spacing(v[i]));
  }
  const int cells = std::max(1, static_cast<int>(std::lround(count.back())));
  std::vector<double> lines(cells + 1);
  lines[0] = a;
  lines[cells] = b;
  int j = 1;
  for (int c = 1; c < cells; ++c) {
    const double target = count.back() * c / cells;
    while (count[j] < target) ++j;
    const double t = (target - count[j - 1]) / (count[j] - count[j - 1]);
    lines[c] = v[j - 1] + t * (v[j] - v[j - 1]);
  }
  return lines;
}

HexMesh make_insert_hex_mesh(const TriMesh& insert, double base_y, const InsertMeshOptions& o) {
  if (!(o.element_size > 0.0)) {
    throw InputError("insert hex mesh: element size " + mm(o.element_size) +
                     " mm is out of range (must be > 0)");
  }
  if (o.layers < 1) {
    throw InputError("insert hex mesh: layers " + std::to_string(o.layers) +
                     " is out of range (must be >= 1)");
  }
  if (!(o.grading > 0.0)) {
    throw InputError("insert hex mesh: grading " + std::to_string(o.grading) +
                     " is out of range (top/bottom layer ratio, must be > 0)");
  }
  if (insert.triangles.empty()) throw InputError("insert hex mesh: the insert mesh is empty");
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& v : insert.vertices) {
    lo = lo.cwiseMin(Eigen::Vector2d(v.x(), v.z()));
    hi = hi.cwiseMax(Eigen::Vector2d(v.x(), v.z()));
  }
  // the grid spans the footprint's bounding box, its outer lines pulled in by a hair so that
  // rays along the vertical side walls hit the top rather than graze the wall
  const double inset = 1e-7 * std::max(hi.x() - lo.x(), hi.y() - lo.y());
  lo.array() += inset;
  hi.array() -= inset;
  const double size_z = o.element_size_z > 0.0 ? o.element_size_z : o.element_size;
  const bool refined = o.outer_element_size > std::max(o.element_size, size_z) &&
                       !o.refine_x.empty() && !o.refine_z.empty();
  if (refined && !(o.growth >= 1.0)) {
    throw InputError("insert hex mesh: growth " + std::to_string(o.growth) +
                     " is out of range (must be >= 1)");
  }
  const double outer = o.outer_element_size;
  const std::vector<double> xs = make_refined_lines(lo.x(), hi.x(), refined ? o.refine_x : std::vector<Interval>{},
                                                    o.element_size, refined ? outer : o.element_size, o.growth);
  const std::vector<double> zs = make_refined_lines(lo.y(), hi.y(), refined ? o.refine_z : std::vector<Interval>{},
                                                    size_z, refined ? outer : size_z, o.growth);
  const int nx = static_cast<int>(xs.size()) - 1, nz = static_cast<int>(zs.size()) - 1;
  const TopSurfaceRays rays(insert, lo, hi, std::max(std::min(o.element_size, size_z), 2e-4));

  // heights at the grid points
  std::vector<double> top(static_cast<size_t>(nx + 1) * (nz + 1));
  auto at = [nx](int i, int k) { return static_cast<size_t>(k) * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) top[at(i, k)] = rays.top(xs[i], zs[k]);

  // cells with all four corners on the insert
  std::vector<unsigned char> cell(static_cast<size_t>(nx) * nz, 0);
  std::vector<int> column(top.size(), -1);  // first node id of each used column
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const size_t c[4] = {at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1)};
      bool inside = true;
      for (size_t p : c) inside &= std::isfinite(top[p]);
      if (!inside) continue;
      cell[static_cast<size_t>(k) * nx + i] = 1;
      for (size_t p : c) column[p] = 0;
    }

  HexMesh m;
  const std::vector<double> s = layer_fractions(o.layers, o.grading);
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) {
      const size_t p = at(i, k);
      if (column[p] < 0) continue;
      const double h = top[p] - base_y;
      if (!(h > 0.0)) {
        throw InputError("insert hex mesh: the insert's top at x = " + mm(xs[i]) +
                         " mm, z = " + mm(zs[k]) + " mm is " + mm(h) +
                         " mm above the base plane (layer thickness must be > 0)");
      }
      column[p] = static_cast<int>(m.nodes.size());
      for (int j = 0; j <= o.layers; ++j) {
        m.nodes.emplace_back(xs[i], base_y + s[j] * h, zs[k]);
      }
      m.base_nodes.push_back(column[p]);
    }
  if (m.nodes.empty()) {
    throw InputError("insert hex mesh: element size " + mm(o.element_size) +
                     " mm leaves no grid cell inside the insert's footprint (must be smaller)");
  }
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      if (!cell[static_cast<size_t>(k) * nx + i]) continue;
      // column bases of the cell's corners, in the box mesher's (x, z) order
      const int c00 = column[at(i, k)], c10 = column[at(i + 1, k)];
      const int c11 = column[at(i + 1, k + 1)], c01 = column[at(i, k + 1)];
      for (int j = 0; j < o.layers; ++j) {
        m.elements.push_back({c00 + j, c10 + j, c10 + j + 1, c00 + j + 1, c01 + j, c11 + j,
                              c11 + j + 1, c01 + j + 1});
      }
      m.top_faces.push_back({c00 + o.layers, c01 + o.layers, c11 + o.layers, c10 + o.layers});
      m.top_face_element.push_back(static_cast<int>(m.elements.size()) - 1);
    }
  return m;
}

}  // namespace kneesim::models
