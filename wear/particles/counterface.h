// Particles of the counterface's transfer film (the layered model). The film carries the same
// contact pressure as the worn body and the opposite friction traction; the particle criterion
// applies to it as to the worn body: a region of the film where the von Mises stress of the
// layered body (layered_stress.h) exceeds the film's yield stress and that reaches the surface
// detaches. The substrate below the film is the counterface's own, harder material, which the
// model does not wear, so film particles are at most the film thick. This is the film's own
// route into the particle sizes: in a fully plastic contact (every loaded cell at p = H) the
// film cannot change the pressure the worn body sees.
//
// The counterface's surface is kept as it is: a transfer film is a third body, replenished
// from the worn disk as it detaches (the study gives its thickness as an input), and a
// homogeneous counterface is the harder body, which this model does not wear.
//
// Frames: the counterface's own depth axis points the other way; seen from inside it the
// pressure map is mirrored across the sliding direction (y -> -y) and the traction along x is
// reversed. A mirror image has the same von Mises field mirrored, so the regions and their
// sizes are those computed here with the map as it is and the traction -mu p.
#pragma once

#include <memory>
#include <vector>

#include "wear/particles/detachment.h"
#include "wear/particles/layered_stress.h"
#include "wear/particles/pairs.h"

namespace kneesim::particles {

class CounterfaceYield {
 public:
  explicit CounterfaceYield(const ParticleModelConfig& config);

  // false when the counterface has no film (or the film no yield stress)
  bool active() const { return active_; }
  // the counterface's particles under the contact pressure (grid.size(), [Pa])
  std::vector<Particle> find(const std::vector<double>& pressure);

 private:
  // yield-stress ratio vm / sigma_y of the film at depth level k into out (0 below the film)
  void ratio_level(int k, double* out);

  Grid grid_;
  bool active_ = false;
  double friction_ = 0.0;
  double film_ = 0.0;           // film thickness; 0 = homogeneous [m]
  double film_yield_ = 0.0;     // [Pa]
  double dz_ = 0.0;             // level spacing; a level falls on the film's underside [m]
  int nz_ = 0;                  // levels: the film's and one below it [-]
  int refine_ = 1;              // [-]
  std::unique_ptr<LayeredSubsurfaceStress> layered_;
  std::vector<double> levels_;  // nz_ x grid cells of ratios
  int computed_ = 0;            // levels computed in the last call [-]
};

}  // namespace kneesim::particles
