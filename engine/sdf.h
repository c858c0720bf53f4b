// Signed distance field of the rigid femoral component, built once per Model in its own frame
// F and sampled with trilinear interpolation at insert points every step (physics.md section
// 4). Exact distances (FCL's point-triangle projection, engine/fcl_adapter.h) are computed
// only in a narrow band around the surface, each triangle visiting the nodes of its grown
// bounding box; a BVH distance query per node was tried first and was ~100x slower (FCL runs
// a GJK per leaf for a point probe). nodes beyond the band hold +band (outside) or -band (inside, found by
// flood fill from the grid boundary). Sign comes from angle-weighted pseudonormals
// (Baerentzen & Aanaes 2005), so open articular-surface meshes work too: their back side is
// "inside" within the band. A dense grid was preferred over a sparse/hashed one: at 0.4 mm it
// costs a few MB and one memory access per corner, and sampling sits in the hot loop.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace kneesim::engine {

struct SignedDistanceField {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // position of node (0,0,0) [m], F frame
  double spacing = 1e-3;                             // node spacing [m]
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();    // nodes per axis
  double band = 3e-3;                                // exact within |phi| < band [m]
  std::vector<float> phi;                            // signed distance [m], x fastest

  bool empty() const { return phi.empty(); }

  // signed distance [m] at p_F (negative inside) and its gradient; +band outside the grid
  double sample(const Eigen::Vector3d& p_F, Eigen::Vector3d* gradient = nullptr) const;
};

// builds the field of a triangle mesh (metres, outward normals) with node spacing [m] and an
// exact band half-width [m]; OpenMP threads own z-slabs (bit-identical for any thread count)
SignedDistanceField make_signed_distance_field(const std::vector<Eigen::Vector3d>& vertices,
                                               const std::vector<Eigen::Vector3i>& triangles,
                                               double spacing, double band);

}  // namespace kneesim::engine
