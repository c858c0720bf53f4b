// Material pairs of the particle model and their inputs, each with its source. The harder body
// is the counterface (the study's cylinder, or a polished CoCr femoral component), the softer
// body wears and sheds the particles (the study's disk, or the polymer insert).
#pragma once

#include <string>

#include "wear/particles/deflection.h"
#include "wear/particles/grid.h"
#include "wear/particles/surface.h"

namespace kneesim::particles {

enum class PairName { kSteelSteel, kSteelBrass, kUhmwpeCocr, kPeekCocr, kCfrpeekCocr };

struct BodySpec {
  std::string material;     // name for reports
  ElasticBody elastic;      // E, nu and an optional transfer film
  double hardness = 0.0;    // H [Pa]
  double yield_stress = 0.0;// sigma_y [Pa]
  SurfaceSpec roughness;    // Rq, skewness, kurtosis, correlation length, seed
  std::string surface_csv;  // measured height map replacing the generated one; empty = none
};

struct ParticleModelConfig {
  std::string pair;               // e.g. "steel-steel"
  BodySpec harder, softer;        // counterface and worn body
  double cylinder_radius = 2e-3;  // [m]
  double cylinder_length = 6e-3;  // [m]
  double load = 10.0;             // total normal load on the cylinder [N]
  double friction = 0.16;         // mu, traction s = mu p [-]
  Grid grid;                      // contact window, periodic along the cylinder axis
  int nz = 64;                    // stress depth levels [-]
  double dz = 95e-9;              // level spacing [m]
  int refine = 4;                 // voxels per level interval (interpolation) [-]
  int track_factor = 2;           // worn-track length / window length [-]
  int slide_cells = 30;           // track advance per iteration [cells]
  // at least three blocks: the first block is the run-in of the fresh track (its first
  // contact sheds particles about twice the later size), so the reported last two blocks
  // never include it; with 8 the block test passed at iteration 8 and reported 1-8
  int min_iterations = 12;        // [-]
  int max_iterations = 16;        // [-]
  int block = 4;                  // iterations per statistics block [-]
  double steady_tolerance = 0.1;  // relative change of the block mean radius [-]
  std::string sources;            // where the inputs come from
};

// parses "steel-steel|steel-brass|uhmwpe-cocr|peek-cocr|cfrpeek-cocr"; throws InputError
// naming `source` otherwise
PairName parse_pair(const std::string& name, const std::string& source);
const char* pair_name(PairName pair);

// the preset inputs of a pair (physics.md section 9 and the materials table of section 6)
ParticleModelConfig make_pair_config(PairName pair);

}  // namespace kneesim::particles
