// Triangle surface meshes and pure helpers on them (normals, areas, enclosed volume, topology
// checks, transforms, sub-meshes). Plain arrays of fixed-size Eigen vectors: no half-edge
// structure, because the engine only reads meshes and the topology checks are a sort of the
// edge list (O(n log n), a few ms for the real implants).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

namespace kneesim::models {

struct TriMesh {
  std::vector<Eigen::Vector3d> vertices;   // [m], n_vertices
  std::vector<Eigen::Vector3i> triangles;  // vertex indices, counter-clockwise seen from outside
};

struct MeshCheck {
  int n_vertices = 0;          // [-]
  int n_triangles = 0;         // [-]
  int boundary_edges = 0;      // edges used by exactly one triangle [-]
  int nonmanifold_edges = 0;   // edges used by three or more triangles [-]
  int inconsistent_edges = 0;  // two-triangle edges traversed in the same direction by both [-]
  int degenerate_faces = 0;    // zero area or repeated vertex index [-]
  int unused_vertices = 0;     // vertices referenced by no triangle [-]
  int bad_indices = 0;         // triangle indices outside 0..n_vertices-1 [-]
  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0 && bad_indices == 0; }
  bool manifold() const { return nonmanifold_edges == 0 && bad_indices == 0; }
  bool consistently_oriented() const { return inconsistent_edges == 0; }
  // closed, manifold, consistently oriented, without degenerate faces
  bool watertight() const { return closed() && consistently_oriented() && degenerate_faces == 0; }
};

struct EdgeStats {
  double min_m = 0.0;   // shortest edge [m]
  double max_m = 0.0;   // longest edge [m]
  double mean_m = 0.0;  // mean over unique edges [m]
  int count = 0;        // unique edges [-]
};

struct SubMesh {
  TriMesh mesh;                         // the selected triangles with compacted vertices
  std::vector<int> vertex_to_parent;    // parent vertex index of each sub-mesh vertex, n_vertices
  std::vector<int> triangle_to_parent;  // parent triangle index of each sub-mesh triangle
  std::vector<int> parent_to_vertex;    // sub-mesh index of each parent vertex, or -1
};

// unit normal of each triangle (zero for a degenerate triangle), n_triangles
std::vector<Eigen::Vector3d> face_normals(const TriMesh& m);
// area of each triangle [m^2], n_triangles
std::vector<double> face_areas(const TriMesh& m);
double surface_area(const TriMesh& m);  // [m^2]
// unit vertex normals, each the angle-weighted sum of its triangles' normals, n_vertices
std::vector<Eigen::Vector3d> vertex_normals(const TriMesh& m);
// volume enclosed by a closed, outward-oriented mesh by the divergence theorem [m^3]
// (negative for an inward-oriented mesh)
double enclosed_volume(const TriMesh& m);
// centroid of the enclosed solid (uniform density) [m]
Eigen::Vector3d enclosed_centroid(const TriMesh& m);
MeshCheck check_mesh(const TriMesh& m);
Eigen::AlignedBox3d bounding_box(const TriMesh& m);  // [m]
EdgeStats edge_length_stats(const TriMesh& m);
// vertices mapped by X (orientation is kept: X must be a proper rigid motion)
TriMesh transformed(const TriMesh& m, const Eigen::Isometry3d& X);
// z -> -z with the triangle winding reversed, so an outward mesh stays outward
TriMesh mirrored_z(const TriMesh& m);
// every triangle with its winding reversed
TriMesh flipped(const TriMesh& m);
// appends b to a (vertex indices of b shifted)
void append(TriMesh& a, const TriMesh& b);
// the triangles for which keep(triangle index) is true, with their vertices renumbered
SubMesh submesh(const TriMesh& m, const std::function<bool(int)>& keep);

}  // namespace kneesim::models
