// The wear loop of the particle-size study: contact of the harder body's rough cylinder on the
// softer body's rough track, subsurface von Mises field in the softer body, detachment of the
// surface-reaching yielded regions as particles, removal of their material from the track,
// and again, until the particle-size statistics settle.
//
// Sliding: the contact window is fixed to the cylinder (the harder body: its own material
// neither wears nor flows; a transfer film on it may flow, see PlasticFlowRule) while the
// worn track, periodic, advances by `slide_cells` per iteration, so each iteration meets
// partly new, partly worn track and the track is run in over the laps. The steady state is
// the run-in track: statistics blocks of two passes, steady when twice in a row the block
// mean radius and the block mean track roughness settle (ParticleModelConfig); the reported
// sizes are the means over the last two blocks.
//
// Cost control: stress levels are computed from the surface down and stop at the first level
// with no yielded cell, since a surface-reaching region cannot pass through it.
#pragma once

#include <functional>
#include <vector>

#include "wear/particles/detachment.h"
#include "wear/particles/pairs.h"

namespace kneesim::particles {

// which body a particle came from: the worn softer body, or the counterface (in practice its
// transfer film, which is softer than the counterface's own material)
enum class ParticleSource { kSofter, kCounterface };

struct ParticleRecord {
  int iteration = 0;  // [-]
  Particle particle;
  ParticleSource source = ParticleSource::kSofter;
};

struct IterationRecord {
  int iteration = 0;              // [-]
  int particles = 0;              // detached this iteration, both bodies [-]
  int counterface_particles = 0;  // of which from the counterface (its film) [-]
  double mean_eq_radius = 0.0;    // over this iteration's particles [m]
  double max_pressure = 0.0;      // [Pa]
  double load = 0.0;              // carried by the contact pressure [N]
  bool contact_converged = false; // contact solver reached its tolerance [-]
  double contact_fraction = 0.0;  // [-]
  double capped_fraction = 0.0;   // share at p = H [-]
  int cg_iterations = 0;          // [-]
  int stress_levels = 0;          // levels computed [-]
  double particle_volume = 0.0;   // detached from the worn body this iteration [m^3]
  double plastic_volume = 0.0;    // permanent set taken off the track this iteration [m^3]
  double counterface_plastic_volume = 0.0;  // flowed off the counterface's film [m^3]
  double track_rq = 0.0;          // rms roughness of the whole worn track after it [m]
  double track_mean_wear = 0.0;   // mean depth worn and flattened off the track so far [m]
  double counterface_rq = 0.0;    // rms roughness of the counterface in the window after it [m]
};

struct SizeStats {
  long particles = 0;        // [-]
  double eq_radius = 0.0;    // mean [m]
  double length = 0.0;       // mean [m]
  double width = 0.0;        // mean [m]
  double thickness = 0.0;    // mean [m]
  double volume = 0.0;       // mean [m^3]
  // volume-weighted mean equivalent radius: sum V R / sum V; unlike the number mean it is
  // carried by the particles that hold the material, not by the many one-cell ones whose
  // count depends on the grid [m]
  double volume_weighted_eq_radius = 0.0;
  // share of the detached volume in particles of equivalent diameter 0.1-1 um, the range
  // the body's response is most active to [-]
  double active_band_volume_fraction = 0.0;
};

struct ParticleModelResult {
  std::vector<ParticleRecord> particles;
  std::vector<IterationRecord> iterations;
  SizeStats steady;               // means over the last two blocks, particles of both bodies
  SizeStats steady_counterface;   // the same window, counterface (film) particles only
  SizeStats all;                  // means over every particle
  bool steady_state = false;      // block criterion met before max_iterations [-]
  int steady_from = 0;            // first iteration of the reported window [-]
  std::vector<double> pressure;   // first iteration's pressure, grid.size() [Pa]
  std::vector<double> von_mises_section;  // first iteration: nz x nx at the y of peak p [Pa]
  int section_levels = 0;         // levels in the section [-]
  double initial_track_rq = 0.0;  // rms roughness of the unworn track [m]
  double initial_counterface_rq = 0.0;  // rms roughness of the counterface's window [m]
  double seconds = 0.0;           // wall time [s]
};

// The run length actually used: config's block / min / max iterations with 0 (automatic)
// resolved to 1 / 3 / 12 passes of the track, and min_iterations <= max_iterations.
struct RunLengths {
  int pass = 1;            // iterations per pass of the track [-]
  int block = 1;           // [-]
  int min_iterations = 1;  // [-]
  int max_iterations = 1;  // [-]
};
RunLengths resolve_run_lengths(const ParticleModelConfig& config);

// Which surfaces flow where the pressure reaches the cap. The cap is the lower of the worn
// body's hardness and the counterface surface's (its transfer film's when it has one, see
// counterface_flow_hardness). A surface flows when its hardness is the cap's within 2 %
// (hardness is known to a few %: the study's brass H 2.64 GPa against 2.8 x 0.94 = 2.63 GPa);
// two such surfaces share the overlap equally, as two equally hard asperities flatten alike.
// A film flows down to its substrate at most; the rest of the overlap is the worn body's.
struct PlasticFlowRule {
  double hardness = 0.0;           // the pressure cap [Pa]
  bool worn_flows = false;         // the softer (worn) body takes a share [-]
  bool counterface_flows = false;  // the counterface's surface (its film) takes a share [-]
  double counterface_share = 0.0;  // of the overlap [-]
};
PlasticFlowRule make_plastic_flow_rule(const ParticleModelConfig& config);

// Throws InputError (naming `source`) for an unusable grid or a load above H x window area.
ParticleModelResult run_particle_model(const ParticleModelConfig& config,
                                       const std::string& source,
                                       const std::function<void(double)>& progress = {});

// the contact window's share of the cylinder load [N]
double window_load(const ParticleModelConfig& config);

// mean sizes of a set of particles (from `first_iteration` on; of one source when given)
SizeStats calc_size_stats(const std::vector<ParticleRecord>& particles, int first_iteration,
                          const ParticleSource* only = nullptr);

}  // namespace kneesim::particles
