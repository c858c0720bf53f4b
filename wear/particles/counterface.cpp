#include "wear/particles/counterface.h"

#include <algorithm>
#include <cmath>

namespace kneesim::particles {

CounterfaceYield::CounterfaceYield(const ParticleModelConfig& c)
    : grid_(c.grid), friction_(c.friction), refine_(std::max(1, c.refine)) {
  const BodySpec& b = c.harder;
  film_ = b.elastic.film_thickness;
  film_yield_ = b.film_yield_stress;
  // only a transfer film can shed: the counterface's own material is the harder body, which
  // the model (as the study) does not wear. Checked on the steel cylinder anyway (steel-brass
  // without film, 32 iterations): single-voxel skins of 24 nm where the cap's one-cell pressure
  // edges meet mu = 0.3, 5 % of the particles at R 41 nm, an artefact of the pressure
  // discretisation rather than wear of a 6 GPa surface.
  active_ = film_ > 0.0 && film_yield_ > 0.0;
  if (!active_) return;
  // levels on a spacing that puts one level exactly on the film's underside, down to it and
  // one below (where nothing yields, which closes the regions)
  const int in_film = static_cast<int>(std::ceil(film_ / c.dz));
  dz_ = film_ / in_film;
  nz_ = in_film + 2;
  layered_ = std::make_unique<LayeredSubsurfaceStress>(grid_, film_, b.elastic.film_modulus,
                                                       b.elastic.film_poisson,
                                                       b.elastic.youngs_modulus,
                                                       b.elastic.poisson_ratio);
}

void CounterfaceYield::ratio_level(int k, double* out) {
  const long n = grid_.size();
  const double z = k * dz_;
  // the level on the film's underside is read on the film side; below it the substrate (the
  // counterface's own material) does not yield
  if (z > film_ * (1.0 + 1e-9)) {
    std::fill(out, out + n, 0.0);
    return;
  }
  layered_->calc_von_mises(std::min(z, film_ * (1.0 - 1e-9)), out);
  const double inv = 1.0 / film_yield_;
  for (long i = 0; i < n; ++i) out[i] *= inv;
}

std::vector<Particle> CounterfaceYield::find(const std::vector<double>& pressure) {
  computed_ = 0;
  if (!active_) return {};
  layered_->set_traction(pressure, -friction_);
  return find_particles_from_levels([&](int k, double* r) { ratio_level(k, r); }, grid_, nz_,
                                    dz_, refine_, 1.0, levels_, &computed_)
      .particles;
}

}  // namespace kneesim::particles
