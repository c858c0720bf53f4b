// Mesh files: the single assimp adapter (design.md: each third-party library lives in one
// adapter file). Import reads STL (ascii/binary), OBJ and PLY through assimp, then welds
// vertices with identical coordinates ourselves: assimp's JoinIdenticalVertices also compares
// the per-face normals STL carries, so it leaves an STL solid as a soup of disconnected
// triangles. Export writes binary STL directly (a fixed 50-byte record per triangle), atomically.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "models/tri_mesh.h"

namespace kneesim::models {

struct MeshImportOptions {
  std::string units = "m";  // unit of the file's coordinates: "m" or "mm"
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();   // file axes -> project axes [-], 3x3
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();  // added after rotation [m], 3
  bool mirror_z = false;        // z -> -z after rotation (left knee -> right knee); winding kept
                                // outward
  bool require_closed = false;  // reject a mesh with open or non-manifold edges
};

// the largest coordinate magnitude accepted, in metres: ten times a body height, so that a
// mesh placed in a lab frame passes while a 1e30 or millimetre-declared-as-metre vertex fails
inline constexpr double kMaxCoordinate_m = 10.0;

// reads a triangle mesh and maps it into the project frame: p = rotation * scale * p_file,
// then z -> -z when mirror_z, then + translation_m. Throws InputError naming the file for a
// missing file, an unreadable or unsupported file, an empty mesh, a rotation that is not proper
// orthonormal, unknown units, a non-finite coordinate or one beyond kMaxCoordinate_m, and (when require_closed) a mesh with open edges, giving
// their count.
TriMesh load_mesh(const std::filesystem::path& file, const MeshImportOptions& options = {});

// writes a binary STL (float32 coordinates, face normals) atomically; creates parent folders;
// throws std::runtime_error naming the path when it cannot be written
void save_mesh(const std::filesystem::path& file, const TriMesh& mesh);

}  // namespace kneesim::models
