// The `kneesim` program: sub-commands run, wear, compare, study, diagnose, bor, particles,
// calibrate-contact, check-contact, config, implant.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "analysis/report/provenance.h"
#include "engine/errors.h"
#include "engine/io/interrupt.h"
#include "tools/kneesim/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "kneesim: explicit-dynamics knee wear simulator (force-controlled ISO 14243-style rig).\n"
      "Every command runs on a built-in default implant when given no config.\n"
      "Units in files and options are in their names (ap_mm, pressure_MPa)."};
  app.require_subcommand(1);
  app.failure_message(
      [](const CLI::App*, const CLI::Error& e) { return "error: " + std::string(e.what()) + "\n"; });
  app.set_version_flag("--version", kneesim::report::kVersion);
  kneesim::report::set_command_line(argc, argv);
  // SIGINT / SIGTERM: tables in progress renamed *.partial.*, exit 130 / 143
  kneesim::io::install_interrupt_handlers();
  kneesim::cli::add_run_command(app);
  kneesim::cli::add_particles_command(app);
  kneesim::cli::add_wear_command(app);
  kneesim::cli::add_compare_command(app);
  kneesim::cli::add_bor_command(app);
  kneesim::cli::add_diagnose_command(app);
  kneesim::cli::add_study_command(app);
  kneesim::cli::add_calibrate_command(app);
  kneesim::cli::add_check_contact_command(app);
  kneesim::cli::add_config_command(app);
  kneesim::cli::add_implant_command(app);
  // an unknown first word is a mistyped command, not a missing one (CLI11 would say "A
  // subcommand is required")
  std::string names;
  bool known = false;
  for (const CLI::App* sub : app.get_subcommands({})) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
    known = known || (argc > 1 && sub->check_name(argv[1]));
  }
  if (argc > 1 && argv[1][0] != '-' && !known) {
    std::fprintf(stderr, "error: '%s' is not a kneesim command; the commands are %s (see "
                 "kneesim --help).\n", argv[1], names.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0 through CLI11; every other parse error is bad input (2),
    // not CLI11's own codes (104-114)
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const kneesim::InputError& e) {
    kneesim::io::abandon_outputs();
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // a file operation that failed mid-run (disk full, folder removed): one sentence, not the
    // library's "filesystem error: ..." text
    kneesim::io::abandon_outputs();
    std::fprintf(stderr, "error: could not write or read '%s' (%s).\n", e.path1().c_str(),
                 e.code().message().c_str());
    return 1;
  } catch (const std::exception& e) {
    kneesim::io::abandon_outputs();
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
