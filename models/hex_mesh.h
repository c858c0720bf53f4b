// Structured hexahedral meshes for the deformable solid (engine/solid): a box (block-on-ring
// block, tests, benchmarks) and an insert meshed from its articular surface.
//
// Insert meshing: the top of the insert is a height field over its footprint (the articular
// dishes, the eminence and the rim all face up), so the solid is a structured grid of columns:
// a grid over the x-z footprint (x anterior, z lateral in T: regular, or refined where the
// contact is and growing away from it, make_refined_lines), a
// vertical ray at each grid point finds the top surface (the highest hit on the closed insert
// mesh), and each column from the base plane y = base_y up to that height is split into
// `layers` elements graded towards the surface (the top layer `grading` times the bottom
// one's thickness, geometric in between). Grid cells with a corner outside the footprint are
// left out, so the outline is stair-stepped by at most one element. Rejected: an unstructured
// hex mesher (no Debian package) and extruding the articular triangles into wedges (poor
// explicit elements). Steep walls (the eminence's sides) are captured at the grid spacing.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "models/tri_mesh.h"

namespace kneesim::models {

struct HexMesh {
  std::vector<Eigen::Vector3d> nodes;         // [m]
  std::vector<std::array<int, 8>> elements;   // node ids, hex8 order (engine/solid/hex8.h)
  // the top surface (+y): quads of node ids counter-clockwise seen from above, and the
  // element under each quad
  std::vector<std::array<int, 4>> top_faces;
  std::vector<int> top_face_element;
  std::vector<int> base_nodes;                // nodes on the base plane (tied to the tray)
  // structured index of a box mesh: node (i, j, k) at i + (nx+1)(j + (ny+1) k); j counts up
  int nx = 0, ny = 0, nz = 0;                 // elements per direction (box meshes)
  int node(int i, int j, int k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
};

// the box [origin, origin + size] [m] split into nx x ny x nz equal elements; its top is the
// y = max face and its base the y = min face
HexMesh make_box_hex_mesh(int nx, int ny, int nz, const Eigen::Vector3d& size,
                          const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

// a box with the given grid lines along x, y and z [m] (strictly increasing, two or more
// each): graded meshes, fine where a contact is; top and base as make_box_hex_mesh
HexMesh make_graded_box_hex_mesh(const std::vector<double>& xs, const std::vector<double>& ys,
                                 const std::vector<double>& zs);

// grid lines from a to b [m]: spacing `fine` within |v - centre| <= half_width, growing by
// `ratio` per element beyond it (the last spacing stretched to end exactly at a or b)
std::vector<double> make_graded_lines(double a, double b, double centre, double half_width,
                                      double fine, double ratio);

// an interval [lo, hi] of a coordinate [m]
struct Interval {
  double lo = 0.0, hi = 0.0;
};

// grid lines from a to b [m] (a < b) with spacing `fine` inside the intervals and growing
// away from them, the spacing s(v) = min(coarse, fine + (growth - 1) d(v)) at a distance d(v)
// from the nearest interval (a geometric growth by `growth` per element, capped at `coarse`);
// the lines divide the integral of 1/s into whole cells, so the spacing is within rounding of
// s(v) and the grid ends exactly at a and b. No interval, or coarse = fine: the uniform grid
// of `coarse` (a whole number of cells, the nearest to (b - a) / coarse).
std::vector<double> make_refined_lines(double a, double b, const std::vector<Interval>& fine_zone,
                                       double fine, double coarse, double growth);

struct InsertMeshOptions {
  double element_size = 1e-3;  // grid spacing over the footprint [m], > 0; in the refined
                               // zone when there is one (along x, and z unless given below)
  double element_size_z = 0.0; // refined spacing along z [m]; 0: element_size
  int layers = 4;              // elements through the thickness, >= 1
  double grading = 0.5;        // top layer thickness / bottom layer thickness, > 0
  // refinement (make_refined_lines): spacing element_size over the intervals of x and of z
  // given (a tensor-product zone), growing by `growth` per element to outer_element_size
  // outside; no intervals or outer_element_size <= element_size: the uniform grid
  double outer_element_size = 0.0;   // [m]
  double growth = 1.3;               // [-], >= 1
  std::vector<Interval> refine_x, refine_z;  // [m], T frame
};

// the hex mesh of a closed insert (frame T, base plane y = base_y); throws InputError for
// options out of range, an insert that covers no grid cell, or a column whose top is not above
// the base (zero or negative layer thickness, naming x and z)
HexMesh make_insert_hex_mesh(const TriMesh& insert, double base_y, const InsertMeshOptions& options);

}  // namespace kneesim::models
