#include "models/tri_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace kneesim::models {
namespace {

// an undirected edge key and whether the triangle traverses it from low to high index
struct EdgeUse {
  std::uint64_t key;  // (low << 32) | high
  bool forward;       // a -> b with a < b
};

std::vector<EdgeUse> edge_uses(const TriMesh& m) {
  std::vector<EdgeUse> e;
  e.reserve(m.triangles.size() * 3);
  for (const Eigen::Vector3i& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = static_cast<std::uint32_t>(t[k]);
      const std::uint32_t b = static_cast<std::uint32_t>(t[(k + 1) % 3]);
      if (a == b) continue;
      const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
      e.push_back({(lo << 32) | hi, a < b});
    }
  }
  std::sort(e.begin(), e.end(), [](const EdgeUse& x, const EdgeUse& y) { return x.key < y.key; });
  return e;
}

Eigen::Vector3d corner(const TriMesh& m, int tri, int k) { return m.vertices[m.triangles[tri][k]]; }

}  // namespace

std::vector<Eigen::Vector3d> face_normals(const TriMesh& m) {
  std::vector<Eigen::Vector3d> n(m.triangles.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const int t = static_cast<int>(i);
    const Eigen::Vector3d c =
        (corner(m, t, 1) - corner(m, t, 0)).cross(corner(m, t, 2) - corner(m, t, 0));
    const double len = c.norm();
    n[i] = len > 0.0 ? Eigen::Vector3d(c / len) : Eigen::Vector3d::Zero();
  }
  return n;
}

std::vector<double> face_areas(const TriMesh& m) {
  std::vector<double> a(m.triangles.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const int t = static_cast<int>(i);
    a[i] =
        0.5 * (corner(m, t, 1) - corner(m, t, 0)).cross(corner(m, t, 2) - corner(m, t, 0)).norm();
  }
  return a;
}

double surface_area(const TriMesh& m) {
  double s = 0.0;
  for (double a : face_areas(m)) s += a;
  return s;
}

std::vector<Eigen::Vector3d> vertex_normals(const TriMesh& m) {
  std::vector<Eigen::Vector3d> n(m.vertices.size(), Eigen::Vector3d::Zero());
  const std::vector<Eigen::Vector3d> fn = face_normals(m);
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    // each corner adds the face normal weighted by its interior angle
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = m.vertices[m.triangles[i][k]];
      const Eigen::Vector3d u = m.vertices[m.triangles[i][(k + 1) % 3]] - p;
      const Eigen::Vector3d v = m.vertices[m.triangles[i][(k + 2) % 3]] - p;
      const double angle = std::atan2(u.cross(v).norm(), u.dot(v));
      n[m.triangles[i][k]] += angle * fn[i];
    }
  }
  for (Eigen::Vector3d& v : n) {
    const double len = v.norm();
    if (len > 0.0) v /= len;
  }
  return n;
}

double enclosed_volume(const TriMesh& m) {
  // sum of signed tetrahedra to the origin (divergence theorem)
  double v6 = 0.0;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const int t = static_cast<int>(i);
    v6 += corner(m, t, 0).dot(corner(m, t, 1).cross(corner(m, t, 2)));
  }
  return v6 / 6.0;
}

Eigen::Vector3d enclosed_centroid(const TriMesh& m) {
  double v6 = 0.0;
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const int t = static_cast<int>(i);
    const Eigen::Vector3d a = corner(m, t, 0), b = corner(m, t, 1), c = corner(m, t, 2);
    const double d = a.dot(b.cross(c));
    v6 += d;
    s += d * (a + b + c) / 4.0;
  }
  return v6 != 0.0 ? Eigen::Vector3d(s / v6) : Eigen::Vector3d::Zero();
}

MeshCheck check_mesh(const TriMesh& m) {
  MeshCheck c;
  c.n_vertices = static_cast<int>(m.vertices.size());
  c.n_triangles = static_cast<int>(m.triangles.size());
  std::vector<char> used(m.vertices.size(), 0);
  TriMesh valid;
  valid.vertices = m.vertices;
  for (const Eigen::Vector3i& t : m.triangles) {
    if (t.minCoeff() < 0 || t.maxCoeff() >= c.n_vertices) {
      ++c.bad_indices;
      continue;
    }
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
    valid.triangles.push_back(t);
  }
  // zero area covers repeated indices as well
  for (double a : face_areas(valid)) c.degenerate_faces += a <= 0.0 ? 1 : 0;
  c.unused_vertices = static_cast<int>(std::count(used.begin(), used.end(), 0));
  // count the uses of each undirected edge
  const std::vector<EdgeUse> e = edge_uses(valid);
  for (std::size_t i = 0; i < e.size();) {
    std::size_t j = i;
    int fwd = 0;
    while (j < e.size() && e[j].key == e[i].key) fwd += e[j++].forward ? 1 : 0;
    const std::size_t uses = j - i;
    if (uses == 1) ++c.boundary_edges;
    if (uses > 2) ++c.nonmanifold_edges;
    if (uses == 2 && fwd != 1) ++c.inconsistent_edges;
    i = j;
  }
  return c;
}

Eigen::AlignedBox3d bounding_box(const TriMesh& m) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : m.vertices) box.extend(v);
  return box;
}

EdgeStats edge_length_stats(const TriMesh& m) {
  EdgeStats s;
  const std::vector<EdgeUse> e = edge_uses(m);
  double sum = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (i > 0 && e[i].key == e[i - 1].key) continue;
    const int a = static_cast<int>(e[i].key >> 32);
    const int b = static_cast<int>(e[i].key & 0xffffffffu);
    const double len = (m.vertices[a] - m.vertices[b]).norm();
    s.min_m = s.count == 0 ? len : std::min(s.min_m, len);
    s.max_m = std::max(s.max_m, len);
    sum += len;
    ++s.count;
  }
  s.mean_m = s.count > 0 ? sum / s.count : 0.0;
  return s;
}

TriMesh transformed(const TriMesh& m, const Eigen::Isometry3d& X) {
  TriMesh out = m;
  for (Eigen::Vector3d& v : out.vertices) v = X * v;
  return out;
}

TriMesh flipped(const TriMesh& m) {
  TriMesh out = m;
  for (Eigen::Vector3i& t : out.triangles) std::swap(t[1], t[2]);
  return out;
}

TriMesh mirrored_z(const TriMesh& m) {
  TriMesh out = flipped(m);
  for (Eigen::Vector3d& v : out.vertices) v.z() = -v.z();
  return out;
}

void append(TriMesh& a, const TriMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const Eigen::Vector3i& t : b.triangles) {
    a.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
}

SubMesh submesh(const TriMesh& m, const std::function<bool(int)>& keep) {
  SubMesh s;
  s.parent_to_vertex.assign(m.vertices.size(), -1);
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    if (!keep(static_cast<int>(i))) continue;
    Eigen::Vector3i t;
    for (int k = 0; k < 3; ++k) {
      const int p = m.triangles[i][k];
      if (s.parent_to_vertex[p] < 0) {
        s.parent_to_vertex[p] = static_cast<int>(s.mesh.vertices.size());
        s.mesh.vertices.push_back(m.vertices[p]);
        s.vertex_to_parent.push_back(p);
      }
      t[k] = s.parent_to_vertex[p];
    }
    s.mesh.triangles.push_back(t);
    s.triangle_to_parent.push_back(static_cast<int>(i));
  }
  return s;
}

}  // namespace kneesim::models
