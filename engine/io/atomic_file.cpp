#include "engine/io/atomic_file.h"

#include "engine/io/interrupt.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace kneesim::io {

void write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  namespace fs = std::filesystem;
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  // the temporary name carries the pid so concurrent writers never share one
  const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  // an interrupted or failed command removes the temporary file (engine/io/interrupt.h)
  const int slot = register_temp(tmp);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    unregister_temp(slot);
    throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
  }
  auto fail = [&](const std::string& why) {
    ::close(fd);
    ::unlink(tmp.c_str());
    unregister_temp(slot);
    throw std::runtime_error("cannot write " + path.string() + ": " + why);
  };
  const char* data = content.data();
  size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(std::strerror(errno));
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  // a full disk may show only here (delayed allocation, network file systems)
  if (::fsync(fd) != 0 && errno != EINVAL) fail(std::strerror(errno));
  if (::close(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    unregister_temp(slot);
    throw std::runtime_error("cannot write " + path.string() + ": " + why);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    unregister_temp(slot);
    throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " +
                             why);
  }
  unregister_temp(slot);
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace kneesim::io
