// Output of one simulated gait cycle: kinematics table, summary figures, pressure maps.
// Shared by the gait run, the wear run and the studies, which all report the kinematics of a
// cycle.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "engine/io/table.h"
#include "engine/simulate.h"
#include "models/build_model.h"
#include "wear/wear_accumulator.h"

namespace kneesim::run {

// one row per frame; every column carries its unit
io::Table make_kinematics_table(const std::vector<engine::Frame>& frames);

struct CycleFigures {
  double ap_rom_mm = 0.0, ie_rom_deg = 0.0;  // max - min over the cycle [mm], [deg]
  double peak_pressure_MPa = 0.0;           // max over the cycle
  double mean_peak_pressure_MPa = 0.0;      // mean over the frames in contact
  double peak_contact_force_N = 0.0;
  double peak_axial_load_N = 0.0;           // applied
  double contact_force_at_peak_load_N = 0.0;  // contact force (axial part) at that frame
  double medial_fraction_stance = 0.0;      // medial / (medial + lateral), mean over 0-60 %
  double mean_contact_area_mm2 = 0.0;       // elements (nodes) with p > 0, mean in contact
  double mean_contact_line_area_mm2 = 0.0;  // inside the contact line, mean in contact
};
CycleFigures calc_cycle_figures(const std::vector<engine::Frame>& frames);

// summary fields common to every command that simulates cycles
nlohmann::json describe_model(const models::BuiltModel& built, const models::Config& config);
nlohmann::json describe_figures(const CycleFigures& f);

// insert surface with per-element pressure [Pa] as a .vtp file (pressure_MPa cell array)
void write_pressure_map(const std::filesystem::path& path, const engine::InsertSurface& insert,
                        const std::vector<double>& pressure_Pa);

// the I/O unit of the wear potential (what the law multiplies by its coefficient): N mm for the
// k laws (k [mm^3/(N mm)] x potential = volume [mm^3]), mm^3 for contact_area (C [-] x
// potential = volume); outputs name it wear_potential_<suffix>
struct WearPotentialUnit {
  std::string suffix;  // "Nmm" or "mm3"
  double per_si;       // I/O value per SI value (J -> N mm: 1e3; m^3 -> mm^3: 1e9)
  std::string text;    // "N mm" or "mm³", for tables
};
WearPotentialUnit wear_potential_unit(const std::string& law);

// the wear law of a config as summary.json reports it: wear_law, wear_law_params (the law's
// parameters by their [wear] names, I/O units), creep and its parameters
nlohmann::json describe_wear_law(const models::Config& config);

// the wear-rate map of a simulated cycle: per element the law's depth rate (wear_rate_mm_per_Mc),
// the cross-shear ratio and the wear potential per cycle, over the rigid insert's surface
void write_wear_rate_map(const std::filesystem::path& path, const engine::InsertSurface& insert,
                         const wear::WearAccumulator& acc);

// the cycle's wear figures for summary.json: the law (wear_law, wear_law_params), the volume
// rate it implies on the unworn insert (cycle_wear_rate_mm3_per_Mc), its peak depth rate and
// the work-weighted mean cross-shear ratio
nlohmann::json describe_wear_rate(const engine::Model& model, const wear::WearAccumulator& acc,
                                  const models::Config& config);

}  // namespace kneesim::run
