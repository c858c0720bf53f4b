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
  };
  std::shared_ptr<const Storage> storage;

  bool empty() const { return !storage; }
  int stored_bricks() const;
  size_t bytes() const;  // memory of the storage [bytes]

  // signed distance [m] at p_F (negative inside) and its gradient; +band outside the grid
  double sample(const Eigen::Vector3d& p_F, Eigen::Vector3d* gradient = nullptr) const;
  // the value at node (i, j, k) [m] (tests, diagnostics)
  float node(int i, int j, int k) const;
};

// builds the field of a triangle mesh (metres, outward normals) with node spacing [m] and an
// exact band half-width [m]; OpenMP threads own z-slabs (bit-identical for any thread count)
SignedDistanceField make_signed_distance_field(const std::vector<Eigen::Vector3d>& vertices,
                                               const std::vector<Eigen::Vector3i>& triangles,
                                               double spacing, double band);

}  // namespace kneesim::engine
