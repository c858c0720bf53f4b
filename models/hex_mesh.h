// Structured hexahedral meshes for the deformable solid (engine/solid): a box (block-on-ring
// block, tests, benchmarks). Node order of each element as in engine/solid/hex8.h.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace kneesim::models {

// a structured mesh of nx x ny x nz elements; node (i, j, k) at index i + (nx+1)(j + (ny+1) k)
struct HexMesh {
  int nx = 0, ny = 0, nz = 0;                 // elements per direction
  std::vector<Eigen::Vector3d> nodes;         // [m]
  std::vector<std::array<int, 8>> elements;   // node ids, hex8 order
  int node(int i, int j, int k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
};

// the box [origin, origin + size] [m] split into nx x ny x nz equal elements
HexMesh make_box_hex_mesh(int nx, int ny, int nz, const Eigen::Vector3d& size,
                          const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

}  // namespace kneesim::models
