// Where the source tree is: the shipped data files (materials library, default waveforms,
// example configs) and the plot scripts are read from it at run time. Only source_tree.cpp is
// compiled with the path, so that every other object file is the same for any checkout (a
// compiler cache shares them between work trees).
#pragma once

#include <filesystem>

namespace kneesim::io {

// the kneesim source tree the program was built from
std::filesystem::path source_dir();

// the plot scripts: $KNEESIM_PLOTS_DIR when set, else source_dir()/tools/plots
std::filesystem::path plots_dir();

}  // namespace kneesim::io
