#include "wear/checkpoint.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <array>

#include "engine/errors.h"
#include "engine/io/atomic_file.h"

namespace kneesim::wear {
namespace {

// v6: records of 24 fields (v5: 22, without the creep depths; v4: 18, without the wear
// potential, sliding distance, cross-shear and stance pressure; v3: 16, without the energy
// ratios) and the deformable insert's state
constexpr char kMagic[16] = "kneesim-wear-v6";

class Writer {
 public:
  template <typename T>
  void put(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put_doubles(const double* p, size_t n) {
    bytes_.append(reinterpret_cast<const char*>(p), n * sizeof(double));
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  Reader(const std::string& bytes, const std::string& file) : b_(bytes), file_(file) {}
  template <typename T>
  T get() {
    T v;
    need(sizeof v);
    std::memcpy(&v, b_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  void get_doubles(double* p, size_t n) {
    // an empty list reads nothing: p is then an empty vector's data(), which may be null, and
    // memcpy(nullptr, ..., 0) is undefined (UBSan, fuzz_checkpoint)
    if (n == 0) return;
    need(n * sizeof(double));
    std::memcpy(p, b_.data() + pos_, n * sizeof(double));
    pos_ += n * sizeof(double);
  }
  size_t count(size_t limit) {
    const uint64_t n = get<uint64_t>();
    if (n > limit) corrupt("a count of " + std::to_string(n) + " exceeds the file size");
    return static_cast<size_t>(n);
  }
  [[noreturn]] void corrupt(const std::string& why) const {
    throw InputError(file_ + ": corrupt wear checkpoint (" + why +
                     "); delete it or run without --resume");
  }

 private:
  void need(size_t n) const {
    if (pos_ + n > b_.size()) corrupt("truncated");
  }
  const std::string& b_;
  std::string file_;
  size_t pos_ = 0;
};

// a frame as a flat list of doubles: to_doubles copies f into d, otherwise d into f; false
// when d holds an element count that is no whole number in [0, 1e9] (a corrupt file: the
// conversion to int of any other value is undefined behaviour; fuzz_checkpoint)
constexpr size_t kFrameDoubles = 2 + 12 + 12 + 3 + 3 + 2 + 2 + 6 + 4 + 2;
bool frame_fields(engine::Frame& f, std::array<double, kFrameDoubles>& d, bool to_doubles) {
  size_t i = 0;
  auto field = [&](double& x) {
    if (to_doubles) {
      d[i] = x;
    } else {
      x = d[i];
    }
    ++i;
  };
  field(f.gait_pct);
  field(f.time);
  for (auto& c : f.q)
    for (double& x : c) field(x);
  for (auto& c : f.applied)
    for (double& x : c) field(x);
  for (int k = 0; k < 3; ++k) field(f.restraint[k]);
  engine::ContactSummary& s = f.contact;
  for (int k = 0; k < 3; ++k) field(s.force_W[k]);
  for (double& x : s.normal_force) field(x);
  for (double& x : s.area) field(x);
  for (auto& p : s.cop_T)
    for (int k = 0; k < 3; ++k) field(p[k]);
  field(s.peak_pressure);
  field(s.mean_pressure);
  field(s.max_penetration);
  field(s.max_penetration_ratio);
  double n = s.elements_in_contact;
  field(n);
  if (!(n >= 0.0 && n <= 1e9 && n == std::floor(n))) return false;
  s.elements_in_contact = static_cast<int>(n);
  field(s.omega_max);
  return true;
}

}  // namespace

uint64_t fnv1a(const void* data, size_t n, uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

void write_checkpoint(const std::filesystem::path& path, const Checkpoint& c) {
  Writer w;
  w.bytes().append(kMagic, sizeof kMagic);
  w.put(c.identity);
  w.put(static_cast<int64_t>(c.cycles_done));
  w.put(static_cast<int64_t>(c.next_update));
  w.put(c.dt);
  w.put(c.state.time);
  w.put(static_cast<int64_t>(c.state.step));
  for (const auto& cs : c.state.carriages) {
    w.put_doubles(cs.pivot_W.data(), 3);
    w.put_doubles(cs.R_WB.data(), 9);
    w.put_doubles(cs.rate.data(), cs.rate.size());
  }
  w.put(static_cast<uint64_t>(c.insert_vertices.size()));
  for (const auto& v : c.insert_vertices) w.put_doubles(v.data(), 3);
  w.put(static_cast<uint64_t>(c.vertex_depth.size()));
  w.put_doubles(c.vertex_depth.data(), c.vertex_depth.size());
  w.put(static_cast<uint64_t>(c.records.size()));
  for (const auto& r : c.records) w.put_doubles(&r.cycles, UpdateRecord::kFields);
  w.put(static_cast<uint64_t>(c.frames.size()));
  for (const auto& f : c.frames) {
    std::array<double, kFrameDoubles> d;
    frame_fields(const_cast<engine::Frame&>(f), d, true);
    w.put_doubles(d.data(), d.size());
  }
  // the deformable insert's nodes and plastic state (empty lists for the rigid insert)
  const engine::solid::SolidState& solid = c.state.insert_solid;
  w.put(static_cast<uint64_t>(solid.position.size()));
  for (size_t n = 0; n < solid.position.size(); ++n) {
    w.put_doubles(solid.position[n].data(), 3);
    w.put_doubles(solid.velocity[n].data(), 3);
  }
  w.put(static_cast<uint64_t>(solid.alpha.size()));
  for (size_t e = 0; e < solid.alpha.size(); ++e) {
    w.put_doubles(solid.plastic_strain[e].data(), 6);
    w.put(solid.alpha[e]);
    w.put(solid.plastic_work[e]);
  }
  const uint64_t hash = fnv1a(w.bytes().data(), w.bytes().size());
  w.put(hash);
  io::write_file_atomic(path, w.bytes());
}

Checkpoint read_checkpoint(const std::filesystem::path& path, uint64_t expected_identity) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": no wear checkpoint to resume from");
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  Reader r(bytes, path.string());
  if (bytes.size() < sizeof kMagic + sizeof(uint64_t) ||
      std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    r.corrupt("not a kneesim wear checkpoint");
  }
  const size_t body = bytes.size() - sizeof(uint64_t);
  uint64_t stored;
  std::memcpy(&stored, bytes.data() + body, sizeof stored);
  if (fnv1a(bytes.data(), body) != stored) r.corrupt("content hash mismatch");
  Checkpoint c;
  for (size_t i = 0; i < sizeof kMagic; ++i) r.get<char>();
  c.identity = r.get<uint64_t>();
  if (c.identity != expected_identity) {
    throw InputError(path.string() + ": the checkpoint belongs to a different wear run (other "
                     "config, material, cycles or update schedule); delete it or run without "
                     "--resume");
  }
  c.cycles_done = r.get<int64_t>();
  const int64_t next_update = r.get<int64_t>();
  if (c.cycles_done < 0 || next_update < 0 || next_update > 1000000000) {
    r.corrupt("negative cycle count or update index out of range");
  }
  c.next_update = static_cast<int>(next_update);
  c.dt = r.get<double>();
  if (!(c.dt > 0.0)) r.corrupt("time step not positive");
  c.state.time = r.get<double>();
  c.state.step = r.get<int64_t>();
  for (auto& cs : c.state.carriages) {
    r.get_doubles(cs.pivot_W.data(), 3);
    r.get_doubles(cs.R_WB.data(), 9);
    r.get_doubles(cs.rate.data(), cs.rate.size());
  }
  const size_t limit = bytes.size() / sizeof(double);
  c.insert_vertices.resize(r.count(limit));
  for (auto& v : c.insert_vertices) r.get_doubles(v.data(), 3);
  c.vertex_depth.resize(r.count(limit));
  r.get_doubles(c.vertex_depth.data(), c.vertex_depth.size());
  c.records.resize(r.count(limit));
  for (auto& rec : c.records) r.get_doubles(&rec.cycles, UpdateRecord::kFields);
  c.frames.resize(r.count(bytes.size() / (kFrameDoubles * sizeof(double))));
  for (auto& f : c.frames) {
    std::array<double, kFrameDoubles> d;
    r.get_doubles(d.data(), d.size());
    if (!frame_fields(f, d, false)) r.corrupt("a frame's element count is out of range");
  }
  engine::solid::SolidState& solid = c.state.insert_solid;
  const size_t nodes = r.count(bytes.size() / (6 * sizeof(double)));
  solid.position.resize(nodes);
  solid.velocity.resize(nodes);
  for (size_t n = 0; n < nodes; ++n) {
    r.get_doubles(solid.position[n].data(), 3);
    r.get_doubles(solid.velocity[n].data(), 3);
  }
  const size_t elements = r.count(bytes.size() / (8 * sizeof(double)));
  solid.plastic_strain.resize(elements);
  solid.alpha.resize(elements);
  solid.plastic_work.resize(elements);
  for (size_t e = 0; e < elements; ++e) {
    r.get_doubles(solid.plastic_strain[e].data(), 6);
    solid.alpha[e] = r.get<double>();
    solid.plastic_work[e] = r.get<double>();
  }
  return c;
}

}  // namespace kneesim::wear
