// A fresh temporary folder per test case, removed at the end of the case.
#pragma once

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace kneesim::test {

struct TempDir {
  std::filesystem::path path;  // the folder
  TempDir() {
    std::random_device rd;
    path = std::filesystem::temp_directory_path() /
           ("kneesim_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  // writes a text file into the folder and returns its path
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    std::filesystem::path p = path / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
};

}  // namespace kneesim::test
