#include "engine/sdf.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <utility>

#include "engine/fcl_adapter.h"

namespace kneesim::engine {

double SignedDistanceField::sample(const Eigen::Vector3d& p_F, Eigen::Vector3d* gradient) const {
  const Eigen::Vector3d g = (p_F - origin) / spacing;
  const double fx = std::floor(g.x()), fy = std::floor(g.y()), fz = std::floor(g.z());
  const int i = static_cast<int>(fx), j = static_cast<int>(fy), k = static_cast<int>(fz);
  if (i < 0 || j < 0 || k < 0 || i >= dims.x() - 1 || j >= dims.y() - 1 || k >= dims.z() - 1) {
    if (gradient) gradient->setZero();
    return band;
  }
  const double tx = g.x() - fx, ty = g.y() - fy, tz = g.z() - fz;
  const long sx = 1, sy = dims.x(), sz = static_cast<long>(dims.x()) * dims.y();
  const long base = i + sy * j + sz * k;
  const double c000 = phi[base], c100 = phi[base + sx];
  const double c010 = phi[base + sy], c110 = phi[base + sx + sy];
  const double c001 = phi[base + sz], c101 = phi[base + sx + sz];
  const double c011 = phi[base + sy + sz], c111 = phi[base + sx + sy + sz];
  // interpolate along x, then y, then z
  const double c00 = c000 + tx * (c100 - c000), c10 = c010 + tx * (c110 - c010);
  const double c01 = c001 + tx * (c101 - c001), c11 = c011 + tx * (c111 - c011);
  const double c0 = c00 + ty * (c10 - c00), c1 = c01 + ty * (c11 - c01);
  if (gradient) {
    const double dx0 = (c100 - c000) + ty * ((c110 - c010) - (c100 - c000));
    const double dx1 = (c101 - c001) + ty * ((c111 - c011) - (c101 - c001));
    const double dy0 = c10 - c00, dy1 = c11 - c01;
    *gradient = Eigen::Vector3d(dx0 + tz * (dx1 - dx0), dy0 + tz * (dy1 - dy0), c1 - c0) /
                spacing;
  }
  return c0 + tz * (c1 - c0);
}

namespace {

// angle-weighted pseudonormals of faces, edges and vertices, for the sign of the distance
struct Pseudonormals {
  std::vector<Eigen::Vector3d> face, vertex;
  std::map<std::pair<int, int>, Eigen::Vector3d> edge;
};

Pseudonormals make_pseudonormals(const std::vector<Eigen::Vector3d>& v,
                                 const std::vector<Eigen::Vector3i>& t) {
  Pseudonormals n;
  n.face.resize(t.size());
  n.vertex.assign(v.size(), Eigen::Vector3d::Zero());
  for (size_t f = 0; f < t.size(); ++f) {
    const Eigen::Vector3d e1 = v[t[f][1]] - v[t[f][0]], e2 = v[t[f][2]] - v[t[f][0]];
    const Eigen::Vector3d nf = e1.cross(e2);
    const double len = nf.norm();
    n.face[f] = len > 0 ? Eigen::Vector3d(nf / len) : Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) {
      const int a = t[f][c], b = t[f][(c + 1) % 3], d = t[f][(c + 2) % 3];
      const Eigen::Vector3d u = (v[b] - v[a]).normalized(), w = (v[d] - v[a]).normalized();
      const double angle = std::acos(std::clamp(u.dot(w), -1.0, 1.0));
      n.vertex[a] += angle * n.face[f];
      const auto key = std::minmax(a, b);
      auto it = n.edge.find({key.first, key.second});
      if (it == n.edge.end()) {
        n.edge.emplace(std::make_pair(key.first, key.second), n.face[f]);
      } else {
        it->second += n.face[f];
      }
    }
  }
  return n;
}

// sign of (p - q) against the pseudonormal of the feature of triangle f nearest to q
double find_sign(const Pseudonormals& n, const std::vector<Eigen::Vector3d>& v,
                 const Eigen::Vector3i& tri, int f, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& q) {
  // barycentric coordinates of q in the triangle
  const Eigen::Vector3d a = v[tri[0]], b = v[tri[1]], c = v[tri[2]];
  const Eigen::Vector3d e0 = b - a, e1 = c - a, d = q - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  double bb = 0, bc = 0;
  if (den > 0) {
    bb = (d11 * d20 - d01 * d21) / den;
    bc = (d00 * d21 - d01 * d20) / den;
  }
  const double ba = 1.0 - bb - bc;
  const double bary[3] = {ba, bb, bc};
  constexpr double kTol = 1e-6;
  int zeros = 0, nonzero_mask = 0;
  for (int i = 0; i < 3; ++i) {
    if (bary[i] < kTol) {
      ++zeros;
    } else {
      nonzero_mask |= 1 << i;
    }
  }
  Eigen::Vector3d normal = n.face[f];
  if (zeros == 2) {
    const int i = nonzero_mask == 1 ? 0 : (nonzero_mask == 2 ? 1 : 2);
    normal = n.vertex[tri[i]];
  } else if (zeros == 1) {
    int ends[2], k = 0;
    for (int i = 0; i < 3; ++i) {
      if (nonzero_mask & (1 << i)) ends[k++] = tri[i];
    }
    const auto key = std::minmax(ends[0], ends[1]);
    auto it = n.edge.find({key.first, key.second});
    if (it != n.edge.end()) normal = it->second;
  }
  return (p - q).dot(normal) >= 0.0 ? 1.0 : -1.0;
}

}  // namespace

SignedDistanceField make_signed_distance_field(const std::vector<Eigen::Vector3d>& vertices,
                                               const std::vector<Eigen::Vector3i>& triangles,
                                               double spacing, double band) {
  if (vertices.empty() || triangles.empty()) {
    throw std::invalid_argument("signed distance field of an empty mesh");
  }
  SignedDistanceField sdf;
  sdf.spacing = spacing;
  sdf.band = band;
  Eigen::Vector3d lo = vertices[0], hi = vertices[0];
  for (const auto& p : vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double pad = band + 2.0 * spacing;
  sdf.origin = lo - Eigen::Vector3d::Constant(pad);
  const Eigen::Vector3d extent = hi - lo + Eigen::Vector3d::Constant(2.0 * pad);
  for (int a = 0; a < 3; ++a) sdf.dims[a] = static_cast<int>(std::ceil(extent[a] / spacing)) + 1;
  const long nx = sdf.dims.x(), ny = sdf.dims.y(), nz = sdf.dims.z();
  const long total = nx * ny * nz;
  auto index = [&](long i, long j, long k) { return i + nx * (j + ny * k); };

  // mark the nodes within the band of some triangle's bounding box
  std::vector<uint8_t> in_band(total, 0);
  for (const auto& t : triangles) {
    Eigen::Vector3d tlo = vertices[t[0]].cwiseMin(vertices[t[1]]).cwiseMin(vertices[t[2]]);
    Eigen::Vector3d thi = vertices[t[0]].cwiseMax(vertices[t[1]]).cwiseMax(vertices[t[2]]);
    tlo -= Eigen::Vector3d::Constant(band);
    thi += Eigen::Vector3d::Constant(band);
    const Eigen::Vector3d glo = (tlo - sdf.origin) / spacing, ghi = (thi - sdf.origin) / spacing;
    const int i0 = std::max(0, static_cast<int>(std::floor(glo.x())));
    const int j0 = std::max(0, static_cast<int>(std::floor(glo.y())));
    const int k0 = std::max(0, static_cast<int>(std::floor(glo.z())));
    const int i1 = std::min<int>(nx - 1, static_cast<int>(std::ceil(ghi.x())));
    const int j1 = std::min<int>(ny - 1, static_cast<int>(std::ceil(ghi.y())));
    const int k1 = std::min<int>(nz - 1, static_cast<int>(std::ceil(ghi.z())));
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) in_band[index(i, j, k)] = 1;
  }
  std::vector<long> band_nodes;
  for (long n = 0; n < total; ++n)
    if (in_band[n]) band_nodes.push_back(n);

  // exact signed distance at band nodes
  const MeshBvh bvh(vertices, triangles);
  const Pseudonormals normals = make_pseudonormals(vertices, triangles);
  sdf.phi.assign(total, static_cast<float>(band));
  const long count = static_cast<long>(band_nodes.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long b = 0; b < count; ++b) {
    const long n = band_nodes[b];
    const long i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
    const Eigen::Vector3d p = sdf.origin + spacing * Eigen::Vector3d(i, j, k);
    Eigen::Vector3d q;
    int f = 0;
    const double dist = bvh.closest_point(p, q, f);
    const double s = find_sign(normals, vertices, triangles[f], f, p, q);
    sdf.phi[n] = static_cast<float>(s * std::min(dist, band));
  }

  // flood fill the non-band nodes from the grid boundary: reached = outside, rest = inside
  std::vector<uint8_t> outside(total, 0);
  std::vector<long> stack;
  for (long k = 0; k < nz; ++k)
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        const bool boundary =
            i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1;
        const long n = index(i, j, k);
        if (boundary && !in_band[n]) {
          outside[n] = 1;
          stack.push_back(n);
        }
      }
  while (!stack.empty()) {
    const long n = stack.back();
    stack.pop_back();
    const long i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
    const long nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k},
                           {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
    for (const auto& c : nb) {
      if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= nx || c[1] >= ny || c[2] >= nz) continue;
      const long m = index(c[0], c[1], c[2]);
      if (in_band[m] || outside[m]) continue;
      outside[m] = 1;
      stack.push_back(m);
    }
  }
  for (long n = 0; n < total; ++n)
    if (!in_band[n] && !outside[n]) sdf.phi[n] = static_cast<float>(-band);
  return sdf;
}

}  // namespace kneesim::engine
