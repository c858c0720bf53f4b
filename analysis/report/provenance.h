// What a report says about where its results come from: program version, the command line as
// typed, the config file's text and its --set overrides, and every input file with its SHA-256.
#pragma once

#include <string>
#include <vector>

#include "analysis/report/report_page.h"
#include "models/config.h"

namespace kneesim::report {

inline constexpr const char* kVersion = "kneesim 0.1.0";

// remembers the process's arguments (main() calls it once); quoted where a shell would need it
void set_command_line(int argc, const char* const* argv);
const std::string& command_line();

// the provenance of a command run on `config` (loaded from `config_path`, "" for the built-in
// defaults, with `sets` applied): config, meshes, gait, measured and contact-law files and the
// materials library, each with its hash; `extra` adds command-specific inputs (role, path)
Provenance make_provenance(const std::string& config_path, const std::vector<std::string>& sets,
                           const models::Config& config,
                           const std::vector<std::pair<std::string, std::string>>& extra = {});

}  // namespace kneesim::report
