// Long validation against the particle-size study (physics.md section 9). References:
// - its model values, steel-steel: length 442, width 245, thickness 197 nm at 10 N and
//   267, 161, 151 nm at 2.5 N; acceptance (issue 5): within a factor of 2;
// - its trends: particle size grows with load; the layered (transfer film) steel-brass model
//   gives smaller particles than the homogeneous one (required: R 5 % smaller or more); the softer surface's roughness barely
//   changes the size while the harder surface's roughness does;
// - equilibrium: every wear-loop contact carries the window's load, and no particle spans
//   the whole periodic window.
// Each case runs the default wear loop to its run-in steady state (blocks of two passes of the
// track; steady when the block mean radius changes by < 2 % and the worn track's rms roughness
// by < 3 % twice in a row; 144-500 iterations here) on the study's 240 x 240 grid with the
// preset surfaces (lay gamma 2 along sliding, lambda_s 0.5 um; the surface-input map is in
// docs/particles.md); the roughness trend is averaged over three surface seeds (about 20 min
// in Release on 2 cores).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "wear/particles/particle_model.h"

using namespace kneesim::particles;

namespace {

struct Case {
  PairName pair = PairName::kSteelSteel;
  double load = 10.0;           // [N]
  double softer_rq_scale = 1.0; // [-]
  double harder_rq_scale = 1.0; // [-]
  bool film = true;
  int seed_offset = 0;          // added to both preset seeds [-]
};

SizeStats run(const Case& k) {
  ParticleModelConfig c = make_pair_config(k.pair);
  c.load = k.load;
  c.softer.roughness.rq *= k.softer_rq_scale;
  c.harder.roughness.rq *= k.harder_rq_scale;
  c.softer.roughness.seed += k.seed_offset;
  c.harder.roughness.seed += k.seed_offset;
  if (!k.film) c.harder.elastic.film_thickness = 0.0;
  const ParticleModelResult r = run_particle_model(c, "long test");
  std::printf("%s %g N (softer Rq x%g, harder Rq x%g, film %d, seeds +%d): %ld particles in %zu "
              "iterations (%s), R %.0f L %.0f W %.0f T %.0f nm, V %.4g um3, film particles %ld "
              "R %.0f nm, track Rq %.0f -> %.0f nm, %.0f s\n",
              c.pair.c_str(), k.load, k.softer_rq_scale, k.harder_rq_scale, int(k.film),
              k.seed_offset, r.steady.particles, r.iterations.size(),
              r.steady_state ? "steady" : "NOT steady", r.steady.eq_radius * 1e9,
              r.steady.length * 1e9, r.steady.width * 1e9, r.steady.thickness * 1e9,
              r.steady.volume * 1e18, r.steady_counterface.particles,
              r.steady_counterface.eq_radius * 1e9, r.initial_track_rq * 1e9,
              r.iterations.back().track_rq * 1e9, r.seconds);
  CHECK(r.steady_state);
  // equilibrium in every iteration (the nearly fully plastic contact once lost up to 60 %)
  for (const IterationRecord& it : r.iterations) {
    CHECK(it.load == doctest::Approx(window_load(c)).epsilon(1e-6));
  }
  // no particle spans the periodic window width: such a band came from a NaN pressure that
  // the plastic placement put on the first rows of the window
  long bands = 0;
  for (const ParticleRecord& p : r.particles) bands += p.particle.width >= c.grid.ny * c.grid.dy;
  CHECK(bands == 0);
  return r.steady;
}

bool within_factor_2(double predicted, double reference) {
  return predicted >= 0.5 * reference && predicted <= 2.0 * reference;
}

// the preset steel-steel runs, shared by the test cases below
const SizeStats& steel(double load) {
  static const SizeStats s10 = run(Case{PairName::kSteelSteel, 10.0});
  static const SizeStats s25 = run(Case{PairName::kSteelSteel, 2.5});
  return load > 5.0 ? s10 : s25;
}

}  // namespace

TEST_CASE("steel-steel at 10 N: sizes within a factor 2 of the study's model") {
  CHECK(within_factor_2(steel(10.0).length * 1e9, 442));
  CHECK(within_factor_2(steel(10.0).width * 1e9, 245));
  CHECK(within_factor_2(steel(10.0).thickness * 1e9, 197));
}

// Measured at the run-in steady state: L / W / T 213 / 176 / 156 nm (ratios 0.80 / 1.09 /
// 1.03); with the earlier five-pass loop 268 / 202 / 173 nm, and 361 nm wide (2.24x) with
// isotropic surfaces (docs/particles.md).
TEST_CASE("steel-steel at 2.5 N: sizes within a factor 2 of the study's model") {
  CHECK(within_factor_2(steel(2.5).length * 1e9, 267));
  CHECK(within_factor_2(steel(2.5).width * 1e9, 161));
  CHECK(within_factor_2(steel(2.5).thickness * 1e9, 151));
}

// Load trend (docs/particles.md): the mean particle volume (measured x4.8), width and length
// grow from 2.5 to 10 N; asserted for the preset seeds (three seed pairs agreed with the
// one-pass loop).
TEST_CASE("steel-steel: particle size grows with load") {
  CHECK(steel(10.0).volume > 1.3 * steel(2.5).volume);
  CHECK(steel(10.0).width > steel(2.5).width);
  CHECK(steel(10.0).length > steel(2.5).length);
}

// Layered vs homogeneous steel-brass (docs/particles.md, "Layered steel-brass"). The brass
// transfer film on the cylinder is as hard as the disk, so at the cap it flows with the disk
// (the plastic flow rule); fixed to the window, it is flattened by every pass of the track's
// asperities into a plateau that conforms to the track, the contact turns partly elastic
// (about a third of the contact cells at H instead of four fifths) and the film's lower
// modulus then lowers the pressure. Measured at 240² with the preset 0.5 um film: R 64 vs
// 114 nm (preset seeds), 68 vs 113 nm (seeds +100). The study's 100 nm film gives R 70 nm but
// did not reach the steady state in 640 iterations (docs/particles.md, "Film thickness"). Without the film's flow (the film only as an elastic layer and a
// source of particles) the contact stayed fully plastic and the sizes differed by 0.4 %.
TEST_CASE("steel-brass: the layered model gives smaller particles than the homogeneous one") {
  const SizeStats layered = run(Case{PairName::kSteelBrass, 10.0, 1.0, 1.0, true});
  const SizeStats homogeneous = run(Case{PairName::kSteelBrass, 10.0, 1.0, 1.0, false});
  CHECK(layered.eq_radius < 0.95 * homogeneous.eq_radius);
}

// Roughness trend, averaged over three surface seeds (mean equivalent radius at 10 N, Rq of
// one body doubled); computed once and shared by the two cases below.
struct RoughnessTrend {
  double base = 0.0, softer2 = 0.0, harder2 = 0.0;  // [m]
};
const RoughnessTrend& roughness_trend() {
  static const RoughnessTrend t = [] {
    RoughnessTrend r;
    for (int s = 0; s < 3; ++s) {
      r.base += (s == 0 ? steel(10.0) : run(Case{PairName::kSteelSteel, 10.0, 1.0, 1.0, true, 100 * s}))
                    .eq_radius / 3.0;
      r.softer2 += run(Case{PairName::kSteelSteel, 10.0, 2.0, 1.0, true, 100 * s}).eq_radius / 3.0;
      r.harder2 += run(Case{PairName::kSteelSteel, 10.0, 1.0, 2.0, true, 100 * s}).eq_radius / 3.0;
    }
    std::printf("roughness trend over 3 seeds: R base %.1f, softer x2 %.1f (%+.1f %%), harder x2 "
                "%.1f (%+.1f %%) nm\n",
                r.base * 1e9, r.softer2 * 1e9, 100 * (r.softer2 / r.base - 1.0), r.harder2 * 1e9,
                100 * (r.harder2 / r.base - 1.0));
    return r;
  }();
  return t;
}

// The harder surface's roughness matters: doubling the cylinder's Rq moves the mean radius by
// more than 5 % (measured +9 to +10 % per seed pair at 240², +8 % at 160²; docs/particles.md).
// Why: the run-in track takes its texture from the cylinder (its steady rms roughness is
// 115 nm with the preset cylinder, 152 nm with Rq x2, at 160²).
TEST_CASE("roughness trend: the harder surface's roughness changes the size (three seeds)") {
  const RoughnessTrend& t = roughness_trend();
  CHECK(t.harder2 / t.base - 1.0 > 0.05);
}

// The softer surface's roughness barely matters: |change| < 5 % when the disk's Rq is doubled,
// and the harder surface's effect more than twice the softer's. Why: the run-in track forgets
// the disk's initial roughness (its rms roughness falls to the same steady value from 610 or
// 1220 nm), which the loop now waits for; stopped on the mean radius alone, the track still
// carried it and the effect was -7.6 % (docs/particles.md, "Run length").
TEST_CASE("roughness trend: the softer surface's roughness barely matters (three seeds)") {
  const RoughnessTrend& t = roughness_trend();
  const double d_soft = std::abs(t.softer2 / t.base - 1.0);
  const double d_hard = t.harder2 / t.base - 1.0;
  CHECK(d_soft < 0.05);
  CHECK(d_hard > 2.0 * d_soft);
}
