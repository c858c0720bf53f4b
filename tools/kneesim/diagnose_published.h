// `kneesim diagnose published-wear` (tools/kneesim/diagnose_published.cpp)
#pragma once

#include <CLI/CLI.hpp>

namespace kneesim::cli {

void add_diagnose_published_wear(CLI::App* diagnose);

}  // namespace kneesim::cli
