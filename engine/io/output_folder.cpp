#include "engine/io/output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <mutex>
#include <sstream>
#include <system_error>
#include <vector>

#include "engine/errors.h"
#include "engine/io/interrupt.h"

namespace kneesim::io {
namespace {

namespace fs = std::filesystem;

// the process's arguments, from /proc/self/cmdline (empty where there is none)
std::vector<std::string> process_arguments() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::vector<std::string> args;
  std::string a;
  while (std::getline(in, a, '\0')) args.push_back(a);
  return args;
}

// the command words: "wear", "diagnose bor", "implant check"
std::string command_words() {
  const std::vector<std::string> args = process_arguments();
  if (args.size() < 2) return "";
  std::string words = args[1];
  if ((args[1] == "diagnose" || args[1] == "implant") && args.size() > 2) words += " " + args[2];
  return words;
}

// an MPI rank other than 0 shares rank 0's folder and does not claim it
bool is_secondary_rank() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    if (const char* r = std::getenv(v); r != nullptr && std::string(r) != "0") return true;
  }
  return false;
}

// a temporary file of an atomic write (engine/io/atomic_file.cpp: NAME.tmp.PID), of a mesh
// (NAME.tmpDIGITS) or of a plot (NAME.tmp.png)
bool is_temporary_name(const std::string& name) {
  const size_t t = name.rfind(".tmp");
  if (t == std::string::npos || t == 0) return false;
  const std::string tail = name.substr(t + 4);
  if (tail == ".png") return true;
  const std::string digits = !tail.empty() && tail[0] == '.' ? tail.substr(1) : tail;
  return !digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos;
}

constexpr const char* kLockName = ".kneesim.lock";
constexpr const char* kCommandName = ".kneesim-command";

struct HeldLock {
  std::string folder;  // canonical
  fs::path file;
  int fd = -1;
  int slot = -1;
  bool created = false;  // this process created the folder (check_output_folder)
};

// a folder this process created that holds nothing but the command marker: the command was
// refused or failed before writing anything, so no empty result folder is left behind
void remove_if_unused(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().filename() != kCommandName) return;
  }
  if (ec) return;
  fs::remove(dir / kCommandName, ec);
  fs::remove(dir, ec);
}

struct LockRegistry {
  std::mutex mutex;
  std::vector<HeldLock> held;
  ~LockRegistry() {
    // a command that returns normally releases its folders
    for (const HeldLock& h : held) {
      unregister_lock(h.slot);
      ::unlink(h.file.c_str());
      ::close(h.fd);
      if (h.created) remove_if_unused(h.file.parent_path());
    }
  }
};
LockRegistry g_locks;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string first_line(const std::string& text) {
  const size_t n = text.find('\n');
  return n == std::string::npos ? text : text.substr(0, n);
}


// the lock file of `dir` held by this process (flock: released by the kernel when a process
// dies, so a lock file left by a killed process is free and taken over)
void claim_folder(const fs::path& dir, const std::string& name, bool created) {
  if (is_secondary_rank()) return;
  std::error_code ec;
  const std::string canonical = fs::weakly_canonical(dir, ec).string();
  std::lock_guard<std::mutex> guard(g_locks.mutex);
  for (const HeldLock& h : g_locks.held) {
    if (h.folder == canonical) return;
  }
  const fs::path lock = dir / kLockName;
  int fd = -1;
  std::string stale;
  for (int attempt = 0; attempt < 10 && fd < 0; ++attempt) {
    fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      throw InputError(name + " is not writable (" + std::strerror(errno) + "); give a folder "
                       "you can write to.");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const std::string holder = first_line(read_text(lock));
      ::close(fd);
      throw InputError(name + " is in use by another kneesim process (" +
                       (holder.empty() ? std::string("lock file ") + kLockName : holder) +
                       "); wait for it to finish or give another folder.");
    }
    // the holder may have removed the file between our open and flock: lock the one in place
    struct stat by_fd {}, by_path {};
    if (::fstat(fd, &by_fd) != 0 || ::stat(lock.c_str(), &by_path) != 0 ||
        by_fd.st_ino != by_path.st_ino || by_fd.st_dev != by_path.st_dev) {
      ::close(fd);
      fd = -1;
      continue;
    }
    stale = first_line(read_text(lock));
  }
  if (fd < 0) throw InputError(name + ": its lock file keeps changing; give another folder.");

  // results of another command are not mixed with this one's
  const std::string words = command_words();
  const std::string previous = first_line(read_text(dir / kCommandName));
  if (!previous.empty() && !words.empty() && previous != words) {
    std::string example;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string n = e.path().filename().string();
      if (!n.empty() && n[0] != '.' && !is_temporary_name(n)) {
        example = n;
        break;
      }
    }
    if (!example.empty()) {
      ::unlink(lock.c_str());
      ::close(fd);
      throw InputError(name + " holds the results of 'kneesim " + previous + "' (e.g. '" +
                       example + "'); give another folder, or empty this one to use it for "
                       "'kneesim " + words + "'.");
    }
  }
  // a lock file left by a process that no longer runs (killed): taken over silently, its
  // text replaced below (stderr keeps one sentence per outcome)
  (void)stale;
  char when[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  const std::string text = "pid " + std::to_string(::getpid()) + ": kneesim " + words +
                           ", since " + when + "\n";
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) < 0) {
    ::close(fd);
    throw InputError(name + " is not writable (" + std::strerror(errno) + "); give a folder "
                     "you can write to.");
  }
  if (!words.empty() && previous != words) {
    std::ofstream(dir / kCommandName, std::ios::trunc) << words << "\n";
  }
  // files a killed run of this folder left in the middle of an atomic write
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file(ec) && is_temporary_name(e.path().filename().string())) {
      fs::remove(e.path(), ec);
    }
  }
  g_locks.held.push_back({canonical, lock, fd, register_lock(lock), created});
}

}  // namespace

void check_output_folder(const std::filesystem::path& dir, const std::string& flag) {
  namespace fs = std::filesystem;
  const std::string name = flag + " '" + dir.string() + "'";
  if (dir.empty()) throw InputError(flag + " is empty; give a folder for the results.");
  std::error_code ec;
  const bool existed = fs::exists(dir, ec);
  if (existed && !fs::is_directory(dir, ec)) {
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
  claim_folder(dir, name, !existed);
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
