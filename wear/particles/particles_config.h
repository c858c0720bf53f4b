// The particle model's TOML configuration: a pair preset (pair = "steel-steel", ...) with any
// of its inputs overridden. Keys carry their units:
//
//   pair = "steel-steel"          load_N = 10   friction = 0.16
//   contact_pressure_MPa          knee pairs only: the Hertz peak the cylinder is sized to
//                                 (default: a kneesim contact run of the insert material)
//   cylinder_radius_mm = 2        cylinder_length_mm = 6
//   [grid]  nx ny dx_nm nz dz_nm refine
//   [run]   min_iterations max_iterations block (0 = automatic, in passes of the track)
//           slide_cells track_factor steady_tolerance
//   [harder] / [softer]  E_GPa nu hardness_GPa yield_GPa rq_nm skewness kurtosis
//            correlation_length_nm peklenik_gamma lambda_s_nm seed film_thickness_nm film_E_GPa
//            film_nu surface_csv  (peklenik_gamma: lay ratio, correlation length along x / across)
//
// The file is read through the toml++ adapter (engine/io/toml_file.h); unknown keys are errors.
#pragma once

#include <filesystem>
#include <functional>

#include "wear/particles/pairs.h"

namespace kneesim::particles {

// a knee pair's contact pressure [Pa] and the sentence saying where it comes from
struct KneeContactPressure {
  double pressure = 0.0;
  std::string source;
};
using KneeContactPressureFn = std::function<KneeContactPressure(PairName)>;

// throws InputError naming the file, key and value for unreadable files, unknown pairs or
// values out of range. A knee pair's contact pressure is the file's contact_pressure_MPa, or
// else `knee_pressure(pair)`.
ParticleModelConfig read_particle_config(const std::filesystem::path& path,
                                         const KneeContactPressureFn& knee_pressure = {});

}  // namespace kneesim::particles
