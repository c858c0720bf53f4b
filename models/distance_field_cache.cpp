#include "models/distance_field_cache.h"

#include <algorithm>
#include <cstring>
#include <future>
#include <list>
#include <mutex>

#include "models/distance_field_disk.h"

namespace kneesim::models {
namespace {

// fields kept after their last use; each is a few MB
constexpr size_t kCachedFields = 4;

struct Entry {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  double spacing = 0.0, band = 0.0;
  std::shared_future<engine::SignedDistanceField> field;
};

struct Cache {
  std::mutex mutex;
  std::list<Entry> entries;  // most recently used first
  long builds = 0;
  long reads = 0;
};

Cache& cache() {
  static Cache c;
  return c;
}

bool matches(const Entry& e, const std::vector<Eigen::Vector3d>& vertices,
             const std::vector<Eigen::Vector3i>& triangles, double spacing, double band) {
  return e.spacing == spacing && e.band == band && e.vertices.size() == vertices.size() &&
         e.triangles.size() == triangles.size() &&
         std::memcmp(e.vertices.data(), vertices.data(),
                     vertices.size() * sizeof(Eigen::Vector3d)) == 0 &&
         std::memcmp(e.triangles.data(), triangles.data(),
                     triangles.size() * sizeof(Eigen::Vector3i)) == 0;
}

// the field from the disk cache (models/distance_field_disk.h) when it holds a sound copy, else
// built and written there; a cache that cannot be written is no cache (the next run builds)
engine::SignedDistanceField read_or_make(Cache& c, const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<Eigen::Vector3i>& triangles,
                                         double spacing, double band) {
  const std::filesystem::path dir = find_field_cache_dir();
  const std::filesystem::path file =
      dir.empty() ? dir : dir / field_file_name(vertices, triangles, spacing, band);
  if (!file.empty()) {
    if (auto field = read_field_file(file, vertices, triangles, spacing, band)) {
      std::lock_guard<std::mutex> lock(c.mutex);
      ++c.reads;
      return *field;
    }
  }
  engine::SignedDistanceField field =
      engine::make_signed_distance_field(vertices, triangles, spacing, band);
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    ++c.builds;
  }
  if (!file.empty()) {
    try {
      write_field_file(file, vertices, triangles, field);
    } catch (const std::exception&) {
      // read-only or full disk: the run goes on with the field it built
    }
  }
  return field;
}

}  // namespace

engine::SignedDistanceField find_or_make_distance_field(
    const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
    double spacing, double band) {
  Cache& c = cache();
  std::shared_future<engine::SignedDistanceField> field;
  std::promise<engine::SignedDistanceField> promise;
  bool build = false;
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    const auto it = std::find_if(c.entries.begin(), c.entries.end(), [&](const Entry& e) {
      return matches(e, vertices, triangles, spacing, band);
    });
    if (it != c.entries.end()) {
      c.entries.splice(c.entries.begin(), c.entries, it);
      field = it->field;
    } else {
      field = promise.get_future().share();
      c.entries.push_front(Entry{vertices, triangles, spacing, band, field});
      if (c.entries.size() > kCachedFields) c.entries.pop_back();
      build = true;
    }
  }
  if (build) {
    try {
      promise.set_value(read_or_make(c, vertices, triangles, spacing, band));
    } catch (...) {
      // waiters see the error; the entry goes, so a later call tries again
      promise.set_exception(std::current_exception());
      std::lock_guard<std::mutex> lock(c.mutex);
      c.entries.remove_if(
          [&](const Entry& e) { return matches(e, vertices, triangles, spacing, band); });
      throw;
    }
  }
  // another thread may still be building it: wait (outside the lock)
  return field.get();
}

long count_distance_field_builds() {
  std::lock_guard<std::mutex> lock(cache().mutex);
  return cache().builds;
}

long count_distance_field_reads() {
  std::lock_guard<std::mutex> lock(cache().mutex);
  return cache().reads;
}

}  // namespace kneesim::models
