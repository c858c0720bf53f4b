#include "models/smooth_refine.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace kneesim::models {
namespace {

using Vec3 = Eigen::Vector3d;

uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<uint64_t>(std::min(a, b)), hi = static_cast<uint64_t>(std::max(a, b));
  return lo << 32 | hi;
}

struct Edge {
  int faces[2] = {-1, -1};
  int count = 0;
  bool feature = false;
  int midpoint = -1;
};

// the mesh's edges, each with its faces, in a map from the vertex pair
std::unordered_map<uint64_t, Edge> collect_edges(const TriMesh& m) {
  std::unordered_map<uint64_t, Edge> edges;
  edges.reserve(m.triangles.size() * 2);
  for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
    for (int k = 0; k < 3; ++k) {
      Edge& e = edges[edge_key(m.triangles[f][k], m.triangles[f][(k + 1) % 3])];
      if (e.count < 2) e.faces[e.count] = f;
      ++e.count;
    }
  }
  return edges;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// per-corner unit normals (3 per triangle): the angle-weighted mean of the face normals around
// the corner's vertex, over the faces reachable without crossing a feature edge
std::vector<Vec3> find_corner_normals(const TriMesh& m,
                                      const std::unordered_map<uint64_t, Edge>& edges) {
  const int n_faces = static_cast<int>(m.triangles.size());
  const std::vector<Vec3> fn = face_normals(m);
  std::vector<int> parent(3 * n_faces);
  std::iota(parent.begin(), parent.end(), 0);
  auto corner = [&](int f, int v) {
    for (int k = 0; k < 3; ++k) {
      if (m.triangles[f][k] == v) return 3 * f + k;
    }
    return -1;
  };
  for (const auto& [key, e] : edges) {
    if (e.feature || e.count != 2) continue;
    for (int v : {static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)}) {
      const int a = find_root(parent, corner(e.faces[0], v));
      const int b = find_root(parent, corner(e.faces[1], v));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<Vec3> sum(3 * n_faces, Vec3::Zero());
  for (int f = 0; f < n_faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = m.vertices[m.triangles[f][k]];
      const Vec3 u = (m.vertices[m.triangles[f][(k + 1) % 3]] - p).normalized();
      const Vec3 w = (m.vertices[m.triangles[f][(k + 2) % 3]] - p).normalized();
      const double angle = std::acos(std::clamp(u.dot(w), -1.0, 1.0));
      sum[find_root(parent, 3 * f + k)] += angle * fn[f];
    }
  }
  std::vector<Vec3> normals(3 * n_faces);
  for (int c = 0; c < 3 * n_faces; ++c) {
    const Vec3& s = sum[find_root(parent, c)];
    normals[c] = s.norm() > 0.0 ? Vec3(s.normalized()) : fn[c / 3];
  }
  return normals;
}

// the smooth point between vertices p_i, p_j with unit normals n_i, n_j (Phong tessellation at
// the edge midpoint)
Vec3 phong_midpoint(const Vec3& pi, const Vec3& pj, const Vec3& ni, const Vec3& nj, double a) {
  const Vec3 m = 0.5 * (pi + pj);
  const Vec3 proj_i = m - (m - pi).dot(ni) * ni;
  const Vec3 proj_j = m - (m - pj).dot(nj) * nj;
  return (1.0 - a) * m + a * 0.5 * (proj_i + proj_j);
}

}  // namespace

TriMesh refine_smooth(const TriMesh& mesh, const SmoothRefineOptions& options) {
  TriMesh m = mesh;
  if (options.levels <= 0 || m.triangles.empty()) return m;
  const double cos_feature = std::cos(options.feature_angle_deg * M_PI / 180.0);
  std::unordered_map<uint64_t, Edge> edges = collect_edges(m);
  {
    const std::vector<Vec3> fn = face_normals(m);
    for (auto& [key, e] : edges) {
      e.feature = e.count != 2 || fn[e.faces[0]].dot(fn[e.faces[1]]) < cos_feature;
    }
  }
  std::vector<Vec3> corner_normal = find_corner_normals(m, edges);
  for (int level = 0; level < options.levels; ++level) {
    // one new vertex per edge
    TriMesh next;
    next.vertices = m.vertices;
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
      for (int k = 0; k < 3; ++k) {
        const int i = m.triangles[f][k], j = m.triangles[f][(k + 1) % 3];
        Edge& e = edges[edge_key(i, j)];
        if (e.midpoint >= 0) continue;
        const Vec3 p = e.feature ? Vec3(0.5 * (m.vertices[i] + m.vertices[j]))
                                 : phong_midpoint(m.vertices[i], m.vertices[j],
                                                  corner_normal[3 * f + k],
                                                  corner_normal[3 * f + (k + 1) % 3],
                                                  options.phong_shape);
        e.midpoint = static_cast<int>(next.vertices.size());
        next.vertices.push_back(p);
      }
    }
    // four triangles per triangle, their corner normals, and the next level's edges (the halves
    // of a feature edge are features; the three inner edges are not)
    std::vector<Vec3> next_normal;
    next.triangles.reserve(4 * m.triangles.size());
    next_normal.reserve(12 * m.triangles.size());
    std::unordered_map<uint64_t, Edge> next_edges;
    next_edges.reserve(edges.size() * 4);
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
      int v[3], mid[3];
      Vec3 nv[3], nm[3];
      bool feature[3];
      for (int k = 0; k < 3; ++k) {
        v[k] = m.triangles[f][k];
        nv[k] = corner_normal[3 * f + k];
        const Edge& e = edges[edge_key(v[k], m.triangles[f][(k + 1) % 3])];
        mid[k] = e.midpoint;
        feature[k] = e.feature;
      }
      for (int k = 0; k < 3; ++k) nm[k] = (nv[k] + nv[(k + 1) % 3]).normalized();
      const int tri[4][3] = {{v[0], mid[0], mid[2]}, {mid[0], v[1], mid[1]},
                             {mid[2], mid[1], v[2]}, {mid[0], mid[1], mid[2]}};
      const Vec3 tri_n[4][3] = {{nv[0], nm[0], nm[2]}, {nm[0], nv[1], nm[1]},
                                {nm[2], nm[1], nv[2]}, {nm[0], nm[1], nm[2]}};
      for (int t = 0; t < 4; ++t) {
        const int face = static_cast<int>(next.triangles.size());
        next.triangles.emplace_back(tri[t][0], tri[t][1], tri[t][2]);
        for (int k = 0; k < 3; ++k) {
          next_normal.push_back(tri_n[t][k]);
          Edge& e = next_edges[edge_key(tri[t][k], tri[t][(k + 1) % 3])];
          if (e.count < 2) e.faces[e.count] = face;
          ++e.count;
        }
      }
      // the halves of the parent's edges inherit its feature flag
      for (int k = 0; k < 3; ++k) {
        if (!feature[k]) continue;
        next_edges[edge_key(v[k], mid[k])].feature = true;
        next_edges[edge_key(mid[k], v[(k + 1) % 3])].feature = true;
      }
    }
    m = std::move(next);
    edges = std::move(next_edges);
    corner_normal = std::move(next_normal);
  }
  return m;
}

int find_refine_levels(const TriMesh& mesh, double target_m) {
  std::vector<double> lengths;
  lengths.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      lengths.push_back((mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm());
    }
  }
  if (lengths.empty() || !(target_m > 0.0)) return 0;
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const double median = lengths[lengths.size() / 2];
  int levels = 0;
  for (double e = median; e > target_m; e *= 0.5) ++levels;
  return levels;
}

}  // namespace kneesim::models
