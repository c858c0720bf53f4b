// Building the deformable solid: reference geometry of every element, lumped mass, the
// element stable step and optional mass scaling (physics.md section 5).
//
// Stable step: dt_e = L_e / c_e with L_e = V_e / (largest face area) and the dilatational
// wave speed c_e = sqrt((lambda + 2 mu) / rho_e), the usual explicit-code estimate; for a
// regular cube it is h / c, the exact limit inside a regular lumped-mass mesh of uniform-
// gradient elements. Free surfaces raise the highest frequency above it (a free block of
// cubes, power iteration: 6 % at nu 0.3, 17 % at nu 0.47; tests/engine/
// solid_dynamics_test.cpp), so the step used is this estimate times a safety factor of 0.8
// or less. The physical hourglass stiffness does not raise it (its highest mode has
// omega^2 <= 4 E / (rho h^2) against 4 (lambda + 2 mu) / (rho h^2)).
//
// Mass scaling: with a target step dt_target, an element whose dt_e is smaller gets its
// density raised by (dt_target / dt_e)^2 so that its dt_e equals the target; the added mass
// is reported (and the owner reports the kinetic/internal energy ratio of the run, which must
// stay small for the result to be quasi-static).
#pragma once

#include <string>
#include <vector>

#include "engine/errors.h"
#include "engine/solid/solid.h"

namespace kneesim::engine::solid {

struct SolidOptions {
  double mass_scaling_dt = 0.0;  // target stable step [s]; 0: no mass scaling
  double damping_alpha = 0.0;    // mass-proportional damping [1/s]
  int threads = 1;               // threads of the step's loops (0: automatic, work_team.h)
};

// checks the material: E > 0, 0 <= nu < 0.5, rho > 0, yield >= 0, H >= 0
void check_solid_material(const SolidMaterial& material);

// the Model part of a hex8 mesh; throws InputError (one sentence naming the element or the
// field, the value and the allowed range) for a material out of range or an
// element inverted or degenerate in its reference configuration
SolidModel make_solid_model(std::vector<Eigen::Vector3d> nodes,
                            std::vector<std::array<int, kHexNodes>> elements,
                            const SolidMaterial& material, const SolidOptions& options,
                            std::vector<uint8_t> constraint = {});

// cuts the step's loops into `ranges` ranges (at most one per batch; solid.h). The model is
// built with one per thread, fewer for a small mesh (64 batches or more each); the results do
// not depend on it, which the tests check by cutting small meshes into many
void cut_solid_ranges(SolidModel& model, int ranges);

// stable step of one element for the given density [s]
double calc_element_stable_step(const Hex8Reference& ref, const SolidMaterial& material,
                                double density);

// the state at rest in the reference configuration
SolidState make_solid_state(const SolidModel& model);

// scratch sized for the model
SolidData make_solid_data(const SolidModel& model);

}  // namespace kneesim::engine::solid
