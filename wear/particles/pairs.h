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
  double film_yield_stress = 0.0;  // sigma_y of the transfer film, when there is one [Pa]
  double film_hardness = 0.0;      // H of the transfer film; 0 = 2.8 x film_yield_stress [Pa]
};

// The hardness at which the counterface's surface flows: its transfer film's when it has one,
// else its own.
double counterface_flow_hardness(const BodySpec& harder);

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
  // The worn track is one window long and periodic (track_factor 1): every iteration wears
  // every track row in the window, so the track runs in twice as fast per iteration as with
  // a track twice the window, and reaches the same steady state (measured: R 151 / 152 nm,
  // track Rq 115 nm at 160², both track lengths).
  int track_factor = 1;           // worn-track length / window length [-]
  int slide_cells = 30;           // track advance per iteration [cells]
  // Plastic deformation of the worn body: where the pressure is at the cap the surfaces
  // interpenetrate, i.e. the softer body's asperities flow; their height above the deformed
  // counterface is taken off the track as a permanent set (not as wear), so the track
  // conforms to the harder body as it runs in.
  bool plastic_deformation = true;
  // Run length, in iterations; 0 = automatic, in passes of the track (a pass is
  // ceil(track cells / slide_cells) iterations, 8 at the defaults): statistics blocks of two
  // passes, at least 3 blocks, at most 40. The steady state is the run-in track, not only a
  // settled mean radius: the radius settles within a few passes while the worn track still
  // carries the initial roughness of the softer surface (steel-steel, softer Rq x2: track Rq
  // 1050 -> 140 nm over 320 iterations, still falling), and only the run-in track forgets it.
  // Steady when, in each of the last two blocks, the block mean radius changed by less than
  // steady_tolerance and the block mean rms roughness of the track by less than
  // roughness_tolerance (its block-to-block scatter in the steady state is about 2 %).
  int min_iterations = 0;         // [-]
  int max_iterations = 0;         // [-]
  int block = 0;                  // iterations per statistics block [-]
  double steady_tolerance = 0.02; // relative change of the block mean radius [-]
  double roughness_tolerance = 0.03; // relative change of the block mean track Rq [-]
  // CG iterations per wear-loop contact; about a third of the nearly fully plastic contacts end
  // there without meeting the complementarity tolerance, carrying the load exactly, with the
  // sizes unchanged against 100 (docs/particles.md)
  int contact_max_iterations = 40;  // [-]
  // knee pairs: the Hertz peak pressure the cylinder is sized to, from a kneesim contact run
  // of the same insert material (kneesim particles) or the config's contact_pressure_MPa
  double contact_pressure = 0.0;  // [Pa]; 0 for the study's pairs
  std::string contact_pressure_source;
  std::string sources;            // where the inputs come from
};

// parses "steel-steel|steel-brass|uhmwpe-cocr|peek-cocr|cfrpeek-cocr"; throws InputError
// naming `source` otherwise
PairName parse_pair(const std::string& name, const std::string& source);
const char* pair_name(PairName pair);

// the knee pairs (an insert material against polished CoCr), whose contact pressure is not a
// preset: it comes from a kneesim contact run of the material
bool is_knee_pair(PairName pair);
// the kneesim material name of a knee pair's insert ("uhmwpe", "peek", "cfr-peek")
const char* knee_pair_material(PairName pair);

// the preset inputs of a pair (physics.md section 9 and the materials table of section 6);
// knee pairs need contact_pressure > 0 [Pa] (the Hertz peak the cylinder is sized to) and the
// sentence saying where it comes from, else InputError
ParticleModelConfig make_pair_config(PairName pair, double contact_pressure = 0.0,
                                     const std::string& contact_pressure_source = "");

}  // namespace kneesim::particles
