// The project's only door to FCL/libccd (design.md: one adapter file per library).
// Two services: exact point-to-mesh distance queries on a BVH (used once, to build the
// femoral signed distance field) and BVH culling of insert triangles against an oriented box
// (used by the contact candidate search). FCL types stay inside fcl_adapter.cpp.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

namespace kneesim::engine {

// closest point of triangle abc to p (FCL's simplex projection): squared distance [m^2],
// barycentric weights of the closest point, and which vertices support it (bit i = vertex i:
// 7 face interior, two bits an edge, one bit a vertex)
struct TriangleProjection {
  double squared_distance = 0.0;
  double weight[3] = {0, 0, 0};
  unsigned int support = 0;
};
TriangleProjection project_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c, const Eigen::Vector3d& p);

class MeshBvh {
 public:
  MeshBvh(const std::vector<Eigen::Vector3d>& vertices,
          const std::vector<Eigen::Vector3i>& triangles);
  ~MeshBvh();
  MeshBvh(MeshBvh&&) noexcept;
  MeshBvh& operator=(MeshBvh&&) noexcept;

  // unsigned distance [m] from p to the mesh; the closest point and its triangle index
  double closest_point(const Eigen::Vector3d& p, Eigen::Vector3d& closest, int& triangle) const;

  // indices of triangles whose bounding volumes overlap the box (half extents [m]) placed at
  // X_MB in the mesh frame; appended to `out` (cleared first), sorted ascending
  void find_triangles_in_box(const Eigen::Isometry3d& X_MB, const Eigen::Vector3d& half_extents,
                             std::vector<int>& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kneesim::engine
