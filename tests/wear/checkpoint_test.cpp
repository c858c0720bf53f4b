// Wear checkpoints (issue 3, "a corrupt checkpoint is never silently used"): a written
// checkpoint reads back bit for bit; a flipped byte anywhere, a truncation, a missing file or a
// checkpoint of another run identity is rejected with one sentence naming the file. Also the
// materials library's bad-input errors (unknown material) from models::load_config.
#include <doctest/doctest.h>

#include "tests/loads/temp_dir.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "engine/errors.h"
#include "models/config.h"
#include "wear/checkpoint.h"

using namespace kneesim;
namespace fs = std::filesystem;

namespace {

using test::TempDir;  // tests/loads/temp_dir.h

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// a checkpoint with every field filled from a seeded generator
wear::Checkpoint make_checkpoint(uint64_t identity) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  wear::Checkpoint c;
  c.identity = identity;
  c.cycles_done = 750'000;
  c.next_update = 3;
  c.dt = 2.5e-5;
  c.state.time = 4.0;
  c.state.step = 160'000;
  for (auto& cs : c.state.carriages) {
    cs.pivot_W = Eigen::Vector3d(u(rng), u(rng), u(rng));
    for (int i = 0; i < 9; ++i) cs.R_WB.data()[i] = u(rng);
    for (double& r : cs.rate) r = u(rng);
  }
  for (int v = 0; v < 50; ++v) c.insert_vertices.emplace_back(u(rng), u(rng), u(rng));
  for (int v = 0; v < 30; ++v) c.vertex_depth.push_back(1e-4 * (1.0 + u(rng)));
  for (int r = 0; r < 4; ++r) {
    wear::UpdateRecord rec;
    double* f = &rec.cycles;
    for (int i = 0; i < wear::UpdateRecord::kFields; ++i) f[i] = u(rng);
    c.records.push_back(rec);
  }
  return c;
}

template <typename T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// the InputError message of reading the checkpoint, "" if it was accepted
std::string read_error(const fs::path& p, uint64_t identity) {
  try {
    wear::read_checkpoint(p, identity);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// one sentence naming the file: the error contract
void check_one_sentence(const std::string& msg, const fs::path& file) {
  CAPTURE(msg);
  CHECK(!msg.empty());
  CHECK(msg.find('\n') == std::string::npos);
  CHECK(msg.find(file.string()) != std::string::npos);
}

}  // namespace

TEST_CASE("checkpoint round trip is bit-identical") {
  // reference: the invariant resume relies on (every double restored bit for bit); the
  // records are written as kFields doubles from &cycles, so the record must be exactly that
  CHECK(sizeof(wear::UpdateRecord) == wear::UpdateRecord::kFields * sizeof(double));
  TempDir dir;
  const fs::path p = dir.path / "wear.checkpoint";
  const wear::Checkpoint c = make_checkpoint(0x1234abcdULL);
  wear::write_checkpoint(p, c);
  const wear::Checkpoint r = wear::read_checkpoint(p, c.identity);
  CHECK(r.identity == c.identity);
  CHECK(r.cycles_done == c.cycles_done);
  CHECK(r.next_update == c.next_update);
  CHECK(same_bits(r.dt, c.dt));
  CHECK(same_bits(r.state.time, c.state.time));
  CHECK(r.state.step == c.state.step);
  CHECK(engine::hash_state(r.state) == engine::hash_state(c.state));
  REQUIRE(r.insert_vertices.size() == c.insert_vertices.size());
  for (size_t i = 0; i < c.insert_vertices.size(); ++i)
    CHECK(std::memcmp(r.insert_vertices[i].data(), c.insert_vertices[i].data(), 24) == 0);
  REQUIRE(r.vertex_depth.size() == c.vertex_depth.size());
  CHECK(std::memcmp(r.vertex_depth.data(), c.vertex_depth.data(), 8 * c.vertex_depth.size()) == 0);
  REQUIRE(r.records.size() == c.records.size());
  for (size_t i = 0; i < c.records.size(); ++i) CHECK(same_bits(r.records[i], c.records[i]));
}

TEST_CASE("a corrupt checkpoint is rejected, never silently used") {
  TempDir dir;
  const fs::path p = dir.path / "wear.checkpoint";
  const uint64_t id = 77;
  wear::write_checkpoint(p, make_checkpoint(id));
  const std::string good = slurp(p);
  REQUIRE(good.size() > 200);

  SUBCASE("one flipped byte anywhere (magic, header, body, hash)") {
    // reference: the FNV-1a content hash changes with any single byte (each step is a
    // bijection of the running hash), so every position must be caught
    for (size_t pos : {size_t{0}, size_t{20}, good.size() / 3, good.size() / 2,
                       good.size() - 9, good.size() - 1}) {
      CAPTURE(pos);
      std::string bad = good;
      bad[pos] = static_cast<char>(bad[pos] ^ 0x01);
      spit(p, bad);
      const std::string msg = read_error(p, id);
      check_one_sentence(msg, p);
      CHECK(msg.find("corrupt") != std::string::npos);
    }
    // exhaustively: every byte position, one bit each (the file is a few kB)
    int accepted = 0;
    for (size_t pos = 0; pos < good.size(); ++pos) {
      std::string bad = good;
      bad[pos] = static_cast<char>(bad[pos] ^ 0x80);
      spit(p, bad);
      if (read_error(p, id).empty()) ++accepted;
    }
    CHECK(accepted == 0);
  }
  SUBCASE("truncated") {
    for (size_t n : {size_t{0}, size_t{10}, good.size() / 2, good.size() - 1}) {
      CAPTURE(n);
      spit(p, good.substr(0, n));
      const std::string msg = read_error(p, id);
      check_one_sentence(msg, p);
    }
  }
  SUBCASE("another run's checkpoint") {
    const std::string msg = read_error(p, id + 1);
    check_one_sentence(msg, p);
    CHECK(msg.find("different wear run") != std::string::npos);
  }
  SUBCASE("missing") {
    fs::remove(p);
    check_one_sentence(read_error(p, id), p);
  }
  SUBCASE("the intact file still reads (the failures above are the corruption's)") {
    spit(p, good);
    CHECK(read_error(p, id).empty());
  }
}

TEST_CASE("unknown material: one sentence naming it and the known ones") {
  // reference: issue 3 bad-input list; the library ships uhmwpe, peek and cfr-peek
  std::string msg;
  try {
    models::load_config("", {{"material.name", "\"unobtainium\""}});
  } catch (const InputError& e) {
    msg = e.what();
  }
  CAPTURE(msg);
  CHECK(msg.find("unobtainium") != std::string::npos);
  CHECK(msg.find("uhmwpe") != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
  // the three library materials load, with wear factors inside the plausible range
  for (const char* name : {"uhmwpe", "peek", "cfr-peek"}) {
    const models::Config c = models::load_config("", {{"material.name", std::string("\"") + name + "\""}});
    CHECK(c.material.wear_factor_mm3_per_Nmm >= 1e-12);
    CHECK(c.material.wear_factor_mm3_per_Nmm <= 1e-6);
  }
}
