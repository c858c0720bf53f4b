// The femoral distance field on disk, so that a one-shot run of an implant built before does not
// pay the build again (docs/performance.md: the default femur's fine field takes ~3.5 billion
// instructions to build and 3.9 MB to store; reading and checking the file takes milliseconds).
//
// A file holds one field with everything it was built from: the mesh (vertices and triangles,
// in full), the spacing and the band. Its name is a 64-bit FNV-1a hash of those, but a hash is
// only where to look: a file is used only when its mesh and parameters equal the request bit
// for bit, its content hash (the file's last 8 bytes) matches, and its grid is consistent
// (brick indices in range, sizes agreeing with the dimensions). Anything else - missing,
// truncated, corrupted, another format version, a hash collision - reads as "no field", and the
// caller builds it and writes the file again. Files are written atomically (temporary file,
// fsync, rename: io::write_file_atomic), so a reader never sees a partial file and concurrent
// writers of one key leave one complete file.
//
// Where: $KNEESIM_CACHE_DIR if set, else $XDG_CACHE_HOME/kneesim, else $HOME/.cache/kneesim;
// KNEESIM_CACHE_DIR=off (or an empty value) turns the cache off. The test suite runs with it
// off, except the cache's own tests, which use a folder of their own.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <vector>

#include "engine/sdf.h"

namespace kneesim::models {

// the cache folder, or an empty path when the cache is off
std::filesystem::path find_field_cache_dir();

// the file name of the field of this mesh and parameters (in the cache folder)
std::filesystem::path field_file_name(const std::vector<Eigen::Vector3d>& vertices,
                                      const std::vector<Eigen::Vector3i>& triangles,
                                      double spacing, double band);

// the field stored in `path` when it is a sound file of exactly this mesh and parameters
std::optional<engine::SignedDistanceField> read_field_file(
    const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& vertices,
    const std::vector<Eigen::Vector3i>& triangles, double spacing, double band);

// writes the field with its mesh atomically; throws std::runtime_error naming the path
void write_field_file(const std::filesystem::path& path,
                      const std::vector<Eigen::Vector3d>& vertices,
                      const std::vector<Eigen::Vector3i>& triangles,
                      const engine::SignedDistanceField& field);

}  // namespace kneesim::models
