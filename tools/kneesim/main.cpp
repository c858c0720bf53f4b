// The `kneesim` program: sub-commands run, wear, compare, study, diagnose, bor, particles.
#include <cstdio>
#include <exception>

#include "engine/errors.h"
#include "tools/kneesim/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "kneesim: explicit-dynamics knee wear simulator (force-controlled ISO 14243-style rig).\n"
      "Every command runs on a built-in default implant when given no config.\n"
      "Units in files and options are in their names (ap_mm, pressure_MPa)."};
  app.require_subcommand(1);
  app.failure_message(
      [](const CLI::App*, const CLI::Error& e) { return "error: " + std::string(e.what()) + "\n"; });
  app.set_version_flag("--version", "kneesim 0.1.0");
  kneesim::cli::add_run_command(app);
  kneesim::cli::add_particles_command(app);
  kneesim::cli::add_wear_command(app);
  kneesim::cli::add_compare_command(app);
  kneesim::cli::add_bor_command(app);
  kneesim::cli::add_diagnose_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const kneesim::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
