// The femoral distance field depends only on the femoral mesh and the field's spacing and band:
// not on the material, rig, gait, insert or wear state. Building it is most of a Model build
// (docs/performance.md), so a process builds each distinct field once and every Model built
// from the same femur shares it const (engine/sdf.h: a field is a value with shared storage):
// the conditions of a diagnosis, the materials of `kneesim compare`, the wear updates and the
// trials of a study. A key is the mesh content itself (vertices and triangles compared in
// full, not a hash, so two meshes can never be confused) and the two parameters. Concurrent
// builders of one key wait for the first instead of building it twice. The last few fields
// stay cached; older ones live as long as a Model holds them.
//
// Below this in-process cache lies a disk cache (models/distance_field_disk.h): a process that
// has not built a field yet reads it from there when an earlier run stored it, so a one-shot
// run of an implant built before does not pay the build.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "engine/sdf.h"

namespace kneesim::models {

// the field of this mesh (metres, F frame) at spacing and band [m]: built on first use
engine::SignedDistanceField find_or_make_distance_field(
    const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
    double spacing, double band);

// fields this process has built so far (tests: a second Model must not build again), and
// fields it has read from the disk cache instead
long count_distance_field_builds();
long count_distance_field_reads();

}  // namespace kneesim::models
