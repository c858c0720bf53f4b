#include "engine/io/plot.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace kneesim::io {
namespace {

std::string plots_dir() {
  if (const char* env = std::getenv("KNEESIM_PLOTS_DIR")) return env;
  return KNEESIM_PLOTS_DIR;
}

}  // namespace

bool run_plot(const std::string& script, const std::vector<std::string>& args) {
  const std::string python = "/usr/bin/python3";
  const std::string path = plots_dir() + "/" + script;
  if (!std::filesystem::exists(python)) {
    std::fprintf(stderr, "warning: %s not found, skipped plot %s\n", python.c_str(),
                 script.c_str());
    return false;
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setenv("MPLBACKEND", "Agg", 1);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(python.c_str()));
    argv.push_back(const_cast<char*>(path.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(python.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  if (pid < 0 || ::waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) ||
      WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "warning: plot script %s failed; the CSV and JSON results are complete\n",
                 script.c_str());
    return false;
  }
  return true;
}

}  // namespace kneesim::io
