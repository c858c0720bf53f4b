// Content hashes of input files for a report's provenance (OpenSSL's SHA-256, this file only).
#pragma once

#include <filesystem>
#include <string>

namespace kneesim::report {

// lower-case hex SHA-256 of the file's bytes; "" when it cannot be read
std::string sha256_file(const std::filesystem::path& path);

// of a string (tests: the FIPS 180-2 example "abc")
std::string sha256_text(const std::string& text);

}  // namespace kneesim::report
