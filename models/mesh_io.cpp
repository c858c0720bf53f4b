#include "models/mesh_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <assimp/Importer.hpp>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <cstdlib>
#include <sstream>
#include <random>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "engine/errors.h"

namespace kneesim::models {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw InputError(file.string() + ": " + what);
}

// the bit pattern of a float position (-0 folded into +0), for exact welding
struct PositionKey {
  std::array<std::uint32_t, 3> bits;  // IEEE bits of x, y, z
  bool operator==(const PositionKey& o) const { return bits == o.bits; }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};
PositionKey position_key(const aiVector3D& v) {
  PositionKey k;
  const float f[3] = {v.x + 0.0f, v.y + 0.0f, v.z + 0.0f};
  std::memcpy(k.bits.data(), f, sizeof f);
  return k;
}

// collects every triangle of every mesh of the scene (node transforms already applied)
TriMesh gather_and_weld(const aiScene& scene) {
  TriMesh m;
  std::unordered_map<PositionKey, int, PositionHash> index;  // exact position -> welded vertex
  for (unsigned k = 0; k < scene.mNumMeshes; ++k) {
    const aiMesh& mesh = *scene.mMeshes[k];
    std::vector<int> welded(mesh.mNumVertices);
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& v = mesh.mVertices[i];
      auto [it, inserted] = index.emplace(position_key(v), static_cast<int>(m.vertices.size()));
      if (inserted) m.vertices.emplace_back(v.x, v.y, v.z);
      welded[i] = it->second;
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by Triangulate
      m.triangles.emplace_back(welded[face.mIndices[0]], welded[face.mIndices[1]],
                               welded[face.mIndices[2]]);
    }
  }
  return m;
}

// every file coordinate finite and, in metres, within kMaxCoordinate_m: a NaN or 1e30 vertex
// would otherwise reach the distance field (a grid sized by the bounding box) or be dropped
// silently with its faces
void check_coordinates(const std::filesystem::path& file, const TriMesh& m, double scale,
                       const std::string& units) {
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double v = m.vertices[i][k];
      const char axis = static_cast<char>('x' + k);
      if (!std::isfinite(v)) {
        fail(file, "vertex " + std::to_string(i) + " has " + axis + " = " + std::to_string(v) +
                       "; every coordinate must be a finite number.");
      }
      if (std::abs(v * scale) > kMaxCoordinate_m) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "vertex %zu has %c = %g %s, implausibly far for a knee implant; "
                      "coordinates must lie within +-%g m (check implant.mesh.units).",
                      i, axis, v, units.c_str(), kMaxCoordinate_m);
        fail(file, buf);
      }
    }
  }
}

void put_f32(std::string& out, double v) {
  const float f = static_cast<float>(v);
  char b[4];
  std::memcpy(b, &f, 4);
  out.append(b, 4);
}

// a face with no index or an index beyond its mesh's vertices (a truncated or inconsistent
// file), as one sentence, or ""
std::string find_bad_face(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr) return "the file holds an empty mesh record (truncated or inconsistent).";
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr) {
        return "face " + std::to_string(f) + " has no vertex indices (is the file cut off?).";
      }
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          return "face " + std::to_string(f) + " refers to vertex " +
                 std::to_string(face.mIndices[k]) + " but the file holds " +
                 std::to_string(mesh->mNumVertices) + " vertices (is the file cut off?).";
        }
      }
    }
  }
  return "";
}

// assimp 5.2 (Debian 12) reads a PLY file whose header has no end_header line forever
// (fuzz_mesh: tests/fuzz/regressions/mesh/hang_assimp_ply_no_end_header.bin did not return in
// 120 s; hang_assimp_ply_cend_header.bin has "cend_header" instead): a file named .ply or
// starting with the PLY magic must close its header with a line that is exactly end_header
// within its first 64 kB (real headers take a few hundred bytes) before assimp sees it
void check_ply_header(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(65536, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".ply" && head.rfind("ply", 0) != 0) return;
  bool closed = false;
  for (size_t at = head.find("end_header"); at != std::string::npos && !closed;
       at = head.find("end_header", at + 1)) {
    const size_t after = at + 10;
    closed = at > 0 && head[at - 1] == '\n' &&
             (after == head.size() || head[after] == '\n' || head[after] == '\r');
  }
  if (!closed) {
    fail(file, "is not a complete PLY file: its header has no end_header line within the first "
               "64 kB.");
  }
}

// what assimp reports in its own words for files that are not what their name says: a file
// of another kind (an image, an archive, a PDF) under a mesh name, a binary STL whose size
// disagrees with its triangle count (cut off, or a count that was not written), and an OBJ
// face that names a vertex not defined: one sentence each, with the line for OBJ
void check_file_kind(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(512, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const struct {
    const char* magic;
    const char* kind;
  } kinds[] = {{"\x89PNG", "a PNG image"},      {"\xFF\xD8\xFF", "a JPEG image"},
               {"GIF8", "a GIF image"},         {"%PDF", "a PDF document"},
               {"PK\x03\x04", "a ZIP archive"}, {"\x1F\x8B", "a gzip archive"}};
  for (const auto& k : kinds) {
    if (head.rfind(k.magic, 0) == 0) {
      fail(file, std::string("is ") + k.kind + ", not a mesh; STL, OBJ and PLY are supported.");
    }
  }
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ext == ".stl" && !ec) {
    // ASCII STL starts with "solid" and is text; a binary one (which may also start with
    // "solid") has a zero byte by offset 83, the high byte of its triangle count
    const bool ascii = head.rfind("solid", 0) == 0 && head.find('\0') == std::string::npos;
    if (!ascii) {
      if (size < 84) {
        fail(file, "is too short for a binary STL (" + std::to_string(size) + " bytes; a "
                   "binary STL has an 84-byte header with its triangle count).");
      }
      std::uint32_t n = 0;
      std::memcpy(&n, head.data() + 80, 4);
      const std::uintmax_t expected = 84 + 50 * static_cast<std::uintmax_t>(n);
      if (size != expected) {
        fail(file, "is not a complete binary STL: its header counts " + std::to_string(n) +
                   " triangles, which take " + std::to_string(expected) + " bytes, but the "
                   "file has " + std::to_string(size) + " bytes (cut off, or a wrong count).");
      }
    }
  }
  if (ext == ".obj") {
    // OBJ indices are 1-based; negative ones count back from the last vertex defined
    in.clear();
    in.seekg(0);
    long vertices = 0, line_no = 0;
    std::string line;
    while (std::getline(in, line)) {
      ++line_no;
      if (line.rfind("v ", 0) == 0 || line.rfind("v\t", 0) == 0) {
        ++vertices;
      } else if (line.rfind("f ", 0) == 0 || line.rfind("f\t", 0) == 0) {
        std::istringstream words(line.substr(2));
        std::string word;
        while (words >> word) {
          char* end = nullptr;
          const long idx = std::strtol(word.c_str(), &end, 10);
          if (end == word.c_str()) continue;  // assimp reports what it cannot parse
          if (idx == 0 || idx > vertices || idx < -vertices) {
            fail(file, "line " + std::to_string(line_no) + ": face index " + std::to_string(idx) +
                       " names no vertex: " + std::to_string(vertices) + " vertices are defined "
                       "above it (allowed: 1 to " + std::to_string(vertices) + ", or -1 to -" +
                       std::to_string(vertices) + ").");
          }
        }
      }
    }
  }
}

}  // namespace

TriMesh load_mesh(const std::filesystem::path& file, const MeshImportOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    fail(file, "is a folder, not a mesh file; give an STL, OBJ or PLY file.");
  }
  if (!std::filesystem::is_regular_file(file, ec)) fail(file, "mesh file not found.");
  double scale = 1.0;
  if (options.units == "mm") {
    scale = 1e-3;
  } else if (options.units != "m") {
    fail(file, "units '" + options.units + "' are not allowed; use \"m\" or \"mm\".");
  }
  const Eigen::Matrix3d& R = options.rotation;
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-9 || R.determinant() < 0.0) {
    fail(file, "the import rotation is not a proper rotation matrix (orthonormal, det +1).");
  }

  check_ply_header(file);
  check_file_kind(file);
  // read with assimp, check the faces, then triangulate and flatten the node hierarchy: the
  // post-processing of assimp 5.2 (Debian 12) aborts the process (ai_assert in
  // TriangulateProcess) on faces without indices, e.g. a PLY cut off before its face list
  // (fuzz_mesh: tests/fuzz/regressions/mesh/abort_assimp_truncated_ply.bin)
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_COLORS);
  const aiScene* scene = importer.ReadFile(file.string(), 0);
  if (scene != nullptr) {
    if (const std::string why = find_bad_face(*scene); !why.empty()) fail(file, why);
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                         aiProcess_RemoveComponent | aiProcess_SortByPType);
  }
  if (scene == nullptr) {
    // assimp reports a well-formed file without faces as an error of its own
    const std::string why = importer.GetErrorString();
    if (why.find("No output meshes") != std::string::npos) fail(file, "the mesh has no triangles.");
    fail(file, "cannot be read as a mesh (assimp: " + why + "); STL, OBJ and PLY are supported.");
  }
  TriMesh m = gather_and_weld(*scene);
  if (m.triangles.empty()) fail(file, "the mesh has no triangles.");
  check_coordinates(file, m, scale, options.units);

  // units, rotation, mirror, translation
  for (Eigen::Vector3d& v : m.vertices) {
    v = R * (scale * v);
    if (options.mirror_z) v.z() = -v.z();
    v += options.translation_m;
  }
  if (options.mirror_z) m = flipped(m);

  if (options.require_closed) {
    const MeshCheck c = check_mesh(m);
    if (!c.closed()) {
      fail(file, "the mesh is not closed: " + std::to_string(c.boundary_edges) +
                     " open edges and " + std::to_string(c.nonmanifold_edges) +
                     " non-manifold edges; a closed manifold surface is required (or "
                     "implant.mesh.insert_closed = false, which gives no wear volume).");
    }
  }
  return m;
}

void save_mesh(const std::filesystem::path& file, const TriMesh& mesh) {
  // header, count, then per triangle: normal, three vertices, attribute word
  std::string out(80, '\0');
  const char title[] = "kneesim binary STL, metres";
  std::memcpy(out.data(), title, sizeof title - 1);
  const std::uint32_t n = static_cast<std::uint32_t>(mesh.triangles.size());
  out.append(reinterpret_cast<const char*>(&n), 4);
  const std::vector<Eigen::Vector3d> normals = face_normals(mesh);
  out.reserve(out.size() + 50 * static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) put_f32(out, normals[i][k]);
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) put_f32(out, mesh.vertices[mesh.triangles[i][c]][k]);
    }
    out.append(2, '\0');
  }

  // temporary file beside the target, then rename
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::random_device rd;
  const std::filesystem::path tmp = file.string() + ".tmp" + std::to_string(rd() % 1000000);
  {
    std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
    os.write(out.data(), static_cast<std::streamsize>(out.size()));
    os.flush();
    if (!os) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error(file.string() + ": cannot write the STL file.");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(file.string() + ": cannot move the written STL into place.");
  }
}

}  // namespace kneesim::models
