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

// Reference: the flow rule's cases (particle_model.h): the softer surface at the contact sets
// the cap and flows; equally hard surfaces (within 2 %) share the overlap equally.
TEST_CASE("plastic flow rule: which surfaces flow at the cap, and their shares") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelSteel);
  PlasticFlowRule r = make_plastic_flow_rule(c);  // steel cylinder 6 GPa on a 1.8 GPa disk
  CHECK(r.hardness == 1.8e9);
  CHECK(r.worn_flows);
  CHECK_FALSE(r.counterface_flows);
  CHECK(r.counterface_share == 0.0);
  c = make_pair_config(PairName::kSteelBrass);  // brass film on the cylinder, as hard as the disk
  r = make_plastic_flow_rule(c);
  CHECK(r.hardness == 2.64e9);
  CHECK(r.worn_flows);
  CHECK(r.counterface_flows);
  CHECK(r.counterface_share == 0.5);
  c.harder.film_hardness = 0.0;  // 2.8 x 0.94 = 2.632 GPa: within 2 % of the disk's, shared
  r = make_plastic_flow_rule(c);
  CHECK(r.hardness == doctest::Approx(2.632e9));
  CHECK(r.counterface_share == 0.5);
  c.harder.film_hardness = 2.0e9;  // a softer film takes the whole overlap
  r = make_plastic_flow_rule(c);
  CHECK(r.hardness == 2.0e9);
  CHECK_FALSE(r.worn_flows);
  CHECK(r.counterface_share == 1.0);
  c.harder.film_hardness = 3.0e9;  // a harder film does not flow
  r = make_plastic_flow_rule(c);
  CHECK(r.hardness == 2.64e9);
  CHECK_FALSE(r.counterface_flows);
  c.harder.elastic.film_thickness = 0.0;  // no film: the steel's own 6 GPa
  CHECK_FALSE(make_plastic_flow_rule(c).counterface_flows);
  c = make_pair_config(PairName::kSteelBrass);
  c.plastic_deformation = false;
  r = make_plastic_flow_rule(c);
  CHECK_FALSE(r.worn_flows);
  CHECK_FALSE(r.counterface_flows);
  CHECK(r.hardness == 2.64e9);  // the cap stays
}

// Reference: shakedown with both surfaces flowing. The two shares add up to the capped cells'
// overlap, so pressed again at the same place the surfaces fit and hardly flow again; with an
// equal share the film and the track flow by the same volume; a film thinner than its share
// flows down to its substrate and no further, the track taking the rest.
TEST_CASE("wear loop: a transfer film as hard as the disk flows with it, at most its thickness") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelBrass);
  c.grid = Grid{64, 64, 102e-9, 102e-9, true};
  c.nz = 8;
  c.slide_cells = 0;
  c.load = 0.2;
  c.softer.yield_stress = 1e12;  // no particles from either body: only the flow changes them
  c.harder.film_yield_stress = 1e12;
  c.softer.roughness.lambda_s = 0.0;
  c.harder.roughness.lambda_s = 0.0;
  c.min_iterations = c.max_iterations = 2;
  const ParticleModelResult r = run_particle_model(c, "test");
  REQUIRE(r.iterations.size() == 2);
  CHECK(r.particles.empty());
  const IterationRecord& first = r.iterations[0];
  CHECK(first.plastic_volume > 0.0);
  CHECK(first.counterface_plastic_volume ==
        doctest::Approx(first.plastic_volume).epsilon(1e-12).scale(0));
  CHECK(first.counterface_rq != r.initial_counterface_rq);  // the film changed shape
  const double flowed = first.plastic_volume + first.counterface_plastic_volume;
  CHECK(r.iterations[1].plastic_volume + r.iterations[1].counterface_plastic_volume <
        0.05 * flowed);
  // a 2 nm film: each cell's film flows 2 nm at most, the track the rest of the overlap
  c.harder.elastic.film_thickness = 2e-9;
  const ParticleModelResult t = run_particle_model(c, "test");
  const IterationRecord& thin = t.iterations[0];
  const double cells = thin.capped_fraction * c.grid.size();
  CHECK(thin.counterface_plastic_volume > 0.0);
  CHECK(thin.counterface_plastic_volume <= 2e-9 * cells * c.grid.cell_area() * (1 + 1e-9));
  CHECK(thin.plastic_volume > thin.counterface_plastic_volume);
  CHECK(t.iterations[1].plastic_volume + t.iterations[1].counterface_plastic_volume <
        0.05 * (thin.plastic_volume + thin.counterface_plastic_volume));
  MESSAGE("film 500 nm: track " << first.plastic_volume * 1e18 << " um3, film "
                                << first.counterface_plastic_volume * 1e18 << " um3; film 2 nm: "
                                << thin.plastic_volume * 1e18 << " / "
                                << thin.counterface_plastic_volume * 1e18 << " um3");
}

// Reference: the definitions, by hand. Three particles of radius 40, 100 and 600 nm (spheres'
// volumes): number mean 246.7 nm; volume-weighted sum V R / sum V; the 0.1-1 um diameter band
// holds only the 100 nm one (diameter 200 nm); the 40 nm one (80 nm) and the 600 nm one
// (1.2 um) fall outside. The window and source filters keep what they name.
TEST_CASE("size statistics: number mean, volume-weighted radius, active-band volume share") {
  auto sphere = [](double r) {
    Particle p;
    p.eq_radius = r;
    p.volume = 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
    return p;
  };
  std::vector<ParticleRecord> ps = {{1, sphere(40e-9), ParticleSource::kSofter},
                                    {2, sphere(100e-9), ParticleSource::kSofter},
                                    {2, sphere(600e-9), ParticleSource::kCounterface}};
  const SizeStats s = calc_size_stats(ps, 1);
  const double v1 = ps[0].particle.volume, v2 = ps[1].particle.volume, v3 = ps[2].particle.volume;
  CHECK(s.particles == 3);
  CHECK(s.eq_radius == doctest::Approx(740e-9 / 3).scale(0));
  CHECK(s.volume_weighted_eq_radius ==
        doctest::Approx((v1 * 40e-9 + v2 * 100e-9 + v3 * 600e-9) / (v1 + v2 + v3)).scale(0));
  CHECK(s.active_band_volume_fraction == doctest::Approx(v2 / (v1 + v2 + v3)).scale(0));
  const SizeStats late = calc_size_stats(ps, 2);
  CHECK(late.particles == 2);
  const ParticleSource softer = ParticleSource::kSofter;
  const SizeStats disk = calc_size_stats(ps, 1, &softer);
  CHECK(disk.particles == 2);
  CHECK(disk.active_band_volume_fraction == doctest::Approx(v2 / (v1 + v2)));
  CHECK(calc_size_stats({}, 1).volume_weighted_eq_radius == 0.0);
}
