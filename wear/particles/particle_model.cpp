#include "wear/particles/particle_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "engine/errors.h"
#include "wear/particles/contact.h"
#include "wear/particles/counterface.h"
#include "wear/particles/height_map.h"
#include "wear/particles/stress.h"

namespace kneesim::particles {
namespace {

// a surface: the measured map when given (must match the grid across sliding), else generated
std::vector<double> make_body_surface(const BodySpec& body, const Grid& grid,
                                      const std::string& source) {
  if (body.surface_csv.empty()) return make_rough_surface(grid, body.roughness, source);
  const HeightMap map = read_height_map(body.surface_csv);
  if (map.grid.ny != grid.ny || std::abs(map.grid.dx - grid.dx) > 1e-6 * grid.dx ||
      map.grid.nx < grid.nx) {
    throw InputError(body.surface_csv + ": height map " + std::to_string(map.grid.nx) + " x " +
                     std::to_string(map.grid.ny) + " does not fit the grid; it needs " +
                     std::to_string(grid.ny) + " columns, at least " + std::to_string(grid.nx) +
                     " rows and the grid spacing");
  }
  if (map.grid.nx == grid.nx) return map.height;
  return std::vector<double>(map.height.begin(), map.height.begin() + grid.size());
}

// the last two changes of a block series are each within tol of the earlier value
bool settled(const std::vector<double>& v, double tol) {
  const std::size_t n = v.size();
  auto close = [&](double a, double b) { return std::abs(b - a) <= tol * std::max(std::abs(a), 1e-300); };
  return n >= 3 && close(v[n - 3], v[n - 2]) && close(v[n - 2], v[n - 1]);
}

}  // namespace

double window_load(const ParticleModelConfig& c) {
  return c.load / c.cylinder_length * (c.grid.ny * c.grid.dy);
}

SizeStats calc_size_stats(const std::vector<ParticleRecord>& particles, int first_iteration,
                          const ParticleSource* only) {
  SizeStats s;
  for (const ParticleRecord& r : particles) {
    if (r.iteration < first_iteration || (only != nullptr && r.source != *only)) continue;
    ++s.particles;
    s.eq_radius += r.particle.eq_radius;
    s.length += r.particle.length;
    s.width += r.particle.width;
    s.thickness += r.particle.thickness;
    s.volume += r.particle.volume;
    s.volume_weighted_eq_radius += r.particle.volume * r.particle.eq_radius;
    const double diameter = 2.0 * r.particle.eq_radius;
    if (diameter >= 0.1e-6 && diameter <= 1e-6) s.active_band_volume_fraction += r.particle.volume;
  }
  if (s.particles > 0) {
    const double n = static_cast<double>(s.particles);
    if (s.volume > 0.0) {
      s.volume_weighted_eq_radius /= s.volume;
      s.active_band_volume_fraction /= s.volume;
    }
    s.eq_radius /= n, s.length /= n, s.width /= n, s.thickness /= n, s.volume /= n;
  }
  return s;
}

PlasticFlowRule make_plastic_flow_rule(const ParticleModelConfig& c) {
  constexpr double kSameHardness = 0.02;
  const double counterface = counterface_flow_hardness(c.harder);
  PlasticFlowRule r;
  r.hardness = std::min(c.softer.hardness, counterface);
  if (!c.plastic_deformation) return r;
  r.worn_flows = c.softer.hardness <= r.hardness * (1.0 + kSameHardness);
  r.counterface_flows = counterface <= r.hardness * (1.0 + kSameHardness);
  if (r.counterface_flows) r.counterface_share = r.worn_flows ? 0.5 : 1.0;
  return r;
}

RunLengths resolve_run_lengths(const ParticleModelConfig& c) {
  RunLengths r;
  const long track_rows = static_cast<long>(c.grid.nx) * std::max(1, c.track_factor);
  r.pass = c.slide_cells > 0
               ? static_cast<int>((track_rows + c.slide_cells - 1) / c.slide_cells)
               : 1;  // a track that does not move: every iteration sees the same rows
  r.block = c.block > 0 ? c.block : 2 * r.pass;
  r.max_iterations = c.max_iterations > 0 ? c.max_iterations : 40 * r.block;
  r.min_iterations = std::min(c.min_iterations > 0 ? c.min_iterations : 3 * r.block,
                              r.max_iterations);
  return r;
}

ParticleModelResult run_particle_model(const ParticleModelConfig& c, const std::string& source,
                                       const std::function<void(double)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const Grid& g = c.grid;
  check_grid(g, c.nz, source);
  const double load = window_load(c);
  const PlasticFlowRule flow = make_plastic_flow_rule(c);
  const double hardness = flow.hardness;
  const double cap = hardness * g.nx * g.dx * g.ny * g.dy;
  if (c.load > 0.0 && load > cap) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "%s: load %g N puts %g N on the %.3g um contact window, more than hardness x "
                  "window area = %g N (allowed load up to %g N); lower the load or enlarge the grid",
                  source.c_str(), c.load, load, g.ny * g.dy * 1e6, cap,
                  cap / load * c.load);
    throw InputError(buf);
  }
  check_load(load, hardness, g, source);
  const int nx = g.nx, ny = g.ny;
  const long n = g.size();

  // surfaces: the cylinder's in the window, the worn track longer and periodic
  Grid track_grid = g;
  track_grid.nx = g.nx * std::max(1, c.track_factor);
  std::vector<double> cyl = make_body_surface(c.harder, g, source);
  std::vector<double> track = make_body_surface(c.softer, track_grid, source);
  const int ntrack = static_cast<int>(track.size() / ny);
  track_grid.nx = ntrack;
  ParticleModelResult res;
  std::vector<double> removed(track.size());
  const SurfaceStats track0 = calc_surface_stats(track);
  res.initial_track_rq = track0.rq;
  res.initial_counterface_rq = calc_surface_stats(cyl).rq;
  double counterface_rq = res.initial_counterface_rq;

  DeflectionOperator op(g, c.harder.elastic, c.softer.elastic);
  SubsurfaceStress stress(g, c.softer.elastic.poisson_ratio);
  CounterfaceYield counterface(c);
  ContactOptions opt;
  opt.load = load;
  opt.hardness = hardness;
  // the film left on each counterface cell, and this iteration's flow of it
  std::vector<double> film_left(flow.counterface_flows ? n : 0, c.harder.elastic.film_thickness);
  std::vector<double> flowed(flow.counterface_flows ? n : 0);
  opt.tolerance = 1e-6;
  opt.max_iterations = c.contact_max_iterations;

  std::vector<double> h(n);
  std::vector<double> levels(static_cast<long>(c.nz) * n);
  const int refine = std::max(1, c.refine);
  std::vector<double> block_means, block_rq;
  const RunLengths run = resolve_run_lengths(c);
  bool track_changed = false;  // by a particle or a plastic set since the start
  int it = 0;
  for (it = 1; it <= run.max_iterations; ++it) {
    // gap: cylinder profile minus both rough surfaces at this track position
    const long offset = static_cast<long>(it - 1) * c.slide_cells % ntrack;
    for (int i = 0; i < nx; ++i) {
      const long row = (offset + i) % ntrack;
      const double xi = g.x(i);
      for (int j = 0; j < ny; ++j) {
        h[static_cast<long>(i) * ny + j] = xi * xi / (2.0 * c.cylinder_radius) -
                                           cyl[static_cast<long>(i) * ny + j] -
                                           track[row * ny + j];
      }
    }
    // contact pressure from a uniform start: the track moved by slide_cells, so the previous
    // pressure is no guess for the new contact spots; started from it, the nearly fully
    // plastic CG kept the old spots for 100 iterations (a copy of the previous iteration's
    // particles) in about a third of the iterations
    const ContactResult cr = solve_contact(op, h, opt);
    // particles of the softer body: von Mises levels from the surface down, refined; their
    // material leaves the track
    stress.set_traction(cr.pressure, c.friction);
    int computed = 0;
    const Detachment det = find_particles_from_levels(
        [&](int k, double* vm) { stress.calc_von_mises(k * c.dz, vm); }, g, c.nz, c.dz, refine,
        c.softer.yield_stress, levels, &computed);
    // plastic set: where the pressure is at the cap the surfaces overlap by -gap; that height
    // flows away for good (elastic-perfectly plastic contact) from the surfaces that yield
    // there (the flow rule): the worn track, and a transfer film as soft as the cap. The
    // next pass meets the flattened track; the counterface, fixed to the window, keeps its
    // flattened film.
    double plastic_sum = 0.0, counterface_sum = 0.0;
    std::fill(removed.begin(), removed.end(), 0.0);
    std::fill(flowed.begin(), flowed.end(), 0.0);
    for (int i = 0; i < nx; ++i) {
      const long row = (offset + i) % ntrack;
      for (int j = 0; j < ny; ++j) {
        const long k = static_cast<long>(i) * ny + j;
        const double overlap = c.plastic_deformation && cr.pressure[k] >= hardness
                                   ? std::max(0.0, -cr.gap[k])
                                   : 0.0;
        // a film flows down to its substrate at most; the rest is the worn body's
        double film = 0.0;
        if (flow.counterface_flows) {
          film = std::min(flow.counterface_share * overlap, film_left[k]);
          flowed[k] = film;
          film_left[k] -= film;
        }
        const double plastic = flow.worn_flows ? overlap - film : 0.0;
        counterface_sum += film;
        plastic_sum += plastic;
        removed[row * ny + j] = det.removed_depth[k] + plastic;
      }
    }
    if (counterface_sum > 0.0) {
      apply_lambda_s_filter(g, c.harder.roughness.lambda_s, flowed);
      for (long k = 0; k < n; ++k) cyl[k] -= flowed[k];
      counterface_rq = calc_surface_stats(cyl).rq;
    }
    track_changed = track_changed || plastic_sum > 0.0 || counterface_sum > 0.0 ||
                    !det.particles.empty();
    // the removed depth is band-limited like the surfaces themselves (lambda_s of the worn
    // body): a particle's voxel outline would otherwise cut one-cell cliffs into the track,
    // short wavelengths that each grid resolves at its own spacing, and the worn track, unlike
    // the first contact, would not converge with the grid (R 152 / 129 / 102 nm at 160² /
    // 240² / 320²). The filter keeps the removed volume.
    apply_lambda_s_filter(track_grid, c.softer.roughness.lambda_s, removed);
    for (std::size_t k = 0; k < track.size(); ++k) track[k] -= removed[k];
    // records
    IterationRecord rec;
    rec.iteration = it;
    // the counterface's (its transfer film's) particles under the same pressure
    const std::vector<Particle> from_counterface = counterface.find(cr.pressure);
    rec.particles = static_cast<int>(det.particles.size() + from_counterface.size());
    for (const Particle& p : det.particles) {
      res.particles.push_back({it, p, ParticleSource::kSofter});
      rec.mean_eq_radius += p.eq_radius / rec.particles;
      rec.particle_volume += p.volume;
    }
    for (const Particle& p : from_counterface) {
      res.particles.push_back({it, p, ParticleSource::kCounterface});
      rec.mean_eq_radius += p.eq_radius / rec.particles;
    }
    rec.counterface_particles = static_cast<int>(from_counterface.size());
    rec.max_pressure = *std::max_element(cr.pressure.begin(), cr.pressure.end());
    rec.load = cr.load;
    rec.contact_converged = cr.converged;
    rec.contact_fraction = cr.contact_fraction;
    rec.capped_fraction = cr.capped_fraction;
    rec.cg_iterations = cr.iterations;
    rec.stress_levels = computed;
    rec.plastic_volume = plastic_sum * g.cell_area();
    rec.counterface_plastic_volume = counterface_sum * g.cell_area();
    const SurfaceStats worn = calc_surface_stats(track);
    rec.track_rq = worn.rq;
    rec.track_mean_wear = track0.mean - worn.mean;
    rec.counterface_rq = counterface_rq;
    res.iterations.push_back(rec);
    if (it == 1) {
      // maps of the first (unworn) contact for the plots: pressure, and a vM section
      res.pressure = cr.pressure;
      const long peak = std::max_element(cr.pressure.begin(), cr.pressure.end()) - cr.pressure.begin();
      const int jp = static_cast<int>(peak % ny);
      const int ns = std::min(c.nz, 24);
      res.section_levels = ns;
      res.von_mises_section.assign(static_cast<long>(ns) * nx, 0.0);
      std::vector<double> vm(n);
      for (int k = 0; k < ns; ++k) {
        stress.calc_von_mises(k * c.dz, vm.data());
        for (int i = 0; i < nx; ++i) res.von_mises_section[static_cast<long>(k) * nx + i] = vm[static_cast<long>(i) * ny + jp];
      }
    }
    if (progress) progress(double(it) / run.max_iterations);
    // nothing detached or flattened over a whole pass: the track is unchanged, and when the slide divides
    // the track the next passes meet the same rows at the same offsets, so they would repeat
    // this pass exactly (UHMWPE and CFR-PEEK on CoCr: no yielded region reaches the surface)
    if (!track_changed && it == run.pass && c.slide_cells > 0 &&
        ntrack % c.slide_cells == 0) {
      res.steady_state = true;
      break;
    }
    // steady state: block means of the equivalent radius and of the track's roughness, each
    // settled over the last two block changes
    if (it % run.block == 0) {
      const SizeStats b = calc_size_stats(res.particles, it - run.block + 1);
      double rq = 0.0;
      for (int k = it - run.block; k < it; ++k) rq += res.iterations[k].track_rq / run.block;
      block_means.push_back(b.eq_radius);
      block_rq.push_back(rq);
      if (it >= run.min_iterations && block_means.size() >= 3 &&
          settled(block_means, c.steady_tolerance) && settled(block_rq, c.roughness_tolerance)) {
        res.steady_state = true;
        break;
      }
    }
  }
  const int last = std::min(it, run.max_iterations);
  res.steady_from = std::max(1, last - 2 * run.block + 1);
  res.steady = calc_size_stats(res.particles, res.steady_from);
  const ParticleSource film = ParticleSource::kCounterface;
  res.steady_counterface = calc_size_stats(res.particles, res.steady_from, &film);
  res.all = calc_size_stats(res.particles, 1);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return res;
}

}  // namespace kneesim::particles
