// Geometry update of the worn insert (physics.md section 6): per-element wear depth is spread
// to the articular vertices with area weights, and those vertices recede along the inward
// normal of the articular surface. Area weighting keeps sum_v depth_v A_v = sum_e depth_e A_e,
// so the depth-integral volume is exactly the Archard volume; the enclosed-volume change of
// the closed mesh is the geometric check of it.
#pragma once

#include <vector>

#include "engine/model.h"
#include "models/tri_mesh.h"

namespace kneesim::wear {

// vertex depth [m] (per articular vertex) from element depth [m] (per articular element)
std::vector<double> spread_to_vertices(const engine::InsertSurface& surface,
                                       const std::vector<double>& element_depth);

// tributary area of each articular vertex [m^2]: a third of its elements' areas
std::vector<double> vertex_areas(const engine::InsertSurface& surface);

// unit outward normals of the articular vertices (angle-weighted over articular elements)
std::vector<Eigen::Vector3d> articular_vertex_normals(const engine::InsertSurface& surface);

struct RecessionResult {
  models::TriMesh insert;      // the receded mesh
  int inverted_faces = 0;      // faces whose normal turned by more than 90 deg or collapsed
};

// moves each articular vertex (index map into the insert mesh) by depth along -normal
RecessionResult recede(const models::TriMesh& insert, const std::vector<int>& vertex_to_insert,
                       const std::vector<Eigen::Vector3d>& normals,
                       const std::vector<double>& vertex_depth);

// faces of `after` whose normal reversed or whose area fell below 1 % of `before`
int count_inverted_faces(const models::TriMesh& before, const models::TriMesh& after);

}  // namespace kneesim::wear
