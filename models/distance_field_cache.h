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
// There is no on-disk cache yet: it would beat rebuilding for one-shot runs of one implant
// (the default femur's fine field builds in ~0.4 s CPU, stores 3.9 MB), but a comparison,
// diagnosis or study in one process already pays the build once (docs/performance.md).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "engine/sdf.h"

namespace kneesim::models {

// the field of this mesh (metres, F frame) at spacing and band [m]: built on first use
engine::SignedDistanceField find_or_make_distance_field(
    const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
    double spacing, double band);

// fields this process has built so far (tests: a second Model must not build again)
long count_distance_field_builds();

}  // namespace kneesim::models
