// The distance field's disk cache (models/distance_field_disk.h). References:
//  - a written and re-read field equals the built one bit for bit (grid, brick table, values)
//    and samples identically;
//  - a file that is not a sound copy of exactly the requested field reads as "no field":
//    one flipped byte (content hash), a truncated file, the file of another mesh or another
//    spacing under the requested name, an empty file;
//  - through find_or_make_distance_field: a field stored by an earlier run is read, not built;
//    a corrupted file is replaced by a fresh build, after which it reads back sound; with the
//    cache off nothing is written.
// Each case uses a mesh of its own (the generic femur at a coarse facet size, moved by a
// distinct offset), so the process-wide in-memory cache never answers for the disk.
#include <doctest/doctest.h>

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "engine/io/atomic_file.h"
#include "models/distance_field_cache.h"
#include "models/distance_field_disk.h"
#include "models/generic_tkr.h"

using namespace kneesim;
namespace fs = std::filesystem;

namespace {

constexpr double kSpacing = 1e-3, kBand = 2e-3;

models::TriMesh femur_moved(double dx) {
  models::TriMesh femur = models::make_generic_femur(models::GenericTkrParams{}, 3e-3);
  for (auto& v : femur.vertices) v.x() += dx;
  return femur;
}

// a fresh folder for this test process, set as the cache folder while the object lives
struct CacheFolder {
  fs::path dir = fs::temp_directory_path() /
                 ("kneesim-field-cache-test-" + std::to_string(::getpid()));
  std::string saved;
  bool had = false;
  CacheFolder() {
    fs::remove_all(dir);
    if (const char* v = std::getenv("KNEESIM_CACHE_DIR")) {
      had = true;
      saved = v;
    }
    setenv("KNEESIM_CACHE_DIR", dir.c_str(), 1);
  }
  ~CacheFolder() {
    fs::remove_all(dir);
    if (had) {
      setenv("KNEESIM_CACHE_DIR", saved.c_str(), 1);
    } else {
      unsetenv("KNEESIM_CACHE_DIR");
    }
  }
};

bool same_field(const engine::SignedDistanceField& a, const engine::SignedDistanceField& b) {
  return a.dims == b.dims && a.bricks == b.bricks && a.origin == b.origin &&
         a.spacing == b.spacing && a.band == b.band &&
         a.storage->brick_of == b.storage->brick_of &&
         a.storage->values.size() == b.storage->values.size() &&
         std::memcmp(a.storage->values.data(), b.storage->values.data(),
                     a.storage->values.size() * sizeof(float)) == 0;
}

void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace

TEST_CASE("a field written to disk reads back bit-identical, and unsound files read as none") {
  const CacheFolder folder;
  const models::TriMesh femur = femur_moved(0.0);
  const engine::SignedDistanceField built =
      engine::make_signed_distance_field(femur.vertices, femur.triangles, kSpacing, kBand);
  const fs::path file =
      folder.dir / models::field_file_name(femur.vertices, femur.triangles, kSpacing, kBand);
  models::write_field_file(file, femur.vertices, femur.triangles, built);
  const auto read = models::read_field_file(file, femur.vertices, femur.triangles, kSpacing, kBand);
  REQUIRE(read.has_value());
  CHECK(same_field(built, *read));
  // the brick tables are rebuilt: samples agree everywhere in the grid
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int differ = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d g(u(rng) * (built.dims.x() - 1), u(rng) * (built.dims.y() - 1),
                            u(rng) * (built.dims.z() - 1));
    const Eigen::Vector3d p = built.origin + built.spacing * g;
    differ += built.sample(p) != read->sample(p);
  }
  CHECK(differ == 0);

  const std::string bytes = io::read_file(file);
  // one byte flipped in the middle of the values
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  write_bytes(file, flipped);
  CHECK(!models::read_field_file(file, femur.vertices, femur.triangles, kSpacing, kBand));
  // truncated
  write_bytes(file, bytes.substr(0, bytes.size() - 100));
  CHECK(!models::read_field_file(file, femur.vertices, femur.triangles, kSpacing, kBand));
  write_bytes(file, "");
  CHECK(!models::read_field_file(file, femur.vertices, femur.triangles, kSpacing, kBand));
  // a sound file of this mesh, asked for at another spacing or band
  write_bytes(file, bytes);
  CHECK(!models::read_field_file(file, femur.vertices, femur.triangles, 2 * kSpacing, kBand));
  CHECK(!models::read_field_file(file, femur.vertices, femur.triangles, kSpacing, 2 * kBand));
  // a sound file of another mesh under this name (as a hash collision would put it)
  const models::TriMesh other = femur_moved(1e-6);
  CHECK(!models::read_field_file(file, other.vertices, other.triangles, kSpacing, kBand));
  CHECK(models::read_field_file(file, femur.vertices, femur.triangles, kSpacing, kBand));
}

TEST_CASE("find_or_make_distance_field reads a stored field and replaces a corrupted one") {
  const CacheFolder folder;
  // stored by an "earlier run": read, not built
  const models::TriMesh a = femur_moved(2e-3);
  const engine::SignedDistanceField built =
      engine::make_signed_distance_field(a.vertices, a.triangles, kSpacing, kBand);
  models::write_field_file(folder.dir / models::field_file_name(a.vertices, a.triangles,
                                                                kSpacing, kBand),
                           a.vertices, a.triangles, built);
  long builds = models::count_distance_field_builds();
  long reads = models::count_distance_field_reads();
  const engine::SignedDistanceField got =
      models::find_or_make_distance_field(a.vertices, a.triangles, kSpacing, kBand);
  CHECK(models::count_distance_field_builds() == builds);
  CHECK(models::count_distance_field_reads() == reads + 1);
  CHECK(same_field(built, got));

  // a corrupted file: built again, and the file is sound afterwards
  const models::TriMesh b = femur_moved(3e-3);
  const fs::path file =
      folder.dir / models::field_file_name(b.vertices, b.triangles, kSpacing, kBand);
  write_bytes(file, "KNSDF\0\0\0 not a field");
  builds = models::count_distance_field_builds();
  reads = models::count_distance_field_reads();
  const engine::SignedDistanceField rebuilt =
      models::find_or_make_distance_field(b.vertices, b.triangles, kSpacing, kBand);
  CHECK(models::count_distance_field_builds() == builds + 1);
  CHECK(models::count_distance_field_reads() == reads);
  const auto reread = models::read_field_file(file, b.vertices, b.triangles, kSpacing, kBand);
  REQUIRE(reread.has_value());
  CHECK(same_field(rebuilt, *reread));
  // no temporary files left behind
  int files = 0;
  for (const auto& entry : fs::directory_iterator(folder.dir)) {
    files += 1;
    CHECK(entry.path().extension() == ".sdf");
  }
  CHECK(files == 2);
}

TEST_CASE("with the disk cache off nothing is written") {
  const CacheFolder folder;
  setenv("KNEESIM_CACHE_DIR", "off", 1);
  CHECK(models::find_field_cache_dir().empty());
  const models::TriMesh c = femur_moved(4e-3);
  const long builds = models::count_distance_field_builds();
  models::find_or_make_distance_field(c.vertices, c.triangles, kSpacing, kBand);
  CHECK(models::count_distance_field_builds() == builds + 1);
  CHECK(!fs::exists(folder.dir));
}
