// Import of a measured height map (AFM or profilometer export) as CSV:
//
//   # optional comment lines
//   spacing_nm,102
//   h(0,0),h(0,1),...,h(0,ny-1)      heights in nanometres; one row per x, columns along y
//   ...
//
// Every row must have the same number of values; sizes must be even (the real FFT).
#pragma once

#include <filesystem>
#include <vector>

#include "wear/particles/grid.h"

namespace kneesim::particles {

struct HeightMap {
  Grid grid;                   // nx rows, ny columns, dx = dy = spacing
  std::vector<double> height;  // grid.size() heights with the mean removed [m]
};

// throws InputError naming the file, row and value for unreadable files, ragged rows,
// non-numbers, spacing <= 0 or unusable sizes
HeightMap read_height_map(const std::filesystem::path& path);

}  // namespace kneesim::particles
