// The block-on-ring wear rig of Hussin 2024 (physics.md section 7): a rigid steel ring turning
// against a UHMWPE block under a dead load. The block is an elastic-foundation plate (Winkler
// layer of thickness h), the ring a rigid cylinder. Defaults are the paper's rig; every field
// can be overridden from the command line.
#pragma once

#include <string>

namespace kneesim::bor {

struct BorRig {
  double ring_radius = 17.5e-3;     // R_c, ring diameter 35 mm [m]
  double ring_width = 10.0e-3;      // w, ring width = contact length along the ring axis [m]
  double block_height = 12.0e-3;    // h, foundation thickness (block 12 x 12 x 18 mm) [m]
  double block_width = 12.0e-3;     // block width across the ring axis; must hold the ring [m]
  double block_length = 18.0e-3;    // block length along the sliding direction [m]
  double youngs_modulus = 690.0e6;  // E of the UHMWPE block [Pa]
  double poisson_ratio = 0.317;     // nu of the UHMWPE block [-]
  double friction = 0.19;           // mu, steel ring on UHMWPE [-]
  double speed_rpm = 1000.0;        // ring speed [rev/min]
};

// foundation constant C = (1 - nu) E / ((1 + nu)(1 - 2 nu) h) [Pa/m]; 81.5 MPa/mm by default
double foundation_constant(const BorRig& rig);

// sliding distance per ring revolution S = 2 pi R_c [m]
double sliding_distance_per_cycle(const BorRig& rig);

// seconds of test time per cycle [s]
double seconds_per_cycle(const BorRig& rig);

// Sarkar's multidirectional-stress factor sqrt(1 + 3 mu^2) [-] (1.053 for mu = 0.19). The BOR
// wear factor k_D is calibrated on measured volume, so it already contains this factor; it is
// reported, not applied again.
double sarkar_factor(double friction);

// throws InputError naming `source` and the field when a value is outside its physical range
void check_rig(const BorRig& rig, const std::string& source);

}  // namespace kneesim::bor
