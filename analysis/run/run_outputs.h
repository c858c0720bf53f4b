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
  double mean_contact_area_mm2 = 0.0;
};
CycleFigures calc_cycle_figures(const std::vector<engine::Frame>& frames);

// summary fields common to every command that simulates cycles
nlohmann::json describe_model(const models::BuiltModel& built, const models::Config& config);
nlohmann::json describe_figures(const CycleFigures& f);

// insert surface with per-element pressure [Pa] as a .vtp file (pressure_MPa cell array)
void write_pressure_map(const std::filesystem::path& path, const engine::InsertSurface& insert,
                        const std::vector<double>& pressure_Pa);

}  // namespace kneesim::run
