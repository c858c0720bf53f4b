// Signed distance field of the rigid femoral component, built once per Model in its own frame
// F and sampled with trilinear interpolation at insert points every step (physics.md section
// 4). Exact distances (FCL's point-triangle projection, engine/fcl_adapter.h) are computed
// only in a narrow band around the surface, each triangle visiting the nodes of its grown
// bounding box; a BVH distance query per node was tried first and was ~100x slower (FCL runs
// a GJK per leaf for a point probe). nodes beyond the band hold +band (outside) or -band (inside, found by
// flood fill from the grid boundary). Sign comes from angle-weighted pseudonormals
// (Baerentzen & Aanaes 2005), so open articular-surface meshes work too: their back side is
// "inside" within the band.
//
// Storage is bricked (CHANGELOG.md, performance round 1): the node grid is cut into bricks of 8^3 nodes that
// overlap by one node, so each brick covers 7^3 cells and the 8 corners of any cell lie in one
// 2 KB brick. Only bricks that hold a value other than the clamp value are stored; the rest are
// uniform (+band or -band) and read one of two shared clamp bricks (4 KB, always in cache), so
// that sampling takes no branch on the brick. A dense x-fastest grid (24 MB at
// 0.4 mm for the generic femur) was used first: a step's ~900 samples scattered their 4 cache
// lines each over 120 KB z-slabs and pages, and the loads missed (a third of the sample's time
// on its first load). In a brick the step's samples share a few hundred KB of contiguous
// memory. The values and the interpolation arithmetic are those of the dense grid, so the
// layout does not change a single result bit.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace kneesim::engine {

// nodes per brick edge, cells per brick edge (bricks share their boundary nodes)
inline constexpr int kBrickNodes = 8;
inline constexpr int kBrickCells = kBrickNodes - 1;
inline constexpr int kBrickSize = kBrickNodes * kBrickNodes * kBrickNodes;
// brick_of entries of bricks not stored: every node holds +band or -band
inline constexpr int32_t kBrickOutside = -1;
inline constexpr int32_t kBrickInside = -2;

// per axis and cell index: the cell's brick's share of the brick index (bricks before it along
// the axis times the axis's brick stride) and its corner node's offset inside the brick; a
// table lookup instead of a division by kBrickCells per axis
struct BrickAxis {
  int32_t brick;
  int32_t node;
};

// what sampling reads, as plain values and pointers: the contact kernel copies one per step so
// that its loop holds them in registers (engine/contact.cpp)
struct FieldSampler {
  double limit[3];                // cells per axis: g must lie in [0, limit) [nodes]
  double band;                    // the value outside the grid [m]
  double outside, inside;         // +band and -band of the clamp bricks, as stored (float) [m]
  const int32_t* brick_of;        // SignedDistanceField::Storage
  const float* values;
  const float* clamp_bricks;      // Storage::clamp_bricks
  const BrickAxis* axis[3];
  // the first value of brick_of's entry `brick`: a stored brick's values, or for a brick not
  // stored the clamp brick of its value (kBrickOutside = -1: the first, kBrickInside = -2: the
  // second), whose 8 equal corners interpolate to exactly that value (c + t (c - c) = c).
  // Selected with a mask, not a conditional, which the compiler makes a branch that about one
  // sample in ten takes in no predictable order; no out-of-range pointer is formed.
  [[gnu::always_inline]] const float* brick_values(int32_t brick) const {
    static_assert(kBrickOutside == -1 && kBrickInside == -2, "clamp brick order");
    const uintptr_t stored = -static_cast<uintptr_t>(brick >= 0);  // all ones when stored
    const uintptr_t base = (reinterpret_cast<uintptr_t>(values) & stored) |
                           (reinterpret_cast<uintptr_t>(clamp_bricks) & ~stored);
    const long index = brick ^ (brick >> 31);  // brick when stored, -1 - brick when not
    return reinterpret_cast<const float*>(base) + index * kBrickSize;
  }
  // the field at grid coordinates g = (p_F - origin) / spacing [nodes]; +band outside the
  // grid [m]
  double sample_grid(const Eigen::Vector3d& g) const;
};

// a field is a small value (grid geometry and a shared pointer): copies of a Model share one
// const storage, so a field built once serves every condition, material and wear update
struct SignedDistanceField {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // position of node (0,0,0) [m], F frame
  double spacing = 1e-3;                             // node spacing [m]
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();    // nodes per axis
  double band = 3e-3;                                // exact within |phi| < band [m]
  Eigen::Vector3i bricks = Eigen::Vector3i::Zero();  // bricks per axis (cells / 7, rounded up)
  struct Storage {
    std::vector<int32_t> brick_of;  // per brick, x fastest: its index in values, or
                                    // kBrickOutside / kBrickInside
    std::vector<float> values;      // signed distance [m] of the stored bricks, 8^3 nodes
                                    // each, x fastest within a brick
    std::array<std::vector<BrickAxis>, 3> axes;  // per axis, one per cell (make_brick_axes)
    // a brick of +band nodes then one of -band (as stored, float): a cell of a brick not
    // stored reads its corners here, so sampling needs no branch on the brick (make_brick_axes)
    std::vector<float> clamp_bricks;
  };
  std::shared_ptr<const Storage> storage;

  bool empty() const { return !storage; }
  int stored_bricks() const;
  size_t bytes() const;  // memory of the storage [bytes]

  // signed distance [m] at p_F (negative inside) and its gradient; +band outside the grid
  double sample(const Eigen::Vector3d& p_F, Eigen::Vector3d* gradient = nullptr) const;
  // the same without the gradient at grid coordinates g = (p_F - origin) / spacing [nodes]:
  // the contact kernel carries insert points into them with one affine map per element
  // (engine/contact.cpp), which saves a transform, the subtraction and three divisions [m]
  double sample_grid(const Eigen::Vector3d& g) const { return sampler().sample_grid(g); }
  FieldSampler sampler() const;
  // the value at node (i, j, k) [m] (tests, diagnostics)
  float node(int i, int j, int k) const;
};

// the per-axis tables and the clamp bricks of a storage whose brick_of and values are set, for
// the field's dims, bricks and band
void make_brick_axes(const SignedDistanceField& field, SignedDistanceField::Storage& storage);

[[gnu::always_inline]] inline double FieldSampler::sample_grid(const Eigen::Vector3d& g) const {
#ifdef __SSE2__
  // x and y in the two lanes of one register: the bounds, the truncation, the fractions and
  // the x and y interpolations take one packed instruction for two scalar ones. Each lane does
  // the scalar code's operations in its order (no FMA on the baseline target), so the result
  // is the scalar code's, bit for bit (CHANGELOG.md, performance round 3).
  const __m128d gxy = _mm_set_pd(g.y(), g.x());
  const double gz = g.z();
  // outside the grid's cells (or NaN): +band
  const __m128d in_xy = _mm_and_pd(_mm_cmpge_pd(gxy, _mm_setzero_pd()),
                                   _mm_cmplt_pd(gxy, _mm_loadu_pd(limit)));
  if (_mm_movemask_pd(in_xy) != 3 || !(gz >= 0.0 && gz < limit[2])) return band;
  const __m128i ij = _mm_cvttpd_epi32(gxy);  // truncation is the floor inside the grid
  const int i = _mm_cvtsi128_si32(ij), j = _mm_cvtsi128_si32(_mm_shuffle_epi32(ij, 1));
  const int k = static_cast<int>(gz);
#else
  // outside the grid's cells (or NaN); inside, truncation is the floor (std::floor is a libm
  // call on the baseline x86-64 target, which has no roundsd)
  if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.z() >= 0.0 && g.x() < limit[0] && g.y() < limit[1] &&
        g.z() < limit[2])) {
    return band;
  }
  const int i = static_cast<int>(g.x()), j = static_cast<int>(g.y()), k = static_cast<int>(g.z());
#endif
  const BrickAxis ax = axis[0][i], ay = axis[1][j], az = axis[2][k];
  const int32_t brick = brick_of[ax.brick + ay.brick + az.brick];
  constexpr long sx = 1, sy = kBrickNodes, sz = kBrickNodes * kBrickNodes;
  const float* phi = brick_values(brick) + (ax.node + ay.node + az.node);
#ifdef __SSE2__
  static_assert(sx == 1, "x-neighbours adjacent: one 64-bit load holds a cell edge along x");
  const auto edge = [](const float* p) {  // (p[0], p[1]) as doubles
    return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
  };
  const __m128d e00 = edge(phi), e10 = edge(phi + sy);          // (c000, c100), (c010, c110)
  const __m128d e01 = edge(phi + sz), e11 = edge(phi + sy + sz);  // (c001, c101), (c011, c111)
  const __m128d txy = _mm_sub_pd(gxy, _mm_cvtepi32_pd(ij));
  const __m128d tx = _mm_unpacklo_pd(txy, txy), ty = _mm_unpackhi_pd(txy, txy);
  const double tz = gz - static_cast<double>(k);
  // along x: (c00, c10) and (c01, c11), c00 = c000 + tx (c100 - c000) as below
  const __m128d lo0 = _mm_unpacklo_pd(e00, e10), hi0 = _mm_unpackhi_pd(e00, e10);
  const __m128d lo1 = _mm_unpacklo_pd(e01, e11), hi1 = _mm_unpackhi_pd(e01, e11);
  const __m128d cy0 = _mm_add_pd(lo0, _mm_mul_pd(tx, _mm_sub_pd(hi0, lo0)));
  const __m128d cy1 = _mm_add_pd(lo1, _mm_mul_pd(tx, _mm_sub_pd(hi1, lo1)));
  // along y: (c0, c1)
  const __m128d a = _mm_unpacklo_pd(cy0, cy1), b = _mm_unpackhi_pd(cy0, cy1);
  const __m128d c = _mm_add_pd(a, _mm_mul_pd(ty, _mm_sub_pd(b, a)));
  const double c0 = _mm_cvtsd_f64(c), c1 = _mm_cvtsd_f64(_mm_unpackhi_pd(c, c));
  return c0 + tz * (c1 - c0);
#else
  const double tx = g.x() - static_cast<double>(i), ty = g.y() - static_cast<double>(j),
               tz = g.z() - static_cast<double>(k);
  const double c000 = phi[0], c100 = phi[sx];
  const double c010 = phi[sy], c110 = phi[sx + sy];
  const double c001 = phi[sz], c101 = phi[sx + sz];
  const double c011 = phi[sy + sz], c111 = phi[sx + sy + sz];
  // interpolate along x, then y, then z
  const double c00 = c000 + tx * (c100 - c000), c10 = c010 + tx * (c110 - c010);
  const double c01 = c001 + tx * (c101 - c001), c11 = c011 + tx * (c111 - c011);
  const double c0 = c00 + ty * (c10 - c00), c1 = c01 + ty * (c11 - c01);
  return c0 + tz * (c1 - c0);
#endif
}

// builds the field of a triangle mesh (metres, outward normals) with node spacing [m] and an
// exact band half-width [m]; OpenMP threads own z-slabs (bit-identical for any thread count)
SignedDistanceField make_signed_distance_field(const std::vector<Eigen::Vector3d>& vertices,
                                               const std::vector<Eigen::Vector3i>& triangles,
                                               double spacing, double band);

}  // namespace kneesim::engine
