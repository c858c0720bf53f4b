// The configuration reference as a document: every key of the config registry
// (models/config.h config_reference()) with its type, default, allowed range and meaning,
// grouped by section. `kneesim config --reference` prints it; docs/config-reference.md is its
// output, and a test fails when the two differ, so the document follows the code.
#pragma once

#include <string>

namespace kneesim::models {

// the reference in Markdown
std::string config_reference_markdown();

}  // namespace kneesim::models
