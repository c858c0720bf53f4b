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
  // Run length, in iterations; 0 = automatic, in passes of the track (a pass is
  // ceil(track cells / slide_cells) iterations, 16 at the defaults): statistics blocks of one
  // pass, at least 3 passes, at most 12. A pass is the natural block: every track row has met
  // the window once. The pass mean radius keeps falling for about 5 passes as the track runs
  // in (steel-steel 10 N: 169, 153, 146, 142, 140, 138 nm), so a shorter block or a looser
  // tolerance declares a steady state that is not one (the earlier 4-iteration blocks at
  // 10 % stopped after one pass, 10 % above the run-in value).
  int min_iterations = 0;         // [-]
  int max_iterations = 0;         // [-]
  int block = 0;                  // iterations per statistics block [-]
  double steady_tolerance = 0.02; // relative change of the block mean radius [-]
  std::string sources;            // where the inputs come from
};

// parses "steel-steel|steel-brass|uhmwpe-cocr|peek-cocr|cfrpeek-cocr"; throws InputError
// naming `source` otherwise
PairName parse_pair(const std::string& name, const std::string& source);
const char* pair_name(PairName pair);

// the preset inputs of a pair (physics.md section 9 and the materials table of section 6)
ParticleModelConfig make_pair_config(PairName pair);

}  // namespace kneesim::particles
