#include "engine/io/output_folder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "engine/errors.h"

namespace kneesim::io {

void check_output_folder(const std::filesystem::path& dir, const std::string& flag) {
  namespace fs = std::filesystem;
  const std::string name = flag + " '" + dir.string() + "'";
  if (dir.empty()) throw InputError(flag + " is empty; give a folder for the results.");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw InputError(name + " is an existing file, not a folder; give a folder path (it is "
                     "created when missing).");
  }
  fs::create_directories(dir, ec);
  if (ec) {
    // name the part of the path that is in the way when it is a file
    for (fs::path p = dir.parent_path(); !p.empty(); p = p.parent_path()) {
      if (fs::exists(p) && !fs::is_directory(p)) {
        throw InputError(name + " cannot be created: '" + p.string() + "' is a file, not a "
                         "folder; give a folder path.");
      }
      if (p == p.root_path()) break;
    }
    throw InputError(name + " cannot be created (" + ec.message() + "); give a folder you can "
                     "write to.");
  }
  // a probe file: permission bits say nothing about read-only mounts or immutable folders
  const fs::path probe = dir / (".kneesim_write_test." + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    throw InputError(name + " is not writable (" + std::strerror(errno) + "); give a folder you "
                     "can write to.");
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

std::uintmax_t free_bytes(const std::filesystem::path& dir) {
  std::error_code ec;
  const std::filesystem::space_info s = std::filesystem::space(dir, ec);
  return ec ? UINTMAX_MAX : s.available;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 5) bytes /= 1000.0, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return buf;
}

}  // namespace kneesim::io
