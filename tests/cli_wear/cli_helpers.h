// Running the built `kneesim` program from the CLI tests: found in the build tree above the
// test binary (<build>/tools/kneesim), run to completion with std::system, or started in the
// background (fork/exec) so that a test can SIGKILL it at a chosen moment. Shared by
// tests/cli (kneesim run) and tests/cli_wear (wear, compare).
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/loads/temp_dir.h"  // TempDir

namespace kneesim::test {

namespace fs = std::filesystem;

// the kneesim executable: the nearest ancestor of this test binary holding tools/kneesim
inline fs::path find_kneesim() {
  const fs::path self = fs::read_symlink("/proc/self/exe");
  for (fs::path dir = self.parent_path(); !dir.empty() && dir != dir.root_path();
       dir = dir.parent_path()) {
    const fs::path candidate = dir / "tools" / "kneesim";
    if (fs::is_regular_file(candidate) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// byte equality, without doctest printing two whole files when they differ
inline bool same_bytes(const std::string& a, const std::string& b) { return a == b; }

inline int count_lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

// stderr without the one-line fallback warning of a config whose implant and material have no
// calibrated contact law (models/contact_law_library.h): tests that change the material to make
// a run fail check the failure's own line count on what remains
inline std::string without_contact_law_warning(const std::string& err) {
  std::istringstream in(err);
  std::string out, line;
  while (std::getline(in, line)) {
    if (line.rfind("warning: no calibrated contact law", 0) == 0) continue;
    out += line + "\n";
  }
  return out;
}

struct Result {
  int exit_code = -1;      // -1 when killed by a signal
  int signal = 0;          // the signal that ended it, 0 if it exited
  std::string out, err;    // captured stdout and stderr
  double seconds = 0.0;    // wall time
};

// starts kneesim with the arguments in the background, stdout and stderr into files of `dir`;
// own_group: in a process group of its own (as a shell job), so a signal can go to the group
inline pid_t start_kneesim(const std::vector<std::string>& args, const fs::path& dir,
                           const std::string& tag, bool own_group = false) {
  const fs::path exe = find_kneesim();
  if (exe.empty()) return -1;
  const std::string out = (dir / (tag + ".stdout")).string();
  const std::string err = (dir / (tag + ".stderr")).string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (own_group) ::setpgid(0, 0);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    ::dup2(e, 2);
    std::vector<std::string> all{exe.string()};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  if (own_group && pid > 0) ::setpgid(pid, pid);
  return pid;
}

inline Result wait_kneesim(pid_t pid, const fs::path& dir, const std::string& tag,
                           std::chrono::steady_clock::time_point t0) {
  Result r;
  int status = 0;
  ::waitpid(pid, &status, 0);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = slurp(dir / (tag + ".stdout"));
  r.err = slurp(dir / (tag + ".stderr"));
  return r;
}

// runs kneesim to completion
inline Result run_kneesim(const std::vector<std::string>& args, const fs::path& dir,
                          const std::string& tag = "run") {
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = start_kneesim(args, dir, tag);
  if (pid < 0) return {};
  return wait_kneesim(pid, dir, tag, t0);
}

// starts kneesim and SIGKILLs it as soon as `when()` is true (polled every millisecond);
// returns how it ended (signal == SIGKILL when the kill came first)
template <typename Predicate>
inline Result kill_when(const std::vector<std::string>& args, const fs::path& dir,
                        Predicate when, const std::string& tag) {
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = start_kneesim(args, dir, tag);
  if (pid < 0) return {};
  for (;;) {
    if (when()) {
      ::kill(pid, SIGKILL);
      break;
    }
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {  // finished before the trigger appeared
      Result r;
      r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      r.out = slurp(dir / (tag + ".stdout"));
      r.err = slurp(dir / (tag + ".stderr"));
      return r;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return wait_kneesim(pid, dir, tag, t0);
}

// SIGKILLs kneesim as soon as `trigger` exists
inline Result kill_when_exists(const std::vector<std::string>& args, const fs::path& dir,
                               const fs::path& trigger, const std::string& tag) {
  return kill_when(args, dir, [&trigger] { return fs::exists(trigger); }, tag);
}

// the coarse short run of the resume acceptance: by default 1 Mc, 4 updates, 2 mm
// elements, with `extra` arguments appended
inline std::vector<std::string> wear_args(const fs::path& out, std::vector<std::string> extra = {},
                                          const std::string& every = "250000",
                                          const std::string& cycles = "1000000") {
  std::vector<std::string> a = {"wear",  "--cycles", cycles, "--update-every", every,
                                "--set", "implant.edge_length_mm=2", "--quiet",
                                "--out", out.string()};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

inline std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, sep);) out.push_back(cell);
  return out;
}

}  // namespace kneesim::test
