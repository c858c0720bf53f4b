// The project's only door to FCL/libccd (design.md: one adapter file per library).
// Two services: the point-triangle projection that builds the femoral signed distance field
// (engine/sdf.h), and exact point-to-mesh distance queries on an OBBRSS bounding-volume
// hierarchy (the reference the field is tested against). FCL types stay in fcl_adapter.cpp.
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

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kneesim::engine
