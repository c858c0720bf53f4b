// The particle wear loop (wear/particles/particle_model.h). References: the pass arithmetic
// (a pass = ceil(track rows / slide_cells) iterations); an exact invariant: when nothing
// detaches or flows, the track never changes, so with a slide that divides the track every
// later pass would repeat the first one and the loop stops after one pass; and shakedown of
// the plastic set (below).
#include <doctest/doctest.h>

#include "wear/particles/particle_model.h"

using namespace kneesim::particles;

TEST_CASE("run lengths: automatic limits are whole blocks of two passes; explicit ones are kept") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelSteel);
  c.grid.nx = 240;
  CHECK(c.track_factor == 1);
  c.slide_cells = 30;
  RunLengths r = resolve_run_lengths(c);
  CHECK(r.pass == 8);  // 240 track rows / 30
  CHECK(r.block == 16);
  CHECK(r.min_iterations == 48);
  CHECK(r.max_iterations == 640);
  c.track_factor = 2;
  CHECK(resolve_run_lengths(c).pass == 16);
  c.slide_cells = 50;  // 480 / 50 = 9.6: a partial last step still belongs to the pass
  CHECK(resolve_run_lengths(c).pass == 10);
  c.block = 4;
  c.min_iterations = 30;
  c.max_iterations = 20;  // min is clamped to max
  r = resolve_run_lengths(c);
  CHECK(r.block == 4);
  CHECK(r.max_iterations == 20);
  CHECK(r.min_iterations == 20);
}

TEST_CASE("wear loop: nothing yields and nothing flows -> one pass, steady, no particles") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelSteel);
  c.grid = Grid{64, 64, 102e-9, 102e-9, true};
  c.nz = 16;
  c.slide_cells = 16;                // track 64 rows: a pass of 4 iterations
  c.load = 0.05;
  c.softer.yield_stress = 1e12;      // nothing can yield
  c.softer.hardness = 1e12;          // nor flow: the contact is elastic
  const ParticleModelResult r = run_particle_model(c, "test");
  CHECK(r.particles.empty());
  CHECK(r.steady_state);
  CHECK(r.iterations.size() == static_cast<size_t>(resolve_run_lengths(c).pass));
  CHECK(resolve_run_lengths(c).pass == 4);
  for (const IterationRecord& it : r.iterations) CHECK(it.plastic_volume == 0.0);
}

// Reference: elastic-perfectly plastic shakedown. The plastic set takes off the track exactly
// the interference of the capped cells with the deformed counterface, so the flattened track
// fits the deformed cylinder under the same load: pressed again at the same place (no slide,
// no particles, no band-limiting filter) the pressure finds the fitted shape and almost no
// new plastic set is made (small remainder: the capped set of the second solve may differ
// by boundary cells).
TEST_CASE("wear loop: a flattened track pressed again at the same place hardly flows again") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelSteel);
  c.grid = Grid{64, 64, 102e-9, 102e-9, true};
  c.nz = 8;
  c.slide_cells = 0;
  c.load = 0.2;
  c.softer.yield_stress = 1e12;  // no particles: only the plastic set changes the track
  c.softer.roughness.lambda_s = 0.0;
  c.min_iterations = c.max_iterations = 2;
  const ParticleModelResult r = run_particle_model(c, "test");
  REQUIRE(r.iterations.size() == 2);
  CHECK(r.particles.empty());
  CHECK(r.iterations[0].capped_fraction > 0.0);
  CHECK(r.iterations[0].plastic_volume > 0.0);
  CHECK(r.iterations[1].plastic_volume < 0.05 * r.iterations[0].plastic_volume);
  MESSAGE("plastic set: " << r.iterations[0].plastic_volume * 1e18 << " then "
                          << r.iterations[1].plastic_volume * 1e18 << " um3");
  // without the plastic set the same track flows by the same amount again
  c.plastic_deformation = false;
  const ParticleModelResult r0 = run_particle_model(c, "test");
  CHECK(r0.iterations[1].plastic_volume == 0.0);
  CHECK(r0.iterations[1].capped_fraction == doctest::Approx(r0.iterations[0].capped_fraction));
}

// Reference: the counterface sheds only from its transfer film, whose underside bounds the
// particles (the substrate is the harder body's own material, which does not wear); the
// interpolated voxels between the film's last level and the next one can add at most one
// level spacing (film / ceil(film / dz) = 50 nm here).
TEST_CASE("wear loop: transfer-film particles are at most the film thick; no film, none") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelBrass);
  c.grid = Grid{64, 64, 102e-9, 102e-9, true};
  c.nz = 16;
  c.slide_cells = 16;
  c.load = 0.2;
  c.min_iterations = c.max_iterations = 2;
  c.harder.elastic.film_thickness = 100e-9;
  const ParticleModelResult r = run_particle_model(c, "test");
  long film = 0;
  for (const ParticleRecord& p : r.particles) {
    if (p.source != ParticleSource::kCounterface) continue;
    ++film;
    CHECK(p.particle.thickness <= 150e-9 + 1e-12);
  }
  CHECK(film > 0);
  CHECK(r.iterations[0].counterface_particles + r.iterations[1].counterface_particles == film);
  c.harder.elastic.film_thickness = 0.0;
  const ParticleModelResult r0 = run_particle_model(c, "test");
  for (const ParticleRecord& p : r0.particles) CHECK(p.source == ParticleSource::kSofter);
}
