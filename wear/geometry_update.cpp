#include "wear/geometry_update.h"

#include <cmath>

namespace kneesim::wear {

std::vector<double> vertex_areas(const engine::InsertSurface& s) {
  std::vector<double> area(s.vertices_T.size(), 0.0);
  for (int e = 0; e < s.size(); ++e)
    for (int k = 0; k < 3; ++k) area[s.triangles[e][k]] += s.area[e] / 3.0;
  return area;
}

std::vector<double> spread_to_vertices(const engine::InsertSurface& s,
                                       const std::vector<double>& element_depth) {
  std::vector<double> volume(s.vertices_T.size(), 0.0);
  for (int e = 0; e < s.size(); ++e)
    for (int k = 0; k < 3; ++k) volume[s.triangles[e][k]] += element_depth[e] * s.area[e] / 3.0;
  const std::vector<double> area = vertex_areas(s);
  for (size_t v = 0; v < volume.size(); ++v) volume[v] = area[v] > 0.0 ? volume[v] / area[v] : 0.0;
  return volume;
}

std::vector<Eigen::Vector3d> articular_vertex_normals(const engine::InsertSurface& s) {
  std::vector<Eigen::Vector3d> n(s.vertices_T.size(), Eigen::Vector3d::Zero());
  for (int e = 0; e < s.size(); ++e) {
    const auto& t = s.triangles[e];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = s.vertices_T[t[(k + 1) % 3]] - s.vertices_T[t[k]];
      const Eigen::Vector3d b = s.vertices_T[t[(k + 2) % 3]] - s.vertices_T[t[k]];
      const double angle = std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
      n[t[k]] += angle * s.normal_T[e];
    }
  }
  for (auto& v : n) {
    const double len = v.norm();
    if (len > 0.0) v /= len;
  }
  return n;
}

int count_inverted_faces(const models::TriMesh& before, const models::TriMesh& after) {
  int bad = 0;
  for (size_t f = 0; f < before.triangles.size(); ++f) {
    const auto& t = before.triangles[f];
    const Eigen::Vector3d n0 = (before.vertices[t[1]] - before.vertices[t[0]])
                                   .cross(before.vertices[t[2]] - before.vertices[t[0]]);
    const Eigen::Vector3d n1 = (after.vertices[t[1]] - after.vertices[t[0]])
                                   .cross(after.vertices[t[2]] - after.vertices[t[0]]);
    if (n0.dot(n1) <= 0.0 || n1.norm() < 0.01 * n0.norm()) ++bad;
  }
  return bad;
}

RecessionResult recede(const models::TriMesh& insert, const std::vector<int>& vertex_to_insert,
                       const std::vector<Eigen::Vector3d>& normals,
                       const std::vector<double>& vertex_depth) {
  RecessionResult r;
  r.insert = insert;
  for (size_t v = 0; v < vertex_to_insert.size(); ++v) {
    r.insert.vertices[vertex_to_insert[v]] -= vertex_depth[v] * normals[v];
  }
  r.inverted_faces = count_inverted_faces(insert, r.insert);
  return r;
}

}  // namespace kneesim::wear
