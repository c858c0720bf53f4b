#include "engine/solid/surface_contact.h"

#include <algorithm>
#include <map>

#include <Eigen/Geometry>

namespace kneesim::engine::solid {

SurfaceContact make_surface_contact(const SolidModel& model,
                                    const std::vector<std::array<int, 4>>& faces,
                                    const std::vector<int>& face_element, double friction,
                                    double slip_regularization) {
  // tributary area and the shortest element height of each surface node
  std::map<int, std::pair<double, double>> per_node;  // node -> (area, length), ascending
  for (size_t f = 0; f < faces.size(); ++f) {
    const auto& q = faces[f];
    const Eigen::Vector3d* x[4];
    for (int a = 0; a < 4; ++a) x[a] = &model.reference_positions[q[a]];
    const double area = 0.5 * (*x[2] - *x[0]).cross(*x[3] - *x[1]).norm();
    const double length = model.reference[face_element[f]].characteristic_length;
    for (int a = 0; a < 4; ++a) {
      auto [it, fresh] = per_node.try_emplace(q[a], 0.0, length);
      it->second.first += 0.25 * area;
      it->second.second = std::min(it->second.second, length);
    }
  }
  SurfaceContact c;
  c.friction = friction;
  c.slip_regularization = slip_regularization;
  const double modulus = model.material.dilatational_modulus();
  c.index_of_node.assign(model.num_nodes(), -1);
  for (const auto& [node, al] : per_node) {
    c.index_of_node[node] = static_cast<int>(c.nodes.size());
    c.nodes.push_back(node);
    c.area.push_back(al.first);
    c.stiffness.push_back(modulus * al.first / al.second);
  }
  return c;
}

SurfaceContactData make_surface_contact_data(const SurfaceContact& contact) {
  SurfaceContactData d;
  const int n = contact.size();
  d.pressure.assign(n, 0.0);
  d.force.assign(n, Eigen::Vector3d::Zero());
  d.friction_force.assign(n, Eigen::Vector3d::Zero());
  d.body_velocity.assign(n, Eigen::Vector3d::Zero());
  d.position.assign(n, Eigen::Vector3d::Zero());
  d.wake_at.assign(n, 0.0);
  d.sleep_scale.assign(n, 1.0);
  d.checked_position.assign(n, Eigen::Vector3d::Zero());
  d.slip_speed.assign(n, 0.0);
  return d;
}

}  // namespace kneesim::engine::solid
