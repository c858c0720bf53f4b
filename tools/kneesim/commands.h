// Each `kneesim` sub-command lives in its own file and registers itself on the CLI11 app.
// A command's callback returns through CLI11; errors reach main() as exceptions, where an
// InputError becomes one sentence on stderr and exit code 2.
#pragma once

#include <CLI/CLI.hpp>

namespace kneesim::cli {

void add_run_command(CLI::App& app);
void add_particles_command(CLI::App& app);
void add_wear_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_bor_command(CLI::App& app);
void add_diagnose_command(CLI::App& app);

}  // namespace kneesim::cli
