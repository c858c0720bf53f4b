// Forward runs of the block-on-ring model: worn volume, scar depth, contact width and mean
// pressure at a list of cycle counts for one load and one wear law.
//
// Two paths compute the same thing. simulate_bor solves the three-equation contact with KINSOL
// at every requested cycle count, and integrates the geometry-dependent pressure law with
// CVODE (its right-hand side solves the contact at the current volume): the reference used by
// `kneesim bor`. simulate_bor_table interpolates a BorContactTable and integrates the pressure
// law as a quadrature N(V) = int dV / (k F S (p(V)/p_ref)^-alpha), which is exact for an
// autonomous rate and thousands of times faster: the diagnosis calls it inside its fits. A
// test holds the two paths together.
#pragma once

#include <vector>

#include "wear/bor/bor_contact.h"
#include "wear/bor/bor_rig.h"
#include "wear/bor/bor_wear_law.h"

namespace kneesim::bor {

struct BorRow {
  double cycles = 0.0;          // N [cycles]
  double volume = 0.0;          // worn volume [m^3]
  double depth = 0.0;           // scar depth plus creep penetration [m]
  double contact_width = 0.0;   // [m]
  double mean_pressure = 0.0;   // [Pa]
  double theta = 0.0;           // contact half-angle [rad]
  double theta_scar = 0.0;      // scar half-angle [rad]
  double scar_radius = 0.0;     // R_w [m]; 0 when unworn (infinite radius)
};

// reference path (KINSOL per row, CVODE for the pressure law); `cycles` ascending, >= 0
std::vector<BorRow> simulate_bor(const BorRig& rig, double load, BorWearLaw law,
                                 const BorWearParams& params, const std::vector<double>& cycles);

// fast path on a table built for the same rig and load; volume and depth only are exact to
// the table's interpolation (relative 1e-5); `cycles` in any order, >= 0
std::vector<BorRow> simulate_bor_table(BorContactTable& table, const BorRig& rig,
                                       BorWearLaw law, const BorWearParams& params,
                                       const std::vector<double>& cycles);

}  // namespace kneesim::bor
