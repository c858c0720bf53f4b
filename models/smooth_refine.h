// Smooth refinement of a coarse triangle surface (implant.mesh.femur_refine_mm).
//
// Why: an imported implant comes as its CAD export's triangles; the Grand Challenge DM femoral
// component's are 1.2 mm across, whose chords lie up to e^2 / (8 R) inside the true arcs
// (9 µm at R = 20 mm). A stiff insert's elastic approach is a few tens of µm, and once the
// deformable insert's elements are finer than a facet the pressure follows the facet ridges
// and the peak does not converge (docs/validation.md, mesh convergence).
//
// What: midpoint subdivision (each triangle into four, per level) whose new edge points are
// placed on a smooth surface through the old vertices: Phong tessellation (Boubekeur & Alexa
// 2008) at the edge midpoint, p* = (1 - a) m + a (pi_i(m) + pi_j(m)) / 2, with m the chord's
// midpoint and pi_k the projection onto vertex k's tangent plane. With a = 1/2 and exact
// normals the point lies on the circular arc through the two vertices to fourth order in the
// arc's angle (the chord's midpoint is off by R th^2 / 8 for an arc of angle th); with the
// mesh's averaged vertex normals the error falls at least as the cube of the edge: on a
// sphere of 17 / 9 / 4 deg edges 18 / 61 / 106 times below the chord's (smooth_refine_test). The new point's normal is
// the normalized mean of the endpoints'. Vertices never move. An edge whose two faces meet at
// more than feature_angle (the component's box cuts, rims, the posterior chamfers) is a
// feature: its midpoint stays on the chord, and the vertex normals are averaged over the faces
// on one side of the features only (per-corner normals), so flat faces stay flat and sharp
// edges sharp. Each new edge point depends on its two endpoints alone, so a watertight mesh
// stays watertight.
#pragma once

#include "models/tri_mesh.h"

namespace kneesim::models {

struct SmoothRefineOptions {
  int levels = 1;                    // midpoint subdivisions (each quarters the triangles)
  double feature_angle_deg = 30.0;   // dihedral angle above which an edge stays sharp [deg]
  double phong_shape = 0.5;          // a: 0 flat, 1/2 arcs to fourth order
};

TriMesh refine_smooth(const TriMesh& mesh, const SmoothRefineOptions& options);

// the levels that bring the median edge to at most target_m [m] (0 when it already is)
int find_refine_levels(const TriMesh& mesh, double target_m);

}  // namespace kneesim::models
