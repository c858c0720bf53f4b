#include "analysis/report/command_reports.h"

#include <tuple>

#include "analysis/report/summary_report.h"

namespace kneesim::report {

void write_bor_report(const std::filesystem::path& out) {
  SummaryReport r;
  r.title = "kneesim bor: block-on-ring wear";
  r.subtitle = "A UHMWPE block on a CoCr ring: the numbers of summary.json and the curves of "
               "bor.csv.";
  for (const auto& [col, title, y] :
       {std::tuple<const char*, const char*, const char*>{"volume_mm3", "Volume loss",
                                                          "volume (mm\u00b3)"},
        {"depth_mm", "Wear depth", "depth (mm)"},
        {"contact_width_mm", "Contact width", "width (mm)"},
        {"mean_pressure_MPa", "Mean contact pressure", "pressure (MPa)"}}) {
    r.plots.push_back({"bor.csv", title, "cycles", "cycles (millions)", y, {{col, ""}}, true, 1e-6});
  }
  write_summary_report(out, r, make_command_provenance());
}

void write_particles_report(const std::filesystem::path& out) {
  SummaryReport r;
  r.title = "kneesim particles: wear particles of a sliding pair";
  r.subtitle = "The numbers of summary.json and the run-in of iterations.csv (one row per "
               "iteration); every particle is in particles.csv.";
  for (const auto& [col, title, y] :
       {std::tuple<const char*, const char*, const char*>{"particles", "Particles released",
                                                          "particles (count)"},
        {"mean_eq_radius_nm", "Mean equivalent radius", "radius (nm)"},
        {"max_pressure_MPa", "Maximum contact pressure", "pressure (MPa)"},
        {"track_rq_nm", "Track roughness Rq", "Rq (nm)"}}) {
    r.plots.push_back({"iterations.csv", title, "iteration", "iteration", y, {{col, ""}}, true, 1.0});
  }
  write_summary_report(out, r, make_command_provenance());
}

namespace {

// the pressure and area traces of a comparison.csv (calibrate-contact's and check-contact's)
std::vector<CsvPlot> pressure_comparison_plots(const char* law_label) {
  std::vector<CsvPlot> plots;
  for (const auto& [q, title, y] :
       {std::tuple<const char*, const char*, const char*>{"peak_MPa", "Peak contact pressure",
                                                          "pressure (MPa)"},
        {"mean_MPa", "Mean contact pressure", "pressure (MPa)"},
        {"area_mm2", "Contact area", "area (mm\u00b2)"}}) {
    const std::string col = q;
    plots.push_back({"comparison.csv", title, "gait_pct", "gait cycle (%)", y,
                     {{"deformable_" + col, "deformable"}, {"rigid_" + col, "rigid"},
                      {"calibrated_" + col, law_label}},
                     true, 1.0});
  }
  return plots;
}

}  // namespace

void write_calibrate_report(const std::filesystem::path& out, const std::string& material) {
  SummaryReport r;
  r.title = "kneesim calibrate-contact: " + material;
  r.subtitle = "The rigid insert's contact calibrated against the deformable insert: the "
               "numbers of summary.json and the pressure and area traces of comparison.csv.";
  r.plots = pressure_comparison_plots("calibrated");
  write_summary_report(out, r, make_command_provenance());
}

void write_check_contact_report(const std::filesystem::path& out, const std::string& material) {
  SummaryReport r;
  r.title = "kneesim check-contact: " + material;
  r.subtitle = "The rigid insert's contact law (the one every command uses; 'rigid' is the law "
               "as specified) against the deformable insert under the config's load case: the "
               "numbers of summary.json and the traces of comparison.csv.";
  r.plots = pressure_comparison_plots("law");
  write_summary_report(out, r, make_command_provenance());
}

void write_study_report(const std::filesystem::path& out, const std::string& method) {
  SummaryReport r;
  r.title = "kneesim study: " + method;
  r.subtitle = "The kinematic envelopes of the trials (1st, 50th, 99th percentile) beside the "
               "nominal run, and each input's correlation with each measure; every trial is in "
               "trials.csv.";
  r.plots = {{"envelopes.csv", "AP translation: envelope of the trials", "gait_pct",
              "gait cycle (%)", "AP, tibia anterior (mm)",
              {{"ap_mm_p01", "p01"}, {"ap_mm_p50", "p50"}, {"ap_mm_p99", "p99"},
               {"ap_mm_nominal", "nominal"}},
              false, 1.0},
             {"envelopes.csv", "IE rotation: envelope of the trials", "gait_pct",
              "gait cycle (%)", "IE, tibia internal (deg)",
              {{"ie_deg_p01", "p01"}, {"ie_deg_p50", "p50"}, {"ie_deg_p99", "p99"},
               {"ie_deg_nominal", "nominal"}},
              false, 1.0}};
  r.plots_note = "Joint coordinates (tibia relative to femur) over the gait cycle.";
  r.tables = {{"Sensitivity: |Pearson r| of each input with each measure", "sensitivity.csv"},
              {"Wear envelopes", "wear_envelopes.csv"}};
  r.table_rows = 60;
  write_summary_report(out, r, make_command_provenance());
}

void write_diagnosis_report(const std::filesystem::path& out, const std::string& kind) {
  SummaryReport r;
  r.title = "kneesim diagnose " + kind;
  r.subtitle = "The candidate effects fitted to the measured data: the numbers of "
               "diagnosis.json and the table of diagnosis.md.";
  r.summary_file = "diagnosis.json";
  r.texts = {{"Diagnosis", "diagnosis.md"}};
  write_summary_report(out, r, make_command_provenance());
}

}  // namespace kneesim::report
