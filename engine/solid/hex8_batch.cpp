#include "engine/solid/hex8_batch.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <immintrin.h>

// the 32- and 64-byte vectors never cross a non-inlined call (every helper below is inlined into
// the three compiled kernels), so GCC's note that their argument passing differs between AVX and
// SSE builds does not apply
#pragma GCC diagnostic ignored "-Wpsabi"

namespace kneesim::engine::solid {
namespace {

constexpr int W = kBatchLanes;
// L doubles in one vector: 8 for the AVX-512 path (the whole batch), 4 for the AVX2 and
// baseline paths, which take a batch in two halves (an 8-wide vector on 16 AVX2 registers
// spills: that path measured 3.9 M element updates per CPU second against 13.3 with 4 lanes)
// (a trait: GCC drops vector_size on an alias template's dependent size)
template <int L>
struct VecOf;
template <>
struct VecOf<4> {
  typedef double type __attribute__((vector_size(32)));
};
template <>
struct VecOf<8> {
  typedef double type __attribute__((vector_size(64)));
};
template <int L>
using VecN = typename VecOf<L>::type;

// h_m,a: the hourglass monomials eta zeta, zeta xi, xi eta, xi eta zeta at the nodes (+-1)
constexpr int hourglass_sign(int m, int a) {
  const int xi = static_cast<int>(kHexNatural[a][0]), eta = static_cast<int>(kHexNatural[a][1]),
            zeta = static_cast<int>(kHexNatural[a][2]);
  switch (m) {
    case 0: return eta * zeta;
    case 1: return zeta * xi;
    case 2: return xi * eta;
    default: return xi * eta * zeta;
  }
}

template <int L>
inline __attribute__((always_inline)) VecN<L> load(const double* p) {
  VecN<L> v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
template <int L>
inline __attribute__((always_inline)) void store(double* p, VecN<L> v) {
  __builtin_memcpy(p, &v, sizeof v);
}

// sum_a h_m,a v_a in node order: additions and subtractions only (also used at build time on
// doubles, so that hX is formed with the rounding the kernel uses on x)
template <class T>
inline __attribute__((always_inline)) T signed_sum(int m, const T* v) {
  T s = hourglass_sign(m, 0) > 0 ? v[0] : -v[0];
  for (int a = 1; a < kHexNodes; ++a) s = hourglass_sign(m, a) > 0 ? s + v[a] : s - v[a];
  return s;
}

// where the forces go: the batch buffer, or scattered to the nodes (Hex8Batch::scatter)
struct ForceOut {
  Hex8BatchForce* buffer;
  double* node_force;
  double* slot_force;
};

// the node positions of lanes [o, o + L), x[a][i] lane l = xs[ref.nodes[a][o + l]][i]: the
// portable form, lane by lane (the compiler makes a masked broadcast or an insert per value)
template <int L>
inline __attribute__((always_inline)) void gather_positions(const Hex8Batch& ref,
                                                            const Eigen::Vector3d* xs, int o,
                                                            VecN<L> (&x)[kHexNodes][3]) {
  for (int a = 0; a < kHexNodes; ++a) {
    const double* p[L];
    for (int l = 0; l < L; ++l) p[l] = xs[ref.nodes[a][o + l]].data();
    for (int i = 0; i < 3; ++i) {
      VecN<L> v;
      for (int l = 0; l < L; ++l) v[l] = p[l][i];
      x[a][i] = v;
    }
  }
}

// the same values on AVX-512 by plain loads: each element node's (x, y, z) as one masked
// 4-wide load (the fourth lane masked off, so nothing past the array is touched), two lanes'
// loads joined into one vector and transposed into the x, y and z vectors of the 8 lanes
// (unpacks and two-source permutes). Measured against the hardware gathers it replaces
// (vgatherdpd, one per coordinate and node): bench_solid on one thread 31.2 -> 35.7 M element
// updates per second (AMD EPYC, family 26; medians of 3 alternating runs); same values, so
// the same bits. Only inlined into the kernel compiled for AVX-512 (a target mismatch
// otherwise), as load_positions_avx2 below is into the AVX2 kernel
__attribute__((target("avx512f,avx512vl"), always_inline)) inline void load_positions_avx512(
    const Hex8Batch& ref, const Eigen::Vector3d* xs, VecN<8> (&x)[kHexNodes][3]) {
  const double* base = xs[0].data();
  // from the unpacks (v0 v1 w0 w1 | v4 v5 w4 w5) and (v2 v3 w2 w3 | v6 v7 w6 w7): v0..v7 and w0..w7
  const __m512i first = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i second = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  for (int a = 0; a < kHexNodes; ++a) {
    __m512d r[4];
    for (int l = 0; l < 4; ++l) {
      const long lo_at = 3 * static_cast<long>(ref.nodes[a][l]);
      const long hi_at = 3 * static_cast<long>(ref.nodes[a][l + 4]);
      const __m256d lo = _mm256_maskz_loadu_pd(0x7, base + lo_at);
      const __m256d hi = _mm256_maskz_loadu_pd(0x7, base + hi_at);
      r[l] = _mm512_maskz_insertf64x4(0xff, _mm512_castpd256_pd512(lo), hi, 1);  // l | l + 4
    }
    // the maskz forms with a full mask are the same instructions; the plain ones pass gcc 12 an
    // undefined source that it warns about
    const __m512d xz01 = _mm512_maskz_unpacklo_pd(0xff, r[0], r[1]);
    const __m512d yw01 = _mm512_maskz_unpackhi_pd(0xff, r[0], r[1]);
    const __m512d xz23 = _mm512_maskz_unpacklo_pd(0xff, r[2], r[3]);
    const __m512d yw23 = _mm512_maskz_unpackhi_pd(0xff, r[2], r[3]);
    const __m512d vx = _mm512_permutex2var_pd(xz01, first, xz23);
    const __m512d vy = _mm512_permutex2var_pd(yw01, first, yw23);
    const __m512d vz = _mm512_permutex2var_pd(xz01, second, xz23);
    __builtin_memcpy(&x[a][0], &vx, sizeof vx);
    __builtin_memcpy(&x[a][1], &vy, sizeof vy);
    __builtin_memcpy(&x[a][2], &vz, sizeof vz);
  }
}
// the node positions of lanes [o, o + 4) on AVX2 by plain loads, as load_positions_avx512:
// each element node's (x, y, z) by one masked 4-wide load (vmaskmovpd: the fourth lane is
// not read), transposed by unpacks and 128-bit permutes. Against the AVX2 hardware gathers it
// replaces: bench_solid --isa avx2 on one thread 22.0 -> 25.0 M element updates per second
// (AMD EPYC, family 26; medians of 3 alternating runs); the same values, so the same bits
__attribute__((target("avx2"), always_inline)) inline void load_positions_avx2(
    const Hex8Batch& ref, const Eigen::Vector3d* xs, int o, VecN<4> (&x)[kHexNodes][3]) {
  const double* base = xs[0].data();
  const __m256i xyz = _mm256_set_epi64x(0, -1, -1, -1);
  for (int a = 0; a < kHexNodes; ++a) {
    __m256d r[4];
    for (int l = 0; l < 4; ++l) {
      r[l] = _mm256_maskload_pd(base + 3 * static_cast<long>(ref.nodes[a][o + l]), xyz);
    }
    const __m256d xz01 = _mm256_unpacklo_pd(r[0], r[1]), yw01 = _mm256_unpackhi_pd(r[0], r[1]);
    const __m256d xz23 = _mm256_unpacklo_pd(r[2], r[3]), yw23 = _mm256_unpackhi_pd(r[2], r[3]);
    const __m256d vx = _mm256_permute2f128_pd(xz01, xz23, 0x20);
    const __m256d vy = _mm256_permute2f128_pd(yw01, yw23, 0x20);
    const __m256d vz = _mm256_permute2f128_pd(xz01, xz23, 0x31);
    __builtin_memcpy(&x[a][0], &vx, sizeof vx);
    __builtin_memcpy(&x[a][1], &vy, sizeof vy);
    __builtin_memcpy(&x[a][2], &vz, sizeof vz);
  }
}

// the lanes [o, o + L) of a batch at node positions x (loaded by one of the above); `count`
// of them are elements (count >= 1). Each lane's arithmetic is the same whatever L and o, so
// every path gives the same bits. The lanes' forces go to `force`
template <bool kPlastic, int L>
inline __attribute__((always_inline)) void batch_kernel(
    const Hex8Batch& ref, const SolidMaterial& mat, const VecN<L> (&x)[kHexNodes][3],
    const Sym6* plastic_strain, const double* alpha, int count, Hex8BatchForce& force,
    Hex8BatchResult& out, int o) {
  using Vec = VecN<L>;
  // one pass over the nodes: F_ij = sum_a x_a,i B_a,j and the hourglass sums
  // xh_m,i = sum_a h_m,a x_a,i, each accumulated in node order (the order of the separate
  // loops they replace, so the same bits). x and B die here: kept to the end (the forces
  // need B, the hourglass x) they were 48 vectors, more than the 32 registers, and spilled to
  // the stack; B is read again for the forces instead
  Vec F[3][3], xh[kHourglassModes][3];
#pragma GCC unroll 8
  for (int a = 0; a < kHexNodes; ++a) {
    Vec Ba[3];
    for (int j = 0; j < 3; ++j) Ba[j] = load<L>(ref.gradient[a][j] + o);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) F[i][j] = a == 0 ? x[0][i] * Ba[j] : F[i][j] + x[a][i] * Ba[j];
      for (int m = 0; m < kHourglassModes; ++m) {
        if (a == 0)
          xh[m][i] = hourglass_sign(m, 0) > 0 ? x[0][i] : -x[0][i];
        else
          xh[m][i] = hourglass_sign(m, a) > 0 ? xh[m][i] + x[a][i] : xh[m][i] - x[a][i];
      }
    }
  }
  store<L>(out.det_F + o, F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
                       F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                       F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]));
  // Green-Lagrange strain, Voigt xx yy zz xy yz zx: E_ij = (sum_k F_ki F_kj - delta_ij) / 2
  constexpr int kI[6] = {0, 1, 2, 0, 1, 2}, kJ[6] = {0, 1, 2, 1, 2, 0};
  Vec E[6];
  for (int v = 0; v < 6; ++v) {
    const int i = kI[v], j = kJ[v];
    Vec c = F[0][i] * F[0][j] + F[1][i] * F[1][j] + F[2][i] * F[2][j];
    if (v < 3) c = c - 1.0;
    E[v] = 0.5 * c;
  }
  // elastic strain: E - E_p, with E_p loaded only for lanes that have yielded before
  Vec e[6];
  for (int v = 0; v < 6; ++v) e[v] = E[v];
  bool any_plastic_history = false;
  if constexpr (kPlastic) {
    for (int l = 0; l < count; ++l) any_plastic_history |= alpha[o + l] != 0.0;
    if (any_plastic_history) {
      for (int v = 0; v < 6; ++v) {
        Vec ep{};
        for (int l = 0; l < count; ++l) ep[l] = plastic_strain[o + l][v];
        e[v] = E[v] - ep;
      }
    }
  }
  // trial stress S = 2 mu e + lambda tr(e) I, in calc_stress's order of operations
  const double lambda = mat.lame_lambda(), two_mu = 2.0 * mat.shear_modulus();
  const Vec tr = e[0] + e[1] + e[2];
  Vec S[6];
  for (int v = 0; v < 6; ++v) S[v] = two_mu * e[v];
  for (int v = 0; v < 3; ++v) S[v] = S[v] + lambda * tr;
  Vec strain_energy_2;  // S : E_e (tensor contraction) per lane
  for (int l = 0; l < L; ++l) out.yielded[o + l] = false;
  if constexpr (kPlastic) {
    // trial check on the squared deviator norm; lanes near or beyond yield take the scalar
    // radial return (which repeats the trial with its own rounding)
    const Vec p = (S[0] + S[1] + S[2]) / 3.0;
    const Vec d0 = S[0] - p, d1 = S[1] - p, d2 = S[2] - p;
    const Vec norm_sq = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (S[3] * S[3] + S[4] * S[4] + S[5] * S[5]);
    const double sy0 = calc_yield_stress(mat, 0.0);
    for (int l = 0; l < count; ++l) {
      const double sy = any_plastic_history ? calc_yield_stress(mat, alpha[o + l]) : sy0;
      if (norm_sq[l] < (2.0 / 3.0) * sy * sy * (1.0 - 1e-6)) continue;
      Sym6 strain, ep = Sym6::Zero();
      for (int v = 0; v < 6; ++v) strain[v] = E[v][l];
      if (any_plastic_history) ep = plastic_strain[o + l];
      const double a0 = any_plastic_history ? alpha[o + l] : 0.0;
      StressUpdate u = calc_stress(mat, strain, ep, a0);
      for (int v = 0; v < 6; ++v) {
        S[v][l] = u.stress[v];
        e[v][l] = strain[v] - u.plastic_strain[v];
      }
      out.yielded[o + l] = u.alpha != a0 || u.plastic_strain != ep;
      out.update[o + l] = u;
    }
  }
  strain_energy_2 = S[0] * e[0] + S[1] * e[1] + S[2] * e[2] +
                    2.0 * (S[3] * e[3] + S[4] * e[4] + S[5] * e[5]);
  const Vec volume = load<L>(ref.volume + o);
  store<L>(out.strain_energy + o, 0.5 * volume * strain_energy_2);
  for (int v = 0; v < 6; ++v) store<L>(out.stress[v] + o, S[v]);
  {
    const Vec a = S[0] - S[1], b = S[1] - S[2], c = S[2] - S[0];
    const Vec vm_sq = 0.5 * (a * a + b * b + c * c) + 3.0 * (S[3] * S[3] + S[4] * S[4] + S[5] * S[5]);
    // the square; each instruction set's kernel takes the whole batch's roots with one vector
    // root (sqrt_von_mises_*: a scalar root and store per lane had about 8 % of the AVX-512
    // kernel's samples)
    store<L>(out.von_mises + o, vm_sq);
  }
  // first Piola-Kirchhoff times the volume, P = V0 F S (S symmetric, full index map)
  constexpr int kVoigt[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
  Vec P[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      P[i][j] = volume * (F[i][0] * S[kVoigt[0][j]] + F[i][1] * S[kVoigt[1][j]] +
                          F[i][2] * S[kVoigt[2][j]]);
  // hourglass: q_m = (sum_a h_m,a x_a - F hX_m) / 8, kq_m = K_m q_m, G = sum_m kq_m hX_m^T
  Vec hX[kHourglassModes][3], kq[kHourglassModes][3];
  Vec hourglass_energy_2 = {};  // set by mode 0 below; initialized so gcc -O1 sees it
  for (int m = 0; m < kHourglassModes; ++m) {
    for (int j = 0; j < 3; ++j) hX[m][j] = load<L>(ref.hourglass_moment[m][j] + o);
    Vec q[3];
    for (int i = 0; i < 3; ++i)
      q[i] = 0.125 * (xh[m][i] - (F[i][0] * hX[m][0] + F[i][1] * hX[m][1] + F[i][2] * hX[m][2]));
    Vec K[6];
    for (int v = 0; v < 6; ++v) K[v] = load<L>(ref.hourglass_stiffness[m][v] + o);
    for (int i = 0; i < 3; ++i)
      kq[m][i] = K[kVoigt[i][0]] * q[0] + K[kVoigt[i][1]] * q[1] + K[kVoigt[i][2]] * q[2];
    const Vec qkq = q[0] * kq[m][0] + q[1] * kq[m][1] + q[2] * kq[m][2];
    hourglass_energy_2 = m == 0 ? qkq : hourglass_energy_2 + qkq;
  }
  Vec G[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      G[i][j] = kq[0][i] * hX[0][j] + kq[1][i] * hX[1][j] + kq[2][i] * hX[2][j] +
                kq[3][i] * hX[3][j];
  store<L>(out.hourglass_energy + o, 0.5 * hourglass_energy_2);
  // f_a = (P - G / 8) B_a + (1/8) sum_m h_m,a kq_m
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P[i][j] = P[i][j] - 0.125 * G[i][j];
  // unrolled so that the signs h_m,a are constants (a rolled loop computed them from
  // kHexNatural and branched on them, every batch)
#pragma GCC unroll 8
  for (int a = 0; a < kHexNodes; ++a) {
    Vec Ba[3];
    for (int j = 0; j < 3; ++j) Ba[j] = load<L>(ref.gradient[a][j] + o);
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
      Vec h = hourglass_sign(0, a) > 0 ? kq[0][i] : -kq[0][i];
      for (int m = 1; m < kHourglassModes; ++m) h = hourglass_sign(m, a) > 0 ? h + kq[m][i] : h - kq[m][i];
      store<L>(force.f[a][i] + o, P[i][0] * Ba[0] + P[i][1] * Ba[1] + P[i][2] * Ba[2] + 0.125 * h);
    }
  }
}

// the scatter (file comment) of the batch's `count` elements' forces: lane by lane
// (ascending element order), each element's eight nodes; a node summed in place is 4 doubles
// (x, y, z, 0), a slot 3 (the pointers in locals: read through force_out they were reloaded
// after every store, which may alias)
inline __attribute__((always_inline)) void scatter_lanes(const Hex8Batch& ref,
                                                         const Hex8BatchForce& force,
                                                         int count, const ForceOut& force_out) {
  double* const node_force = force_out.node_force;
  double* const slot_force = force_out.slot_force;
  for (int l = 0; l < count; ++l) {
    for (int a = 0; a < kHexNodes; ++a) {
      const int s = ref.scatter[a][l];
      const double fx = force.f[a][0][l], fy = force.f[a][1][l], fz = force.f[a][2][l];
      if (s >= 0) {
        double* f = node_force + 4 * static_cast<long>(s);
        f[0] += fx;
        f[1] += fy;
        f[2] += fz;
      } else {
        double* f = slot_force + 3 * static_cast<long>(~s);
        f[0] = fx;
        f[1] = fy;
        f[2] = fz;
      }
    }
  }
}

// the same scatter on AVX-512: each element node's (fx, fy, fz, 0) formed once by a transpose
// of the batch's force vectors (two unpacks and two two-source permutes per two lanes), then
// added to its node with one 4-wide load, add and store; the same additions in the same order
// as scatter_lanes (the fourth component adds 0.0 to 0.0), so the same bits
__attribute__((target("avx512f,avx512vl"), always_inline)) inline void scatter_avx512(
    const Hex8Batch& ref, const Hex8BatchForce& force, int count, const ForceOut& force_out) {
  static_assert(kBatchLanes == 8, "the transpose takes lanes in pairs of one 8-wide vector");
  alignas(64) double quad[kBatchLanes][kHexNodes][4];  // [lane][node] (fx, fy, fz, 0)
  const __m512d zero = _mm512_setzero_pd();
  // from (x0 y0 x2 y2 x4 y4 x6 y6) and (z0 0 z2 0 z4 0 z6 0): lanes 0 | 2 and 4 | 6
  const __m512i low_pairs = _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0);
  const __m512i high_pairs = _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4);
  for (int a = 0; a < kHexNodes; ++a) {
    const __m512d fx = _mm512_load_pd(force.f[a][0]), fy = _mm512_load_pd(force.f[a][1]),
                  fz = _mm512_load_pd(force.f[a][2]);
    const __m512d xy_even = _mm512_maskz_unpacklo_pd(0xff, fx, fy);
    const __m512d xy_odd = _mm512_maskz_unpackhi_pd(0xff, fx, fy);
    const __m512d z_even = _mm512_maskz_unpacklo_pd(0xff, fz, zero);
    const __m512d z_odd = _mm512_maskz_unpackhi_pd(0xff, fz, zero);
    const __m512d q02 = _mm512_permutex2var_pd(xy_even, low_pairs, z_even);
    const __m512d q46 = _mm512_permutex2var_pd(xy_even, high_pairs, z_even);
    const __m512d q13 = _mm512_permutex2var_pd(xy_odd, low_pairs, z_odd);
    const __m512d q57 = _mm512_permutex2var_pd(xy_odd, high_pairs, z_odd);
    _mm256_store_pd(quad[0][a], _mm512_maskz_extractf64x4_pd(0xf, q02, 0));
    _mm256_store_pd(quad[2][a], _mm512_maskz_extractf64x4_pd(0xf, q02, 1));
    _mm256_store_pd(quad[4][a], _mm512_maskz_extractf64x4_pd(0xf, q46, 0));
    _mm256_store_pd(quad[6][a], _mm512_maskz_extractf64x4_pd(0xf, q46, 1));
    _mm256_store_pd(quad[1][a], _mm512_maskz_extractf64x4_pd(0xf, q13, 0));
    _mm256_store_pd(quad[3][a], _mm512_maskz_extractf64x4_pd(0xf, q13, 1));
    _mm256_store_pd(quad[5][a], _mm512_maskz_extractf64x4_pd(0xf, q57, 0));
    _mm256_store_pd(quad[7][a], _mm512_maskz_extractf64x4_pd(0xf, q57, 1));
  }
  double* const node_force = force_out.node_force;
  double* const slot_force = force_out.slot_force;
  for (int l = 0; l < count; ++l) {
#pragma GCC unroll 8
    for (int a = 0; a < kHexNodes; ++a) {
      const int s = ref.scatter[a][l];
      const __m256d q = _mm256_load_pd(quad[l][a]);
      if (s >= 0) {
        double* f = node_force + 4 * static_cast<long>(s);
        _mm256_storeu_pd(f, _mm256_add_pd(_mm256_loadu_pd(f), q));
      } else {
        double* f = slot_force + 3 * static_cast<long>(~s);
        f[0] = quad[l][a][0];
        f[1] = quad[l][a][1];
        f[2] = quad[l][a][2];
      }
    }
  }
}

// the batch's von Mises from its squares, in place, for the lanes the kernel computed (the
// 4-lane paths skip an empty second half); IEEE square roots are correctly rounded, so every
// width gives the bits std::sqrt gives
inline __attribute__((always_inline)) void sqrt_von_mises_sse2(Hex8BatchResult& out,
                                                               int lanes) {
  for (int l = 0; l < lanes; l += 2) {
    _mm_storeu_pd(out.von_mises + l, _mm_sqrt_pd(_mm_loadu_pd(out.von_mises + l)));
  }
}
__attribute__((target("avx2"), always_inline)) inline void sqrt_von_mises_avx2(
    Hex8BatchResult& out, int lanes) {
  for (int l = 0; l < lanes; l += 4) {
    _mm256_storeu_pd(out.von_mises + l, _mm256_sqrt_pd(_mm256_loadu_pd(out.von_mises + l)));
  }
}
__attribute__((target("avx512f"), always_inline)) inline void sqrt_von_mises_avx512(
    Hex8BatchResult& out) {
  _mm512_storeu_pd(out.von_mises, _mm512_maskz_sqrt_pd(0xff, _mm512_loadu_pd(out.von_mises)));
}

// a batch in two halves of 4 lanes, the second only if it holds an element (its outputs are
// never read otherwise); a scatter follows both halves, lane by lane in ascending element
// order
static_assert(kBatchLanes == 8, "the 4-lane paths take a batch in two halves");
template <bool kPlastic, bool kScatter>
inline __attribute__((always_inline)) void batch_halves(
    const Hex8Batch& ref, const SolidMaterial& mat, const Eigen::Vector3d* xs, const Sym6* ep,
    const double* alpha, int count, const ForceOut& force_out, Hex8BatchResult& out) {
  Hex8BatchForce local;
  Hex8BatchForce& force = kScatter ? local : *force_out.buffer;
  VecN<4> x[kHexNodes][3];
  gather_positions<4>(ref, xs, 0, x);
  batch_kernel<kPlastic, 4>(ref, mat, x, ep, alpha, std::min(count, 4), force, out, 0);
  if (count > 4) {
    gather_positions<4>(ref, xs, 4, x);
    batch_kernel<kPlastic, 4>(ref, mat, x, ep, alpha, count - 4, force, out, 4);
  }
  if constexpr (kScatter) scatter_lanes(ref, force, count, force_out);
}

using Kernel = void (*)(const Hex8Batch&, const SolidMaterial&, const Eigen::Vector3d*,
                       const Sym6*, const double*, int, const ForceOut&, Hex8BatchResult&);

template <bool kPlastic, bool kScatter>
void kernel_baseline(const Hex8Batch& ref, const SolidMaterial& mat, const Eigen::Vector3d* x,
                     const Sym6* ep, const double* alpha, int count, const ForceOut& force,
                     Hex8BatchResult& out) {
  batch_halves<kPlastic, kScatter>(ref, mat, x, ep, alpha, count, force, out);
  sqrt_von_mises_sse2(out, count > 4 ? 8 : 4);
}

template <bool kPlastic, bool kScatter>
__attribute__((target("avx2"))) void kernel_avx2(const Hex8Batch& ref, const SolidMaterial& mat,
                                                 const Eigen::Vector3d* x, const Sym6* ep,
                                                 const double* alpha, int count,
                                                 const ForceOut& force_out,
                                                 Hex8BatchResult& out) {
  Hex8BatchForce local;
  Hex8BatchForce& force = kScatter ? local : *force_out.buffer;
  VecN<4> xv[kHexNodes][3];
  load_positions_avx2(ref, x, 0, xv);
  batch_kernel<kPlastic, 4>(ref, mat, xv, ep, alpha, std::min(count, 4), force, out, 0);
  if (count > 4) {
    load_positions_avx2(ref, x, 4, xv);
    batch_kernel<kPlastic, 4>(ref, mat, xv, ep, alpha, count - 4, force, out, 4);
  }
  sqrt_von_mises_avx2(out, count > 4 ? 8 : 4);
  // the scalar scatter: a transpose as scatter_avx512's, on 4-wide vectors, measured no faster
  if constexpr (kScatter) scatter_lanes(ref, force, count, force_out);
}

template <bool kPlastic, bool kScatter>
__attribute__((target("avx512f,avx512vl"))) void kernel_avx512(const Hex8Batch& ref,
                                                      const SolidMaterial& mat,
                                                      const Eigen::Vector3d* x, const Sym6* ep,
                                                      const double* alpha, int count,
                                                      const ForceOut& force_out,
                                                      Hex8BatchResult& out) {
  Hex8BatchForce local;
  Hex8BatchForce& force = kScatter ? local : *force_out.buffer;
  VecN<8> xv[kHexNodes][3];
  load_positions_avx512(ref, x, xv);
  batch_kernel<kPlastic, kBatchLanes>(ref, mat, xv, ep, alpha, count, force, out, 0);
  sqrt_von_mises_avx512(out);
  if constexpr (kScatter) scatter_avx512(ref, force, count, force_out);
}

// kernels[isa][plastic][scatter]
constexpr Kernel kKernels[3][2][2] = {
    {{kernel_baseline<false, false>, kernel_baseline<false, true>},
     {kernel_baseline<true, false>, kernel_baseline<true, true>}},
    {{kernel_avx2<false, false>, kernel_avx2<false, true>},
     {kernel_avx2<true, false>, kernel_avx2<true, true>}},
    {{kernel_avx512<false, false>, kernel_avx512<false, true>},
     {kernel_avx512<true, false>, kernel_avx512<true, true>}}};

Hex8Isa detect_isa() {
  __builtin_cpu_init();
  // the AVX-512 path's 4-wide masked loads need the VL extension (every AVX-512 CPU since
  // Skylake-SP and Zen 4 has it)
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")) {
    return Hex8Isa::kAvx512;
  }
  if (__builtin_cpu_supports("avx2")) return Hex8Isa::kAvx2;
  return Hex8Isa::kBaseline;
}
const Hex8Isa kBestIsa = detect_isa();
std::atomic<Hex8Isa> g_isa{kBestIsa};

Kernel select(Hex8Isa isa, const SolidMaterial& material, bool scatter) {
  if (!hex8_batch_supports(isa)) {
    std::fprintf(stderr, "hex8 batch kernel: the %s path is not supported by this CPU\n",
                 to_string(isa));
    std::abort();
  }
  const bool plastic = material.kind == SolidMaterialKind::kJ2Plastic;
  return kKernels[static_cast<int>(isa)][plastic][scatter];
}

}  // namespace

Hex8Isa hex8_batch_best_isa() { return kBestIsa; }

bool hex8_batch_supports(Hex8Isa isa) { return static_cast<int>(isa) <= static_cast<int>(kBestIsa); }

Hex8Isa hex8_batch_isa() { return g_isa.load(std::memory_order_relaxed); }

void set_hex8_batch_isa(Hex8Isa isa) {
  if (hex8_batch_supports(isa)) g_isa.store(isa, std::memory_order_relaxed);
}

const char* to_string(Hex8Isa isa) {
  switch (isa) {
    case Hex8Isa::kBaseline: return "baseline x86-64";
    case Hex8Isa::kAvx2: return "AVX2";
    case Hex8Isa::kAvx512: return "AVX-512";
  }
  return "?";
}

Hex8Batch make_hex8_batch(const std::array<int, kHexNodes>* element_nodes,
                          const Hex8Reference* reference, int count, const Eigen::Vector3d* X) {
  Hex8Batch b;
  std::memset(&b, 0, sizeof b);
  for (int l = 0; l < W; ++l) {
    const int src = l < count ? l : 0;
    for (int a = 0; a < kHexNodes; ++a) b.scatter[a][l] = b.nodes[a][l] = element_nodes[src][a];
    if (l >= count) continue;  // padding: zero data, zero force
    HexPoints P;
    for (int a = 0; a < kHexNodes; ++a) P[a] = X[element_nodes[l][a]];
    const Hex8Reference& r = reference[l];
    b.volume[l] = r.volume;
    for (int a = 0; a < kHexNodes; ++a)
      for (int j = 0; j < 3; ++j) b.gradient[a][j][l] = r.gradient(a, j);
    for (int m = 0; m < kHourglassModes; ++m) {
      for (int j = 0; j < 3; ++j) {
        double c[kHexNodes];
        for (int a = 0; a < kHexNodes; ++a) c[a] = P[a][j];
        b.hourglass_moment[m][j][l] = signed_sum(m, c);
      }
      const Eigen::Matrix3d& K = r.hourglass_stiffness[m];
      const double k[6] = {K(0, 0), K(1, 1), K(2, 2), K(0, 1), K(1, 2), K(2, 0)};
      for (int v = 0; v < 6; ++v) b.hourglass_stiffness[m][v][l] = k[v];
    }
  }
  return b;
}

void calc_hex8_batch(const Hex8Batch& ref, const SolidMaterial& material,
                     const Eigen::Vector3d* x, const Sym6* plastic_strain, const double* alpha,
                     int count, Hex8BatchForce& force, Hex8BatchResult& out, Hex8Isa isa) {
  const ForceOut to{&force, nullptr, nullptr};
  select(isa, material, false)(ref, material, x, plastic_strain, alpha, count, to, out);
}

void calc_hex8_batch_scatter(const Hex8Batch& ref, const SolidMaterial& material,
                             const Eigen::Vector3d* x, const Sym6* plastic_strain,
                             const double* alpha, int count, double* node_force,
                             double* slot_force, Hex8BatchResult& out, Hex8Isa isa) {
  const ForceOut to{nullptr, node_force, slot_force};
  select(isa, material, true)(ref, material, x, plastic_strain, alpha, count, to, out);
}

}  // namespace kneesim::engine::solid
