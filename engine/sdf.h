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
// Storage is bricked (docs/performance.md): the node grid is cut into bricks of 8^3 nodes that
// overlap by one node, so each brick covers 7^3 cells and the 8 corners of any cell lie in one
// 2 KB brick. Only bricks that hold a value other than the clamp value are stored; the rest are
// uniform (+band or -band) and answer without a memory access. A dense x-fastest grid (24 MB at
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
  const BrickAxis* axis[3];
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

// the per-axis tables of a storage whose brick_of and values are set, for the field's dims
// and bricks
void make_brick_axes(const SignedDistanceField& field, SignedDistanceField::Storage& storage);

inline double FieldSampler::sample_grid(const Eigen::Vector3d& g) const {
  // outside the grid's cells (or NaN); inside, truncation is the floor (std::floor is a libm
  // call on the baseline x86-64 target, which has no roundsd)
  if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.z() >= 0.0 && g.x() < limit[0] && g.y() < limit[1] &&
        g.z() < limit[2])) {
    return band;
  }
  const int i = static_cast<int>(g.x()), j = static_cast<int>(g.y()), k = static_cast<int>(g.z());
  const BrickAxis ax = axis[0][i], ay = axis[1][j], az = axis[2][k];
  const int32_t brick = brick_of[ax.brick + ay.brick + az.brick];
  if (brick < 0) {
    // every corner holds the clamp value: the interpolation would return it exactly
    return brick == kBrickOutside ? outside : inside;
  }
  const double tx = g.x() - static_cast<double>(i), ty = g.y() - static_cast<double>(j),
               tz = g.z() - static_cast<double>(k);
  constexpr long sx = 1, sy = kBrickNodes, sz = kBrickNodes * kBrickNodes;
  const float* phi = values + static_cast<long>(brick) * kBrickSize + (ax.node + ay.node + az.node);
  const double c000 = phi[0], c100 = phi[sx];
  const double c010 = phi[sy], c110 = phi[sx + sy];
  const double c001 = phi[sz], c101 = phi[sx + sz];
  const double c011 = phi[sy + sz], c111 = phi[sx + sy + sz];
  // interpolate along x, then y, then z
  const double c00 = c000 + tx * (c100 - c000), c10 = c010 + tx * (c110 - c010);
  const double c01 = c001 + tx * (c101 - c001), c11 = c011 + tx * (c111 - c011);
  const double c0 = c00 + ty * (c10 - c00), c1 = c01 + ty * (c11 - c01);
  return c0 + tz * (c1 - c0);
}

// builds the field of a triangle mesh (metres, outward normals) with node spacing [m] and an
// exact band half-width [m]; OpenMP threads own z-slabs (bit-identical for any thread count)
SignedDistanceField make_signed_distance_field(const std::vector<Eigen::Vector3d>& vertices,
                                               const std::vector<Eigen::Vector3i>& triangles,
                                               double spacing, double band);

}  // namespace kneesim::engine
