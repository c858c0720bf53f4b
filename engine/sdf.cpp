#include "engine/sdf.h"

#include <algorithm>
#include <bit>
#include <limits>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <utility>

#include "engine/fcl_adapter.h"

namespace kneesim::engine {

FieldSampler SignedDistanceField::sampler() const {
  FieldSampler f;
  f.band = band;
  f.outside = static_cast<float>(band);
  f.inside = static_cast<float>(-band);
  // an empty field has no cells: every point is outside its grid
  for (int a = 0; a < 3; ++a) {
    f.limit[a] = storage ? dims[a] - 1 : 0;
    f.axis[a] = storage ? storage->axes[a].data() : nullptr;
  }
  f.brick_of = storage ? storage->brick_of.data() : nullptr;
  f.values = storage ? storage->values.data() : nullptr;
  f.clamp_bricks = storage ? storage->clamp_bricks.data() : nullptr;
  return f;
}

void make_brick_axes(const SignedDistanceField& field, SignedDistanceField::Storage& storage) {
  const int32_t brick_stride[3] = {1, field.bricks.x(), field.bricks.x() * field.bricks.y()};
  const int32_t node_stride[3] = {1, kBrickNodes, kBrickNodes * kBrickNodes};
  for (int a = 0; a < 3; ++a) {
    storage.axes[a].resize(std::max(0, field.dims[a] - 1));
    for (int i = 0; i < field.dims[a] - 1; ++i) {
      const int b = i / kBrickCells;
      storage.axes[a][i] = {b * brick_stride[a], (i - kBrickCells * b) * node_stride[a]};
    }
  }
  storage.clamp_bricks.assign(kBrickSize, static_cast<float>(field.band));
  storage.clamp_bricks.resize(2 * kBrickSize, static_cast<float>(-field.band));
}

double SignedDistanceField::sample(const Eigen::Vector3d& p_F, Eigen::Vector3d* gradient) const {
  const Eigen::Vector3d g = (p_F - origin) / spacing;
  const double phi = sample_grid(g);
  if (!gradient) return phi;
  gradient->setZero();
  // outside the grid or in a brick of clamp values: the interpolant is flat
  if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.z() >= 0.0 && g.x() < dims.x() - 1 &&
        g.y() < dims.y() - 1 && g.z() < dims.z() - 1)) {
    return phi;
  }
  const int i = static_cast<int>(g.x()), j = static_cast<int>(g.y()), k = static_cast<int>(g.z());
  const BrickAxis ax = storage->axes[0][i], ay = storage->axes[1][j], az = storage->axes[2][k];
  const int32_t brick = storage->brick_of[ax.brick + ay.brick + az.brick];
  if (brick < 0) return phi;
  const double tx = g.x() - static_cast<double>(i), ty = g.y() - static_cast<double>(j),
               tz = g.z() - static_cast<double>(k);
  constexpr long sx = 1, sy = kBrickNodes, sz = kBrickNodes * kBrickNodes;
  const float* c = storage->values.data() + static_cast<long>(brick) * kBrickSize +
                   (ax.node + ay.node + az.node);
  const double c000 = c[0], c100 = c[sx], c010 = c[sy], c110 = c[sx + sy];
  const double c001 = c[sz], c101 = c[sx + sz], c011 = c[sy + sz], c111 = c[sx + sy + sz];
  const double c00 = c000 + tx * (c100 - c000), c10 = c010 + tx * (c110 - c010);
  const double c01 = c001 + tx * (c101 - c001), c11 = c011 + tx * (c111 - c011);
  const double c0 = c00 + ty * (c10 - c00), c1 = c01 + ty * (c11 - c01);
  const double dx0 = (c100 - c000) + ty * ((c110 - c010) - (c100 - c000));
  const double dx1 = (c101 - c001) + ty * ((c111 - c011) - (c101 - c001));
  const double dy0 = c10 - c00, dy1 = c11 - c01;
  *gradient =
      Eigen::Vector3d(dx0 + tz * (dx1 - dx0), dy0 + tz * (dy1 - dy0), c1 - c0) / spacing;
  return phi;
}

int SignedDistanceField::stored_bricks() const {
  return storage ? static_cast<int>(storage->values.size() / kBrickSize) : 0;
}

size_t SignedDistanceField::bytes() const {
  return storage ? storage->values.size() * sizeof(float) +
                       storage->brick_of.size() * sizeof(int32_t) +
                       storage->clamp_bricks.size() * sizeof(float) +
                       (storage->axes[0].size() + storage->axes[1].size() +
                        storage->axes[2].size()) * sizeof(BrickAxis)
                 : 0;
}

float SignedDistanceField::node(int i, int j, int k) const {
  const int bi = std::min(i / kBrickCells, bricks.x() - 1);
  const int bj = std::min(j / kBrickCells, bricks.y() - 1);
  const int bk = std::min(k / kBrickCells, bricks.z() - 1);
  const int32_t brick = storage->brick_of[bi + bricks.x() * (bj + bricks.y() * bk)];
  if (brick < 0) return static_cast<float>(brick == kBrickOutside ? band : -band);
  return storage->values[static_cast<long>(brick) * kBrickSize + (i - kBrickCells * bi) +
                kBrickNodes * ((j - kBrickCells * bj) + kBrickNodes * (k - kBrickCells * bk))];
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

// sign of (p - q) against the pseudonormal of the feature of triangle f supporting q
// (support bit i = vertex i of the triangle: 7 the face, two bits an edge, one bit a vertex)
double find_sign(const Pseudonormals& n, unsigned int support, const Eigen::Vector3i& tri, int f,
                 const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  Eigen::Vector3d normal = n.face[f];
  const int bits = std::popcount(support & 7u);
  if (bits == 1) {
    normal = n.vertex[tri[std::countr_zero(support & 7u)]];
  } else if (bits == 2) {
    int ends[2], k = 0;
    for (int i = 0; i < 3; ++i)
      if (support & (1u << i)) ends[k++] = tri[i];
    const auto key = std::minmax(ends[0], ends[1]);
    if (auto it = n.edge.find({key.first, key.second}); it != n.edge.end()) normal = it->second;
  }
  return (p - q).dot(normal) >= 0.0 ? 1.0 : -1.0;
}

// cuts a dense x-fastest node grid into bricks of 8^3 nodes sharing their boundary nodes;
// bricks whose nodes all hold the same clamp value are not stored (nodes past the grid's last
// node hold +band and are never interpolated)
void make_bricks(const std::vector<float>& phi, SignedDistanceField& sdf) {
  const long nx = sdf.dims.x(), ny = sdf.dims.y(), nz = sdf.dims.z();
  for (int a = 0; a < 3; ++a) {
    sdf.bricks[a] = std::max(1, (sdf.dims[a] - 1 + kBrickCells - 1) / kBrickCells);
  }
  const float outside = static_cast<float>(sdf.band), inside = static_cast<float>(-sdf.band);
  auto storage = std::make_shared<SignedDistanceField::Storage>();
  storage->brick_of.assign(static_cast<size_t>(sdf.bricks.prod()), kBrickOutside);
  std::vector<float> brick(kBrickSize);
  for (int bk = 0; bk < sdf.bricks.z(); ++bk)
    for (int bj = 0; bj < sdf.bricks.y(); ++bj)
      for (int bi = 0; bi < sdf.bricks.x(); ++bi) {
        bool all_outside = true, all_inside = true;
        for (int k = 0; k < kBrickNodes; ++k)
          for (int j = 0; j < kBrickNodes; ++j)
            for (int i = 0; i < kBrickNodes; ++i) {
              const long gi = kBrickCells * bi + i, gj = kBrickCells * bj + j,
                         gk = kBrickCells * bk + k;
              const float v = gi < nx && gj < ny && gk < nz ? phi[gi + nx * (gj + ny * gk)]
                                                            : outside;
              brick[i + kBrickNodes * (j + kBrickNodes * k)] = v;
              all_outside &= v == outside;
              all_inside &= v == inside;
            }
        int32_t& entry = storage->brick_of[bi + sdf.bricks.x() * (bj + sdf.bricks.y() * bk)];
        if (all_outside) continue;
        if (all_inside) {
          entry = kBrickInside;
          continue;
        }
        entry = static_cast<int32_t>(storage->values.size() / kBrickSize);
        storage->values.insert(storage->values.end(), brick.begin(), brick.end());
      }
  make_brick_axes(sdf, *storage);
  sdf.storage = std::move(storage);
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

  // exact distances near the surface: every triangle visits the nodes of its bounding box
  // grown by the band and keeps, per node, the nearest triangle (ties: lowest index). Threads
  // own slabs of z, so each node sees the triangles in index order whatever the thread count.
  std::vector<float> best(total, std::numeric_limits<float>::infinity());
  std::vector<int> nearest(total, -1);
  const int nt = static_cast<int>(triangles.size());
#pragma omp parallel
  {
    int nthreads = 1, tid = 0;
#ifdef _OPENMP
    nthreads = omp_get_num_threads();
    tid = omp_get_thread_num();
#endif
    const long z_lo = nz * tid / nthreads, z_hi = nz * (tid + 1) / nthreads;
    for (int f = 0; f < nt; ++f) {
      const auto& t = triangles[f];
      const Eigen::Vector3d& a = vertices[t[0]];
      const Eigen::Vector3d& b = vertices[t[1]];
      const Eigen::Vector3d& c = vertices[t[2]];
      const Eigen::Vector3d glo =
          (a.cwiseMin(b).cwiseMin(c) - Eigen::Vector3d::Constant(band) - sdf.origin) / spacing;
      const Eigen::Vector3d ghi =
          (a.cwiseMax(b).cwiseMax(c) + Eigen::Vector3d::Constant(band) - sdf.origin) / spacing;
      const long i0 = std::max(0L, static_cast<long>(std::ceil(glo.x())));
      const long j0 = std::max(0L, static_cast<long>(std::ceil(glo.y())));
      const long k0 = std::max(z_lo, static_cast<long>(std::ceil(glo.z())));
      const long i1 = std::min(nx - 1, static_cast<long>(std::floor(ghi.x())));
      const long j1 = std::min(ny - 1, static_cast<long>(std::floor(ghi.y())));
      const long k1 = std::min(z_hi - 1, static_cast<long>(std::floor(ghi.z())));
      // the distance to the triangle's plane bounds the distance to the triangle from below:
      // nodes off the plane by more than the band or than their best so far are skipped
      Eigen::Vector3d normal = (b - a).cross(c - a);
      const double normal_len = normal.norm();
      if (normal_len > 0.0) normal /= normal_len;
      // and so does the distance to the triangle's bounding sphere
      const Eigen::Vector3d centre = (a + b + c) / 3.0;
      const double radius = std::sqrt(std::max(
          {(a - centre).squaredNorm(), (b - centre).squaredNorm(), (c - centre).squaredNorm()}));
      for (long k = k0; k <= k1; ++k)
        for (long j = j0; j <= j1; ++j)
          for (long i = i0; i <= i1; ++i) {
            const long n = index(i, j, k);
            const Eigen::Vector3d p = sdf.origin + spacing * Eigen::Vector3d(i, j, k);
            const double plane = normal.dot(p - a);
            const double limit2 = std::min(static_cast<double>(best[n]), band * band);
            if (plane * plane >= limit2) continue;
            const double to_centre = (p - centre).norm() - radius;
            if (to_centre > 0.0 && to_centre * to_centre >= limit2) continue;
            const double d2 = project_on_triangle(a, b, c, p).squared_distance;
            if (d2 < best[n]) {
              best[n] = static_cast<float>(d2);
              nearest[n] = f;
            }
          }
    }
  }
  // signs from the pseudonormal of the nearest feature; nodes beyond the band wait for the fill
  const Pseudonormals normals = make_pseudonormals(vertices, triangles);
  std::vector<float> phi(total, static_cast<float>(band));
  std::vector<uint8_t> in_band(total, 0);
  const float band2 = static_cast<float>(band * band);
#pragma omp parallel for schedule(static)
  for (long n = 0; n < total; ++n) {
    if (nearest[n] < 0 || best[n] > band2) continue;
    in_band[n] = 1;
    const long i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
    const Eigen::Vector3d p = sdf.origin + spacing * Eigen::Vector3d(i, j, k);
    const auto& t = triangles[nearest[n]];
    const TriangleProjection proj =
        project_on_triangle(vertices[t[0]], vertices[t[1]], vertices[t[2]], p);
    const Eigen::Vector3d q = proj.weight[0] * vertices[t[0]] + proj.weight[1] * vertices[t[1]] +
                              proj.weight[2] * vertices[t[2]];
    const double s = find_sign(normals, proj.support, t, nearest[n], p, q);
    phi[n] = static_cast<float>(s * std::sqrt(static_cast<double>(best[n])));
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
    if (!in_band[n] && !outside[n]) phi[n] = static_cast<float>(-band);
  make_bricks(phi, sdf);
  return sdf;
}

}  // namespace kneesim::engine
