// Where the gait cycle's contact occurs on the insert, and how wide its patches are, for a
// deformable insert mesh refined there ([deformable] refine = "contact"; models/hex_mesh.h
// make_refined_lines).
//
// Both are found with the rigid insert: one gait cycle of the Model as built (the elastic
// foundation, a fraction of a second against the minutes of a deformable cycle). The zone is
// every articular element that carries pressure in a loaded frame (contact force at least a
// quarter of the cycle's peak: stance, not the swing's light contact), grown by a margin. The
// patch widths are the pressure-weighted second moments of each condyle's patch along x (AP)
// and z (ML) in each loaded frame, w = 2 sqrt(5) sigma (the full width of a Hertz patch,
// p ~ sqrt(1 - r^2/a^2) has sigma^2 = a^2/5), and the refined spacing per direction is a
// fraction of the narrowest patches (a low percentile over the loaded frames): a stiff insert
// (a narrow patch) gets a finer mesh than a soft one, and a line contact (the DM implant's
// flat condyles: narrow in AP, long in ML) a finer one across the line than along it.
//
// The rigid run uses the law as specified (the material's K) whatever law the config names, so
// the deformable mesh does not depend on the rigid contact law. That law touches a smaller area
// than the deformable insert (docs/deformable.md: 83 against 136 mm^2 for UHMWPE), which the
// margin covers and which errs towards a finer mesh; a deformable run reports the share of its
// contact impulse outside the refined zone (summary.json `contact_outside_refined_zone`), so an
// insufficient margin shows. Rejected: refining the whole articular surface (2-3 times the
// elements for no gain: the dishes' ends never touch under a gait load) and remeshing during
// the cycle (the wear update needs one structured column mesh throughout).
#pragma once

#include <vector>

#include "engine/model.h"
#include "models/hex_mesh.h"

namespace kneesim::models {

struct ContactFootprint {
  std::vector<Interval> x;  // AP intervals touched, merged, with the margin [m], T frame
  std::vector<Interval> z;  // ML intervals (one per condyle unless they merge) [m], T frame
  int elements_touched = 0; // articular elements with pressure in some loaded frame
  // patch full widths along x and z of each condyle in each loaded frame [m]
  std::vector<double> width_x, width_z;
  double layer_thickness = 0.0;  // median elastic layer thickness under the touched elements [m]
};

// the intervals grown by `margin` on both sides, merged where they overlap or touch
std::vector<Interval> merge_intervals(std::vector<Interval> intervals, double margin);

// the pressure-weighted second moment widths 2 sqrt(5) sigma of a patch along x and z
// (pressures p at points (x, z)); {0, 0} for no pressure
std::pair<double, double> calc_patch_widths(const std::vector<double>& x,
                                            const std::vector<double>& z,
                                            const std::vector<double>& p);

// the value below which a fraction q of the values lie (nearest rank); 0 for none
double find_percentile(std::vector<double> values, double q);

// the footprint of one gait cycle of `rigid` (a Model with the elastic-foundation insert),
// the contact law's modulus set to `foundation_modulus` [Pa] for the run; std::runtime_error
// when the run fails or nothing touches
ContactFootprint find_contact_footprint(const engine::Model& rigid, double foundation_modulus,
                                        double dt_safety, double margin);

}  // namespace kneesim::models
