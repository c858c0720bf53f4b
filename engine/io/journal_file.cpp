#include "engine/io/journal_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace kneesim::io {

void append_line_durable(const std::filesystem::path& path, std::string_view line) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) {
    throw std::runtime_error("cannot append to " + path.string() + ": " + std::strerror(errno));
  }
  // a short write (the disk filled up mid-line) is continued, so the next write names the
  // cause (ENOSPC); a torn last line is what a killed process leaves too, and the journal's
  // reader skips it
  size_t done = 0;
  std::string why;
  while (done < line.size()) {
    const ssize_t n = ::write(fd, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      why = n < 0 ? std::strerror(errno) : "nothing written";
      break;
    }
    done += static_cast<size_t>(n);
  }
  if (why.empty() && ::fsync(fd) != 0) why = std::strerror(errno);
  const bool ok = why.empty();
  ::close(fd);
  if (!ok) throw std::runtime_error("cannot append to " + path.string() + ": " + why);
}

}  // namespace kneesim::io
