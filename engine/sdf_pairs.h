// Two points' field samples at once, for the contact kernel's batched distance pass
// (engine/contact.cpp; CHANGELOG.md, performance round 4): the affine map of two insert points into a
// field's grid and their trilinear samples with one SSE2 register per quantity, lane l holding
// point l. Each lane performs, in the same order, the operations of the scalar path it
// replaces - Eigen's A p + b of GridMap (rows x and y as ((a0 x + a1 y) + a2 z) + b, row z as
// (a0 x + (a1 y + a2 z)) + b, Eigen's unrolled sum of three products) followed by
// FieldSampler::sample_grid - and the build has no FMA contraction (-ffp-contract=off, baseline
// x86-64), so each result is the scalar one, bit for bit (tests/engine/sdf_test.cpp compares
// them over points inside, outside and across the grid's edges). A pair with a point outside
// the grid's cells falls back to the scalar sample for both.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "engine/sdf.h"

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace kneesim::engine {

// the affine map g = A p + b into a field's grid coordinates [nodes], one coefficient per
// register in both lanes
struct PairGridMap {
#ifdef __SSE2__
  __m128d a[3][3], b[3];
#endif
  Eigen::Matrix3d A;
  Eigen::Vector3d b_v;
  PairGridMap() = default;
  PairGridMap(const Eigen::Matrix3d& A_, const Eigen::Vector3d& b_) : A(A_), b_v(b_) {
#ifdef __SSE2__
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) a[r][c] = _mm_set1_pd(A(r, c));
      b[r] = _mm_set1_pd(b_v[r]);
    }
#endif
  }
  // the scalar map, as GridMap (engine/contact.cpp) computes it
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const { return A * p + b_v; }
};

// the field at the grid coordinates of points p and q: out[0] at map(p), out[1] at map(q) [m],
// equal bit for bit to f.sample_grid(map(p)) and f.sample_grid(map(q))
[[gnu::always_inline]] inline void sample_pair(const FieldSampler& f, const PairGridMap& map,
                                               const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                               double out[2]) {
#ifdef __SSE2__
  const __m128d p_xy = _mm_loadu_pd(p.data()), q_xy = _mm_loadu_pd(q.data());
  const __m128d x = _mm_unpacklo_pd(p_xy, q_xy), y = _mm_unpackhi_pd(p_xy, q_xy);
  const __m128d z = _mm_loadh_pd(_mm_load_sd(p.data() + 2), q.data() + 2);
  const auto row_xy = [&](int r) {  // ((a0 x + a1 y) + a2 z) + b
    return _mm_add_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(map.a[r][0], x), _mm_mul_pd(map.a[r][1], y)),
                                 _mm_mul_pd(map.a[r][2], z)),
                      map.b[r]);
  };
  const __m128d gx = row_xy(0), gy = row_xy(1);
  const __m128d gz = _mm_add_pd(  // (a0 x + (a1 y + a2 z)) + b
      _mm_add_pd(_mm_mul_pd(map.a[2][0], x),
                 _mm_add_pd(_mm_mul_pd(map.a[2][1], y), _mm_mul_pd(map.a[2][2], z))),
      map.b[2]);
  // inside the grid's cells in every axis (NaN fails the comparisons, as in sample_grid)
  const __m128d zero = _mm_setzero_pd();
  const __m128d in = _mm_and_pd(
      _mm_and_pd(_mm_and_pd(_mm_cmpge_pd(gx, zero), _mm_cmplt_pd(gx, _mm_set1_pd(f.limit[0]))),
                 _mm_and_pd(_mm_cmpge_pd(gy, zero), _mm_cmplt_pd(gy, _mm_set1_pd(f.limit[1])))),
      _mm_and_pd(_mm_cmpge_pd(gz, zero), _mm_cmplt_pd(gz, _mm_set1_pd(f.limit[2]))));
  if (_mm_movemask_pd(in) != 3) {
    alignas(16) double lx[2], ly[2], lz[2];
    _mm_store_pd(lx, gx);
    _mm_store_pd(ly, gy);
    _mm_store_pd(lz, gz);
    out[0] = f.sample_grid(Eigen::Vector3d(lx[0], ly[0], lz[0]));
    out[1] = f.sample_grid(Eigen::Vector3d(lx[1], ly[1], lz[1]));
    return;
  }
  // truncation is the floor inside the grid
  const __m128i I = _mm_cvttpd_epi32(gx), J = _mm_cvttpd_epi32(gy), K = _mm_cvttpd_epi32(gz);
  const int i0 = _mm_cvtsi128_si32(I), i1 = _mm_cvtsi128_si32(_mm_shuffle_epi32(I, 1));
  const int j0 = _mm_cvtsi128_si32(J), j1 = _mm_cvtsi128_si32(_mm_shuffle_epi32(J, 1));
  const int k0 = _mm_cvtsi128_si32(K), k1 = _mm_cvtsi128_si32(_mm_shuffle_epi32(K, 1));
  const auto corner = [&f](int i, int j, int k) {  // as sample_grid: the cell's first node
    const BrickAxis ax = f.axis[0][i], ay = f.axis[1][j], az = f.axis[2][k];
    const int32_t brick = f.brick_of[ax.brick + ay.brick + az.brick];
    return f.brick_values(brick) + (ax.node + ay.node + az.node);
  };
  const float* c0 = corner(i0, j0, k0);
  const float* c1 = corner(i1, j1, k1);
  constexpr long sy = kBrickNodes, sz = kBrickNodes * kBrickNodes;
  const auto edge = [](const float* e) {  // (e[0], e[1]) as doubles: a cell edge along x
    return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(e))));
  };
  const __m128d a00 = edge(c0), a10 = edge(c0 + sy), a01 = edge(c0 + sz), a11 = edge(c0 + sy + sz);
  const __m128d b00 = edge(c1), b10 = edge(c1 + sy), b01 = edge(c1 + sz), b11 = edge(c1 + sy + sz);
  // corner values with the two points in the lanes
  const __m128d v000 = _mm_unpacklo_pd(a00, b00), v100 = _mm_unpackhi_pd(a00, b00);
  const __m128d v010 = _mm_unpacklo_pd(a10, b10), v110 = _mm_unpackhi_pd(a10, b10);
  const __m128d v001 = _mm_unpacklo_pd(a01, b01), v101 = _mm_unpackhi_pd(a01, b01);
  const __m128d v011 = _mm_unpacklo_pd(a11, b11), v111 = _mm_unpackhi_pd(a11, b11);
  const __m128d tx = _mm_sub_pd(gx, _mm_cvtepi32_pd(I)), ty = _mm_sub_pd(gy, _mm_cvtepi32_pd(J)),
                tz = _mm_sub_pd(gz, _mm_cvtepi32_pd(K));
  const auto lerp = [](__m128d lo, __m128d hi, __m128d t) {  // lo + t (hi - lo)
    return _mm_add_pd(lo, _mm_mul_pd(t, _mm_sub_pd(hi, lo)));
  };
  // along x, then y, then z, as sample_grid
  const __m128d c00 = lerp(v000, v100, tx), c10 = lerp(v010, v110, tx);
  const __m128d c01 = lerp(v001, v101, tx), c11 = lerp(v011, v111, tx);
  const __m128d cz0 = lerp(c00, c10, ty), cz1 = lerp(c01, c11, ty);
  _mm_storeu_pd(out, lerp(cz0, cz1, tz));
#else
  out[0] = f.sample_grid(map(p));
  out[1] = f.sample_grid(map(q));
#endif
}

}  // namespace kneesim::engine
