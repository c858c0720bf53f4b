// Shared by the fuzz harnesses: the readers under test take file paths (the extension picks the
// format), so each input is written to a per-process scratch file first. `first byte selects
// the variant` lets one harness cover several formats of one reader.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace kneesim::fuzz {

// writes data to <tmp>/kneesim_fuzz_<pid>/input<extension> and returns the path
inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size,
                                         const std::string& extension) {
  static const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("kneesim_fuzz_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / ("input" + extension);
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace kneesim::fuzz
