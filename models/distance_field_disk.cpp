#include "models/distance_field_disk.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/io/atomic_file.h"

namespace kneesim::models {
namespace {

// format: magic (8 bytes, the last two the version), then the fields below in native byte
// order, then the FNV-1a hash of everything before it
constexpr char kMagic[8] = {'K', 'N', 'S', 'D', 'F', '\0', '0', '1'};

uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

template <class T>
void put(std::string& out, const T* data, size_t n) {
  out.append(reinterpret_cast<const char*>(data), n * sizeof(T));
}

// reads in order from a byte string; ok() turns false at the first read past the end
class Reader {
 public:
  Reader(const std::string& bytes, size_t end) : bytes_(bytes), end_(end) {}
  template <class T>
  bool get(T* data, size_t n) {
    if (!ok_ || n > (end_ - pos_) / sizeof(T)) return ok_ = false;
    std::memcpy(data, bytes_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return true;
  }
  template <class T>
  T get() {
    T v{};
    get(&v, 1);
    return v;
  }
  bool ok() const { return ok_; }
  bool at_end() const { return pos_ == end_; }

 private:
  const std::string& bytes_;
  size_t end_, pos_ = sizeof kMagic;
  bool ok_ = true;
};

}  // namespace

std::filesystem::path find_field_cache_dir() {
  if (const char* dir = std::getenv("KNEESIM_CACHE_DIR")) {
    if (*dir == '\0' || std::string(dir) == "off") return {};
    return dir;
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return std::filesystem::path(xdg) / "kneesim";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".cache" / "kneesim";
  }
  return {};
}

std::filesystem::path field_file_name(const std::vector<Eigen::Vector3d>& vertices,
                                      const std::vector<Eigen::Vector3i>& triangles,
                                      double spacing, double band) {
  uint64_t h = fnv1a(kMagic, sizeof kMagic);
  h = fnv1a(vertices.data(), vertices.size() * sizeof(Eigen::Vector3d), h);
  h = fnv1a(triangles.data(), triangles.size() * sizeof(Eigen::Vector3i), h);
  h = fnv1a(&spacing, sizeof spacing, h);
  h = fnv1a(&band, sizeof band, h);
  char name[64];
  std::snprintf(name, sizeof name, "femur-field-%016llx.sdf", static_cast<unsigned long long>(h));
  return name;
}

void write_field_file(const std::filesystem::path& path,
                      const std::vector<Eigen::Vector3d>& vertices,
                      const std::vector<Eigen::Vector3i>& triangles,
                      const engine::SignedDistanceField& field) {
  const engine::SignedDistanceField::Storage& st = *field.storage;
  std::string out(kMagic, sizeof kMagic);
  const uint64_t sizes[4] = {vertices.size(), triangles.size(), st.brick_of.size(),
                             st.values.size()};
  put(out, sizes, 4);
  put(out, vertices.data(), vertices.size());
  put(out, triangles.data(), triangles.size());
  put(out, &field.spacing, 1);
  put(out, &field.band, 1);
  put(out, field.origin.data(), 3);
  put(out, field.dims.data(), 3);
  put(out, field.bricks.data(), 3);
  put(out, st.brick_of.data(), st.brick_of.size());
  put(out, st.values.data(), st.values.size());
  const uint64_t hash = fnv1a(out.data(), out.size());
  put(out, &hash, 1);
  io::write_file_atomic(path, out);
}

std::optional<engine::SignedDistanceField> read_field_file(
    const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& vertices,
    const std::vector<Eigen::Vector3i>& triangles, double spacing, double band) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  if (bytes.size() < sizeof kMagic + sizeof(uint64_t) ||
      std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    return std::nullopt;
  }
  const size_t body = bytes.size() - sizeof(uint64_t);
  uint64_t stored;
  std::memcpy(&stored, bytes.data() + body, sizeof stored);
  if (fnv1a(bytes.data(), body) != stored) return std::nullopt;

  Reader r(bytes, body);
  uint64_t sizes[4];
  r.get(sizes, 4);
  if (!r.ok() || sizes[0] != vertices.size() || sizes[1] != triangles.size()) return std::nullopt;
  // the mesh and the parameters, compared in full: the file name's hash only says where to look
  std::vector<Eigen::Vector3d> v(vertices.size());
  std::vector<Eigen::Vector3i> t(triangles.size());
  r.get(v.data(), v.size());
  r.get(t.data(), t.size());
  engine::SignedDistanceField f;
  r.get(&f.spacing, 1);
  r.get(&f.band, 1);
  if (!r.ok() || f.spacing != spacing || f.band != band ||
      std::memcmp(v.data(), vertices.data(), v.size() * sizeof v[0]) != 0 ||
      std::memcmp(t.data(), triangles.data(), t.size() * sizeof t[0]) != 0) {
    return std::nullopt;
  }
  r.get(f.origin.data(), 3);
  r.get(f.dims.data(), 3);
  r.get(f.bricks.data(), 3);
  if (!r.ok()) return std::nullopt;
  // the grid's consistency: bricks cover the cells, one brick_of entry per brick, whole bricks
  // of values, every index in range
  long n_bricks = 1;
  for (int a = 0; a < 3; ++a) {
    if (f.dims[a] < 2 || f.dims[a] > (1 << 20) ||
        f.bricks[a] != (f.dims[a] - 1 + engine::kBrickCells - 1) / engine::kBrickCells) {
      return std::nullopt;
    }
    n_bricks *= f.bricks[a];
  }
  if (static_cast<long>(sizes[2]) != n_bricks || sizes[3] % engine::kBrickSize != 0 ||
      sizes[3] / engine::kBrickSize > sizes[2]) {
    return std::nullopt;
  }
  auto st = std::make_shared<engine::SignedDistanceField::Storage>();
  st->brick_of.resize(sizes[2]);
  st->values.resize(sizes[3]);
  r.get(st->brick_of.data(), st->brick_of.size());
  r.get(st->values.data(), st->values.size());
  if (!r.ok() || !r.at_end()) return std::nullopt;
  const long stored_bricks = static_cast<long>(sizes[3] / engine::kBrickSize);
  for (const int32_t b : st->brick_of) {
    if (b != engine::kBrickOutside && b != engine::kBrickInside && (b < 0 || b >= stored_bricks)) {
      return std::nullopt;
    }
  }
  engine::make_brick_axes(f, *st);
  f.storage = std::move(st);
  return f;
}

}  // namespace kneesim::models
