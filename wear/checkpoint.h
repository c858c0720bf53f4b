// Checkpoint of a wear run: everything needed to continue bit-identically (the engine State
// with a deformable insert's nodes and plastic state, the worn insert's vertices or hex nodes,
// the cumulative depth field, the records so far, the position in the schedule) in one binary file written atomically, ending with an FNV-1a hash of its
// content. A checkpoint whose hash, magic, size or run identity does not match is rejected
// with a clear error: never silently used.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "engine/simulate.h"
#include "engine/state.h"
#include "wear/wear_loop.h"

namespace kneesim::wear {

struct Checkpoint {
  uint64_t identity = 0;                  // hash of the run definition
  long cycles_done = 0;
  int next_update = 0;                    // index of the next update
  double dt = 0.0;                        // time step reached by the run [s]
  engine::State state;
  std::vector<Eigen::Vector3d> insert_vertices;  // worn insert mesh vertices or (deformable)
                                                 // hex node reference positions [m]
  std::vector<double> vertex_depth;        // cumulative per wear site [m]
  std::vector<UpdateRecord> records;
  std::vector<engine::Frame> frames;       // kinematics of the last simulated cycle
};

void write_checkpoint(const std::filesystem::path& path, const Checkpoint& c);
// throws InputError naming the file for a missing, truncated, corrupt or foreign checkpoint
Checkpoint read_checkpoint(const std::filesystem::path& path, uint64_t expected_identity);

uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ull);

}  // namespace kneesim::wear
