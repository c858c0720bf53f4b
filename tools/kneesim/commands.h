// Each `kneesim` sub-command lives in its own file and registers itself on the CLI11 app.
// A command's callback returns through CLI11; errors reach main() as exceptions, where an
// InputError becomes one sentence on stderr and exit code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace kneesim::cli {

// an option's value must be a finite number in [lo, hi] (CLI::Range lets nan through and
// prints its bounds with all their digits); CLI11 prefixes the option's name to the message
inline CLI::Validator finite_range(double lo, double hi) {
  char range[80];
  std::snprintf(range, sizeof range, "%.12g to %.12g", lo, hi);
  const std::string allowed = range;
  return CLI::Validator(
      [lo, hi, allowed](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) {
          return "value '" + text + "' is not a number in the allowed range " + allowed;
        }
        return std::string();
      },
      "[" + allowed + "]");
}

// an option's value must be a whole number in [lo, hi], written as digits: "1e3" and "2.5"
// are refused naming the range (CLI11 would say only "Could not convert"), with the digits
// to write when the value is whole
inline CLI::Validator whole_range(double lo, double hi) {
  char range[80];
  std::snprintf(range, sizeof range, "%.0f to %.0f", lo, hi);
  const std::string allowed = range;
  return CLI::Validator(
      [lo, hi, allowed](std::string& text) -> std::string {
        const size_t first = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
        const bool digits = text.size() > first &&
                            text.find_first_not_of("0123456789", first) == std::string::npos;
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool number = end != text.c_str() && *end == '\0' && std::isfinite(v);
        if (digits) {
          if (v >= lo && v <= hi) return std::string();
          return "value '" + text + "' is not in the allowed range " + allowed;
        }
        std::string hint;
        if (number && v == std::floor(v) && std::abs(v) < 1e15) {
          char buf[64];
          std::snprintf(buf, sizeof buf, " (write %.0f)", v);
          hint = buf;
        }
        return "value '" + text + "' is not a whole number" + hint + "; allowed: a whole number " +
               allowed;
      },
      "[" + allowed + "]");
}

// an option's value must be a finite number; the range `allowed` (e.g. "(0, 10000] N") is
// checked by the command, which names it in its own message; a text that is no number is
// refused here with that range (CLI11 would say only "Could not convert")
inline CLI::Validator finite_number(const std::string& allowed) {
  return CLI::Validator(
      [allowed](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v)) {
          return "value '" + text + "' is not a finite number; allowed: " + allowed;
        }
        return std::string();
      },
      allowed);
}

// the largest seed every option takes: 2^53 - 1, exact in a double as in the seed's integer
inline constexpr double kMaxSeed = 9007199254740991.0;

// --wear-law NAME and --law-param name=value (repeatable, comma-separated): shorthands for
// --set wear.law=NAME and --set wear.<name>=value (wear/wear_law.h wear_law_overrides)
inline void add_wear_law_options(CLI::App* cmd, std::string& law,
                                 std::vector<std::string>& params) {
  cmd->add_option("--wear-law", law,
                  "wear law, shorthand for --set wear.law=NAME: archard (k p ds), "
                  "pressure_dependent_wear (k (p / p_ref)^-alpha p ds), material_pressure "
                  "(k (p / p_ref)^n p ds with the material's own n and p_ref), cross_shear "
                  "(k (1 + g CS) (p / p_ref)^-alpha p ds), contact_area (C (1 + g CS) ds in "
                  "contact), running_in, incubation (docs/theory.md, wear laws)");
  cmd->add_option("--law-param", params,
                  "wear-law parameter name=value, shorthand for --set wear.<name>=value: "
                  "cross_shear_gain (beta), pressure_exponent (alpha), reference_pressure_MPa "
                  "(p_ref_MPa), running_in_excess, running_in_cycles, incubation_cycles; "
                  "creep_ratio, creep_time_s with --set wear.creep=true")
      ->delimiter(',');
}

// --no-calibrate on every command that simulates: the rigid insert's contact law as specified
// instead of the calibrated one (models/contact_law_library.h)
inline void add_no_calibrate_flag(CLI::App* cmd, bool& flag) {
  cmd->add_flag("--no-calibrate", flag,
                "rigid insert: the elastic-foundation law as specified, K = (1-nu)E/((1+nu)(1-2nu)), "
                "instead of the law calibrated against the deformable insert (no calibration on "
                "first use; a warning says how far such pressures run)");
}

// the --set list with contact.calibration = "off" when --no-calibrate was given
inline std::vector<std::string> with_no_calibrate(std::vector<std::string> sets, bool no_calibrate) {
  if (no_calibrate) sets.push_back("contact.calibration=\"off\"");
  return sets;
}

// the --set list of a command whose deformable insert is the contact calibration's reference
// mesh (models::kContactCalibrationReferenceMesh): each of its keys that the config file does
// not set, before `sets` (so the file's [deformable] keys and --set deformable.* change it),
// then the --material and --element-mm shorthands (calibrate-contact, check-contact)
std::vector<std::string> with_reference_mesh(const std::string& config,
                                             const std::vector<std::string>& sets,
                                             const std::string& material, double element_mm);

void add_run_command(CLI::App& app);
void add_particles_command(CLI::App& app);
void add_wear_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_bor_command(CLI::App& app);
void add_diagnose_command(CLI::App& app);
void add_study_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_check_contact_command(CLI::App& app);
void add_config_command(CLI::App& app);
void add_implant_command(CLI::App& app);

}  // namespace kneesim::cli
