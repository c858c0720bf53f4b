#include "engine/fcl_adapter.h"

#include <algorithm>
#include <fcl/fcl.h>
#include <fcl/math/detail/project.h>
#include <limits>

namespace kneesim::engine {

using Bvh = fcl::BVHModel<fcl::OBBRSSd>;

TriangleProjection project_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c, const Eigen::Vector3d& p) {
  const auto r = fcl::detail::Projectd::projectTriangle(a, b, c, p);
  TriangleProjection out;
  out.squared_distance = r.sqr_distance;
  for (int i = 0; i < 3; ++i) out.weight[i] = r.parameterization[i];
  out.support = r.encode;
  return out;
}

struct MeshBvh::Impl {
  std::shared_ptr<Bvh> model;
  std::shared_ptr<fcl::Sphered> probe;
};

MeshBvh::MeshBvh(const std::vector<Eigen::Vector3d>& vertices,
                 const std::vector<Eigen::Vector3i>& triangles)
    : impl_(std::make_unique<Impl>()) {
  impl_->model = std::make_shared<Bvh>();
  std::vector<fcl::Triangle> tris;
  tris.reserve(triangles.size());
  for (const auto& t : triangles) tris.emplace_back(t.x(), t.y(), t.z());
  impl_->model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  impl_->model->addSubModel(vertices, tris);
  impl_->model->endModel();
  impl_->model->computeLocalAABB();
  // a point probe: FCL measures distance between geometries, so the point is a tiny sphere
  // whose radius is added back to the distance
  impl_->probe = std::make_shared<fcl::Sphered>(1e-9);
}

MeshBvh::~MeshBvh() = default;
MeshBvh::MeshBvh(MeshBvh&&) noexcept = default;
MeshBvh& MeshBvh::operator=(MeshBvh&&) noexcept = default;

double MeshBvh::closest_point(const Eigen::Vector3d& p, Eigen::Vector3d& closest,
                              int& triangle) const {
  fcl::CollisionObjectd mesh(impl_->model, fcl::Transform3d::Identity());
  fcl::Transform3d X;
  X.setIdentity();
  X.translation() = p;
  fcl::CollisionObjectd point(impl_->probe, X);
  fcl::DistanceRequestd request(true);  // nearest points
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResultd result;
  // FCL orders mesh-shape pairs mesh first: b1 is the triangle, nearest_points[0] on it
  fcl::distance(&mesh, &point, request, result);
  closest = result.nearest_points[0];
  triangle = static_cast<int>(result.b1);
  return std::max(0.0, result.min_distance + impl_->probe->radius);
}

}  // namespace kneesim::engine
